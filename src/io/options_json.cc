// SPDX-License-Identifier: MIT
#include "mirage/io/options_json.h"

namespace mirage::io {

nlohmann::json OptionsObjectToJson(const core::OptionsDescriptorBase& descriptor, const void* options) {
  nlohmann::json json = nlohmann::json::object();
  for (const auto& field : descriptor.fields()) {
    if (field.kind() == core::OptionKind::kSection) {
      json[field.key()] = OptionsObjectToJson(*field.section(), field.SectionIn(options));
    } else {
      std::visit([&](const auto& value) { json[field.key()] = value; }, field.Get(options));
    }
  }
  return json;
}

}  // namespace mirage::io
