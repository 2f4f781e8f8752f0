// SPDX-License-Identifier: MIT
#include "mirage/io/options_describe.h"

#include <sstream>

namespace mirage::io {
namespace {

using core::OptionField;
using core::OptionKind;

constexpr std::size_t kTextWidth = 100;

std::string TypeName(const OptionField& field) {
  switch (field.kind()) {
    case OptionKind::kNumber: return "number";
    case OptionKind::kInteger: return "integer";
    case OptionKind::kBoolean: return "boolean";
    case OptionKind::kChoice: return "choice";
    case OptionKind::kSection: return "section";
  }
  return "";
}

// The default of a field held by `owner` (a default object); `with_unit` for plain text (the
// Markdown table has a unit column).
std::string DefaultText(const OptionField& field, const void* owner, bool with_unit) {
  const core::OptionValue value = field.Get(owner);
  std::string text = with_unit ? field.ValueText(value) : core::FormatOptionValue(value);
  if (!field.derived()) return text;
  return "derived: " + field.derived()->formula + " (" + text + " without " + field.derived()->NeedsText() + ")";
}

// Words of `text` on lines of at most kTextWidth characters, each line starting with `indent`.
std::string Wrap(const std::string& text, const std::string& indent) {
  std::istringstream words(text);
  std::string out, line, word;
  while (words >> word) {
    if (!line.empty() && indent.size() + line.size() + 1 + word.size() > kTextWidth) {
      out += indent + line + "\n";
      line.clear();
    }
    line += (line.empty() ? "" : " ") + word;
  }
  if (!line.empty()) out += indent + line + "\n";
  return out;
}

void DescribeChecks(const core::OptionsDescriptorBase& descriptor, const std::string& prefix, std::string& out) {
  for (const auto& check : descriptor.checks()) {
    out += "    " + (prefix.empty() ? "" : prefix + ": ") + check.description + "\n";
  }
  for (const auto& field : descriptor.fields()) {
    if (field.kind() == OptionKind::kSection) {
      DescribeChecks(*field.section(), prefix.empty() ? field.key() : prefix + "." + field.key(), out);
    }
  }
}

// The valid values for a table that has type and unit columns already: "> 0", "cir, ranges".
std::string ValidText(const OptionField& field) {
  switch (field.kind()) {
    case OptionKind::kNumber:
    case OptionKind::kInteger: return field.range().Text();
    case OptionKind::kBoolean: return "true, false";
    case OptionKind::kChoice: {
      std::string names;
      for (const auto& name : field.choices()) names += (names.empty() ? "" : ", ") + name;
      return names;
    }
    case OptionKind::kSection: return "";
  }
  return "";
}

std::string EscapeCell(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (c == '|') out += '\\';
    out += c;
  }
  return out;
}

void MarkdownTable(const core::OptionsDescriptorBase& descriptor, const void* defaults, const std::string& path,
                   int level, std::string& out) {
  out += std::string(level, '#') + " `" + path + "` (`" + descriptor.type_name() + "`)\n\n";
  out += "| key | type | unit | default | valid | meaning |\n|---|---|---|---|---|---|\n";
  for (const auto& field : descriptor.fields()) {
    std::string type = TypeName(field), unit, default_text, valid, doc = field.doc();
    if (field.kind() == OptionKind::kSection) {
      doc += " Keys: `" + path + "." + field.key() + "` below.";
    } else {
      unit = field.unit();
      default_text = DefaultText(field, defaults, false);
      valid = ValidText(field);
    }
    out += "| `" + field.key() + "` | " + type + " | " + EscapeCell(unit) + " | " + EscapeCell(default_text) + " | " +
           EscapeCell(valid) + " | " + EscapeCell(doc) + " |\n";
  }
  if (!descriptor.checks().empty()) {
    out += "\nCross-field checks:\n";
    for (const auto& check : descriptor.checks()) out += "- " + check.description + "\n";
  }
  for (const auto& field : descriptor.fields()) {
    if (field.kind() != OptionKind::kSection) continue;
    out += "\n";
    MarkdownTable(*field.section(), field.SectionIn(defaults), path + "." + field.key(), level + 1, out);
  }
}

}  // namespace

std::string DescribeText(const core::OptionsDescriptorBase& descriptor, const std::string& name) {
  std::string out = name + ": " + descriptor.type_name() + "\n";
  descriptor.ForEachField(descriptor.default_object(), [&](const std::string& path, const OptionField& field,
                                                           const void* owner) {
    out += "\n";
    if (field.kind() == OptionKind::kSection) {
      out += path + "  section, " + field.section()->type_name() + "\n";
    } else {
      out += path + "  " + TypeName(field) + (field.unit().empty() ? "" : ", " + field.unit()) + "\n";
      out += "    default: " + DefaultText(field, owner, true) + "\n";
      out += "    valid:   " + field.Expected() + "\n";
    }
    out += Wrap(field.doc(), "    ");
  });
  std::string checks;
  DescribeChecks(descriptor, "", checks);
  if (!checks.empty()) out += "\ncross-field checks:\n" + checks;
  return out;
}

std::string DescribeMarkdown(const core::OptionsDescriptorBase& descriptor, const std::string& name) {
  std::string out;
  MarkdownTable(descriptor, descriptor.default_object(), name, 2, out);
  return out;
}

}  // namespace mirage::io
