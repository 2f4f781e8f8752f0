// SPDX-License-Identifier: MIT
#include "mirage/core/options_descriptor.h"

#include <cmath>

namespace mirage::core {
namespace {

std::string JoinNames(const std::vector<std::string>& names) {
  std::string text;
  for (const auto& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

// "in [0, 1]" for intervals, "> 0" for one-sided ranges: reads as a sentence after "a number".
std::string RangePhrase(const ValueRange& range, const std::string& unit) {
  const std::string text = range.Text(unit);
  return (range.lower && range.upper) ? "in " + text : text;
}

}  // namespace

std::string FormatOptionValue(const OptionValue& value) {
  if (const auto* d = std::get_if<double>(&value)) return FormatNumber(*d);
  if (const auto* i = std::get_if<std::int64_t>(&value)) return std::to_string(*i);
  if (const auto* b = std::get_if<bool>(&value)) return *b ? "true" : "false";
  return std::get<std::string>(value);
}

std::optional<double> DerivedDefault::Evaluate(const PhysicalKeys& keys) const {
  for (const PhysicalKey key : needs) {
    if (!keys.Get(key)) return std::nullopt;
  }
  return compute(keys);
}

std::string DerivedDefault::NeedsText() const {
  std::string text;
  for (const PhysicalKey key : needs) text += (text.empty() ? "" : ", ") + std::string(PhysicalKeyName(key));
  return text;
}

OptionValue OptionField::Get(const void* owner) const {
  assert(kind_ != OptionKind::kSection);
  return get_(owner);
}

void OptionField::Set(void* owner, const OptionValue& value) const {
  assert(kind_ != OptionKind::kSection);
  assert(!CheckValue(value) || kind_ == OptionKind::kNumber || kind_ == OptionKind::kInteger);
  set_(owner, value);
}

void* OptionField::SectionIn(void* owner) const {
  assert(kind_ == OptionKind::kSection);
  return section_access_(owner);
}

const void* OptionField::SectionIn(const void* owner) const {
  assert(kind_ == OptionKind::kSection);
  // The accessor only forms the member's address; nothing is written through it.
  return section_access_(const_cast<void*>(owner));
}

std::string OptionField::Expected() const {
  switch (kind_) {
    case OptionKind::kNumber:
      if (!range_.lower && !range_.upper) return unit_.empty() ? "a finite number" : "a finite number in " + unit_;
      return "a number " + RangePhrase(range_, unit_);
    case OptionKind::kInteger:
      if (!range_.lower && !range_.upper) return unit_.empty() ? "an integer" : "an integer in " + unit_;
      return "an integer " + RangePhrase(range_, unit_);
    case OptionKind::kBoolean: return "true or false";
    case OptionKind::kChoice: return "one of: " + JoinNames(choices_);
    case OptionKind::kSection: return "a map of keys";
  }
  return "";
}

std::optional<std::string> OptionField::CheckValue(const OptionValue& value) const {
  const auto wrong_kind = [this] { return "expected " + Expected(); };
  switch (kind_) {
    case OptionKind::kNumber: {
      if (!std::holds_alternative<double>(value)) return wrong_kind();
      const double v = std::get<double>(value);
      if (range_.Contains(v)) return std::nullopt;
      const char* what = std::isfinite(v) ? "is out of range" : "is not a finite number";
      return ValueText(value) + " " + what + ", expected " + Expected();
    }
    case OptionKind::kInteger: {
      if (!std::holds_alternative<std::int64_t>(value)) return wrong_kind();
      const std::int64_t v = std::get<std::int64_t>(value);
      if (v < integer_min_ || v > integer_max_) {
        return ValueText(value) + " does not fit the option's integer type, expected " + Expected() + " within [" +
               std::to_string(integer_min_) + ", " + std::to_string(integer_max_) + "]";
      }
      if (range_.Contains(static_cast<double>(v))) return std::nullopt;
      return ValueText(value) + " is out of range, expected " + Expected();
    }
    case OptionKind::kBoolean:
      if (!std::holds_alternative<bool>(value)) return wrong_kind();
      return std::nullopt;
    case OptionKind::kChoice: {
      if (!std::holds_alternative<std::string>(value)) return wrong_kind();
      for (const auto& name : choices_) {
        if (name == std::get<std::string>(value)) return std::nullopt;
      }
      return "'" + std::get<std::string>(value) + "' is not a known choice, expected " + Expected();
    }
    case OptionKind::kSection: return wrong_kind();
  }
  return std::nullopt;
}

std::string OptionField::ValueText(const OptionValue& value) const {
  const bool numeric = std::holds_alternative<double>(value) || std::holds_alternative<std::int64_t>(value);
  return numeric ? WithUnit(FormatOptionValue(value), unit_) : FormatOptionValue(value);
}

const OptionField* OptionsDescriptorBase::Find(std::string_view key) const {
  for (const auto& field : fields_) {
    if (field.key() == key) return &field;
  }
  return nullptr;
}

void OptionsDescriptorBase::AddField(OptionField field) {
  assert(Find(field.key()) == nullptr && "duplicate key in an options descriptor");
  assert(!field.key().empty() && field.key().find('.') == std::string::npos);
  fields_.push_back(std::move(field));
}

std::vector<std::string> OptionsDescriptorBase::ValidateObject(const void* options) const {
  std::vector<std::string> problems;
  for (const auto& field : fields_) {
    if (field.kind() == OptionKind::kSection) {
      for (const auto& p : field.section()->ValidateObject(field.SectionIn(options))) {
        problems.push_back(field.key() + "." + p);
      }
    } else if (auto problem = field.CheckValue(field.Get(options))) {
      problems.push_back(field.key() + ": " + *problem);
    }
  }
  for (auto& p : CrossFieldProblems(options)) problems.push_back(std::move(p));
  return problems;
}

std::vector<std::string> OptionsDescriptorBase::CrossFieldProblems(const void* options) const {
  std::vector<std::string> problems;
  for (const auto& check : checks_) {
    for (auto& p : check.check(options)) problems.push_back(std::move(p));
  }
  return problems;
}

void OptionsDescriptorBase::ForEachField(const void* options, const FieldVisitor& visit) const {
  ForEachField("", options, visit);
}

void OptionsDescriptorBase::ForEachField(const std::string& prefix, const void* options,
                                         const FieldVisitor& visit) const {
  for (const auto& field : fields_) {
    const std::string path = prefix + field.key();
    visit(path, field, options);
    if (field.kind() == OptionKind::kSection) {
      field.section()->ForEachField(path + ".", field.SectionIn(options), visit);
    }
  }
}

}  // namespace mirage::core
