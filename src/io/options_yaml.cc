// SPDX-License-Identifier: MIT
#include "mirage/io/options_yaml.h"

#include <cmath>

#include <fmt/format.h>

namespace mirage::io {
namespace {

using core::OptionField;
using core::OptionKind;
using core::OptionValue;

// Writes a value read from the file, after its check.
void SetChecked(YamlMap& m, const OptionField& field, const OptionValue& value, void* out) {
  if (const auto problem = field.CheckValue(value)) m.Fail(field.key(), *problem);
  field.Set(out, value);
}

// The derived default of an absent number, when every physical key it needs is known.
void ApplyDerivedDefault(YamlMap& m, const OptionField& field, const core::PhysicalKeys& keys, void* out) {
  if (!field.derived()) return;
  const std::optional<double> value = field.derived()->Evaluate(keys);
  if (!value) return;
  if (const auto problem = field.CheckValue(*value)) {
    m.Fail(field.key(), fmt::format("the derived default {} gives {}; set the key explicitly", field.derived()->formula,
                                    *problem));
  }
  field.Set(out, *value);
}

void ReadInteger(YamlMap& m, const OptionField& field, void* out) {
  const std::optional<double> value = m.FiniteNumber(field.key(), field.Expected());
  if (!value) return;
  // 2^63: the first double outside the int64 range.
  constexpr double kInt64Limit = 9223372036854775808.0;
  if (*value != std::floor(*value) || *value >= kInt64Limit || *value < -kInt64Limit) {
    m.Fail(field.key(), fmt::format("expected {}, got {}", field.Expected(), FormatValue(*value)));
  }
  SetChecked(m, field, static_cast<std::int64_t>(*value), out);
}

void ReadField(YamlMap& m, const OptionField& field, const core::PhysicalKeys& keys, void* out) {
  switch (field.kind()) {
    case OptionKind::kNumber:
      if (const auto value = m.FiniteNumber(field.key(), field.Expected())) {
        SetChecked(m, field, *value, out);
      } else {
        ApplyDerivedDefault(m, field, keys, out);
      }
      return;
    case OptionKind::kInteger: ReadInteger(m, field, out); return;
    case OptionKind::kBoolean: field.Set(out, m.Boolean(field.key(), std::get<bool>(field.Get(out)))); return;
    case OptionKind::kChoice:
      if (m.Has(field.key())) SetChecked(m, field, m.String(field.key()), out);
      return;
    case OptionKind::kSection: {
      YamlMap sub = m.OptionalMap(field.key());
      ReadOptionsObject(sub, *field.section(), keys, field.SectionIn(out));
      return;
    }
  }
}

}  // namespace

void ReadOptionsObject(YamlMap& section, const core::OptionsDescriptorBase& descriptor, const core::PhysicalKeys& keys,
                       void* out) {
  for (const auto& retired : descriptor.retired()) {
    if (section.Has(retired.key)) {
      section.Fail(retired.key, fmt::format("this key was replaced by {} ({}); write {} instead", retired.replacement,
                                            retired.how, retired.replacement));
    }
  }
  for (const auto& field : descriptor.fields()) ReadField(section, field, keys, out);
  section.RejectUnknownKeys();
  // Range problems of the values read were thrown above; this finds the cross-field problems
  // (and a default that a containing struct set out of range).
  const auto problems = descriptor.ValidateObject(out);
  if (!problems.empty()) section.FailProblem(problems.front());
}

}  // namespace mirage::io
