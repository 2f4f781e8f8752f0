// SPDX-License-Identifier: MIT
#include "mirage/methods/registry.h"

#include "mirage/methods/acoustic/acoustic_estimator.h"
#include "mirage/methods/coop/coop_estimator.h"
#include "mirage/methods/mint/mint_estimator.h"
#include "mirage/methods/range_ekf/range_ekf.h"
#include "mirage/methods/slam/slam_estimator.h"
#include "mirage/methods/tdoa_ekf/tdoa_ekf.h"

namespace mirage::methods {
namespace {

// The type-safe parts of an entry for options struct Options and estimator Est.
template <typename Options, typename Est>
MethodInfo Entry(std::string name, std::string summary, std::string source, const core::OptionsDescriptor<Options>& descriptor) {
  MethodInfo info;
  info.name = std::move(name);
  info.summary = std::move(summary);
  info.source = std::move(source);
  info.descriptor = &descriptor;
  info.make_options = [] { return std::static_pointer_cast<void>(std::make_shared<Options>()); };
  info.create = [](const void* options, const World& world) -> std::unique_ptr<Estimator> {
    return std::make_unique<Est>(*static_cast<const Options*>(options), world);
  };
  return info;
}

std::vector<MethodInfo> BuiltIn() {
  std::vector<MethodInfo> out;
  {
    auto m = Entry<mint::MintOptions, mint::MintEstimator>(
        "mint", "multipath-assisted tracking with a known floor plan: ranges to virtual anchors in an EKF",
        "Lafer 2014 ch. 3", mint::MintOptionsDescriptor());
    m.start_sigma_m = [](const void* o) { return static_cast<const mint::MintOptions*>(o)->initial_position_sigma_m; };
    m.self_initializes = true;  // SearchFloorPlan, confirmed by the next epoch
    out.push_back(std::move(m));
  }
  {
    auto m = Entry<slam::SlamOptions, slam::SlamEstimator>(
        "slam", "multipath SLAM: virtual anchors in the EKF state, discovered from unexplained ranges",
        "Leitinger et al.; Lafer 2014 ch. 4", slam::SlamOptionsDescriptor());
    m.start_sigma_m = [](const void* o) { return static_cast<const slam::SlamOptions*>(o)->initial_position_sigma_m; };
    m.self_initializes = true;  // an anchor fix, else the floor-plan search
    out.push_back(std::move(m));
  }
  {
    auto m = Entry<coop::CoopOptions, coop::CoopEstimator>(
        "coop", "anchorless cooperative tracking of several agents with the floor plan's walls in the state",
        "Kulmer et al., Sec. III-IV", coop::CoopOptionsDescriptor());
    m.input = MethodInput::kLinkCirs;
    m.joint = true;
    m.links = [](const void* o, const World& world) { return coop::CoopLinks(*static_cast<const coop::CoopOptions*>(o), world); };
    m.start_sigma_m = [](const void* o) { return static_cast<const coop::CoopOptions*>(o)->agent_sigma_m; };
    m.check = [](const void* o, const World& world) -> std::vector<std::string> {
      if (static_cast<const coop::CoopOptions*>(o)->anchor_links && world.anchors.empty()) {
        return {"anchor_links: the anchor links need an anchor: list one under anchors"};
      }
      return {};
    };
    out.push_back(std::move(m));
  }
  {
    auto m = Entry<range_ekf::RangeEkfOptions, range_ekf::RangeEkf>(
        "range_ekf", "a 3-D range EKF (or planar at a known height) with a chi-square gate: the plain baseline",
        "textbook EKF with a constant-velocity model", range_ekf::RangeEkfOptionsDescriptor());
    m.start_sigma_m = [](const void* o) { return static_cast<const range_ekf::RangeEkfOptions*>(o)->initial_position_sigma_m; };
    m.self_initializes = true;
    out.push_back(std::move(m));
  }
  {
    auto m = Entry<acoustic::AcousticOptions, acoustic::AcousticEstimator>(
        "acoustic", "a sound sender among ceiling microphones: robust EKF (Hampel), EKF or NLLS on arrival-time stamps",
        "Bordoy 2020 ch. 5", acoustic::AcousticOptionsDescriptor());
    m.input = MethodInput::kToaStamps;
    m.start_sigma_m = [](const void* o) { return static_cast<const acoustic::AcousticOptions*>(o)->initial_position_sigma_m; };
    m.self_initializes = true;  // the filters: the fix over all stamps (multipath_fix.h); the snapshots need no start
    m.check = [](const void* o, const World& world) -> std::vector<std::string> {
      const auto& options = *static_cast<const acoustic::AcousticOptions*>(o);
      // Without the records' emission times the fixer would find no t_0 at any emission.
      if (options.estimator == "ground_echo" && options.ground_echo.sending_time == "known" && !world.emission_times_known) {
        return {"ground_echo.sending_time: 'known' needs the emission times in the records (measurements "
                "emission_time_known: true in a simulation; a recording's toa.csv has none): use estimated or unknown"};
      }
      return {};
    };
    out.push_back(std::move(m));
  }
  {
    auto m = Entry<tdoa_ekf::TdoaEkfOptions, tdoa_ekf::TdoaEkf>(
        "tdoa_ekf", "a 3-D filter on pairwise TDOA (UWB): robust EKF (Hampel), gated EKF or plain EKF",
        "Bordoy 2020 Sec. 5.2 (the REKF) on UWB TDOA rows", tdoa_ekf::TdoaEkfOptionsDescriptor());
    m.input = MethodInput::kTdoa;
    m.start_sigma_m = [](const void* o) { return static_cast<const tdoa_ekf::TdoaEkfOptions*>(o)->initial_position_sigma_m; };
    m.self_initializes = true;
    m.check = [](const void*, const World& world) -> std::vector<std::string> {
      if (world.anchors.size() < 4) return {"anchors: a 3-D position from differences needs at least 4 anchors"};
      return {};
    };
    out.push_back(std::move(m));
  }
  return out;
}

}  // namespace

const std::vector<MethodInfo>& Methods() {
  static const std::vector<MethodInfo> methods = BuiltIn();
  return methods;
}

const MethodInfo* FindMethod(std::string_view name) {
  for (const auto& m : Methods()) {
    if (m.name == name) return &m;
  }
  return nullptr;
}

std::string MethodNames() {
  std::string out;
  for (const auto& m : Methods()) out += (out.empty() ? "" : ", ") + m.name;
  return out;
}

}  // namespace mirage::methods
