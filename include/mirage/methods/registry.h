// SPDX-License-Identifier: MIT
// The method registry: the scenario's `method: {name: ...}` names one of these entries, which
// carries the method's options descriptor (the one place its options, defaults, units and ranges
// are declared; it drives the scenario parser, validation, `mirage describe` and the docs) and
// its factory. The runner and the file formats know methods only through this table, so a new
// method adds its folder under methods/ and one entry in registry.cc.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "mirage/channel/link.h"
#include "mirage/core/options_descriptor.h"
#include "mirage/methods/estimator.h"
#include "mirage/methods/world.h"

namespace mirage::methods {

/// The kind of input a method consumes.
enum class MethodInput {
  kRangeSets,  ///< unlabeled ranges per anchor (from MPC extraction, a ranging system or a file)
  kLinkCirs,   ///< the CIR of every link the method names (methods that extract themselves)
  kToaStamps,  ///< arrival-time stamps per receiver (acoustic), several per emission, unlabeled
  kTdoa,       ///< pairwise differences of arrival distances (UWB TDOA), one pair per row
};

/// One registered method. Options travel type-erased (a pointer to the method's options struct,
/// which its descriptor describes); the functions below cast it back.
struct MethodInfo {
  std::string name;     ///< the scenario's method name
  std::string summary;  ///< one line: what it does
  std::string source;   ///< the paper and sections it implements
  MethodInput input = MethodInput::kRangeSets;
  /// One estimator tracks all walking agents together; otherwise one run per trajectory.
  bool joint = false;
  /// The estimator can start itself from the first epochs (Estimator::InitializeFromEpoch), so
  /// recorded data without truth need no start position.
  bool self_initializes = false;
  const core::OptionsDescriptorBase* descriptor = nullptr;
  /// A default-constructed options struct (the defaults: its member initialisers).
  std::function<std::shared_ptr<void>()> make_options;
  /// A new estimator for one run.
  std::function<std::unique_ptr<Estimator>(const void* options, const World& world)> create;
  /// The links a kLinkCirs method measures.
  std::function<std::vector<channel::LinkSpec>(const void* options, const World& world)> links;
  /// The start position's standard deviation the method assumes (m).
  std::function<double(const void* options)> start_sigma_m;
  /// What the options need of the world beyond their own ranges (e.g. an anchor for anchor
  /// links): problems "key: message", empty if none. Optional.
  std::function<std::vector<std::string>(const void* options, const World& world)> check;
};

/// Every registered method, in the order `mirage describe` lists them.
const std::vector<MethodInfo>& Methods();

/// The method of this name, or null.
const MethodInfo* FindMethod(std::string_view name);

/// The names of all methods, comma-separated, for messages.
std::string MethodNames();

}  // namespace mirage::methods
