// SPDX-License-Identifier: MIT
// What every real options descriptor is tested for, next to its struct's other tests: the
// defaults pass field by field, and the descriptor lists exactly the struct's configurable
// members. C++ cannot list a struct's members, so the test names them by hand in declaration
// order; a member added without a descriptor entry then fails the test once someone adds it to
// that list, and `mirage describe` (DescribeText) must mention every key.
#pragma once

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "mirage/core/options_descriptor.h"
#include "mirage/io/options_describe.h"

namespace mirage::test {

/// The keys of the descriptor's own level (not its sections' keys), in declaration order.
inline std::vector<std::string> KeysOf(const core::OptionsDescriptorBase& descriptor) {
  std::vector<std::string> keys;
  for (const auto& field : descriptor.fields()) keys.push_back(field.key());
  return keys;
}

/// Expects of the descriptor of T:
/// - its keys are `members`, the struct's configurable members in declaration order;
/// - every field of a default-constructed T is valid, and so is the whole (cross-field checks);
/// - every field, sections' fields included, has a doc and appears in DescribeText by key path.
template <typename T>
void ExpectDescribesEveryMember(const core::OptionsDescriptor<T>& descriptor, const std::vector<std::string>& members) {
  const T defaults{};
  const std::string text = io::DescribeText(descriptor, "options");

  EXPECT_EQ(descriptor.fields().size(), members.size()) << descriptor.type_name();
  EXPECT_EQ(KeysOf(descriptor), members) << descriptor.type_name();
  EXPECT_EQ(descriptor.Validate(defaults), std::vector<std::string>{}) << descriptor.type_name();
  descriptor.ForEach(defaults, [&](const std::string& path, const core::OptionField& field, const void* owner) {
    EXPECT_FALSE(field.doc().empty()) << path;
    EXPECT_NE(text.find("\n" + path + "  "), std::string::npos) << path << " is not in:\n" << text;
    if (field.kind() != core::OptionKind::kSection) {
      EXPECT_EQ(field.CheckValue(field.Get(owner)), std::nullopt) << path;
    }
  });
}

}  // namespace mirage::test
