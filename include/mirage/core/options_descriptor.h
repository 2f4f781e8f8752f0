// SPDX-License-Identifier: MIT
// One descriptor per options struct (ROADMAP.md, "options descriptor"; STYLE.md Sec. 4): each
// field's key, unit, valid range and doc, bound to its member, plus the struct's cross-field
// checks. The descriptor drives validation here and, in io/, YAML parsing, the JSON report's
// effective options, `mirage describe` and the generated docs. Defaults stay in the struct's
// member initialisers; a descriptor only adds, per number, an optional default derived from the
// physical keys (physical_keys.h). No YAML and no exceptions here: problems are returned as
// strings "key.path: message".
#pragma once

#include <cassert>
#include <concepts>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "mirage/core/physical_keys.h"
#include "mirage/core/value_range.h"

namespace mirage::core {

/// What an option holds.
enum class OptionKind {
  kNumber,   ///< a finite double with a unit and a range
  kInteger,  ///< an integral member with a range
  kBoolean,  ///< true / false
  kChoice,   ///< one name out of a fixed list (a string member, or an enum member with a name table)
  kSection,  ///< a member that is itself an options struct with its own descriptor
};

/// One option's value without its C++ type: a number (kNumber), an integer (kInteger),
/// true/false (kBoolean) or a choice's name (kChoice).
using OptionValue = std::variant<double, std::int64_t, bool, std::string>;

/// The value as text without a unit ("0.05", "3", "true", "cir").
std::string FormatOptionValue(const OptionValue& value);

/// A default computed from the physical keys instead of the struct's fixed default, e.g. a gate
/// that must cover one step of motion plus the range noise.
struct DerivedDefault {
  /// The formula as printed by `mirage describe` and the docs, in the physical keys' names
  /// ("speed_mps * dt_s + 2 * range_sigma_m").
  std::string formula;
  /// The keys the formula uses; it applies only when all of them are known.
  std::vector<PhysicalKey> needs;
  /// The value; called only when every key in `needs` is known.
  std::function<double(const PhysicalKeys&)> compute;

  /// The derived value, or empty when a needed key is unknown.
  [[nodiscard]] std::optional<double> Evaluate(const PhysicalKeys& keys) const;
  /// The needed keys' names, comma-separated ("speed_mps, dt_s").
  [[nodiscard]] std::string NeedsText() const;
};

/// Declaration of a number field. Written with designated initialisers; key, range and doc have
/// no default, so that leaving one out is a compiler warning (an error with MIRAGE_WERROR).
struct NumberSpec {
  std::string key;   ///< YAML key, equal to the member's name
  std::string unit = {};  ///< "m", "m/s^2", "dB"; empty (may be left out) for ratios and counts
  ValueRange range;  ///< the valid values (always finite)
  std::string doc;   ///< one or two sentences: meaning, unit, why the default
  std::optional<DerivedDefault> derived = std::nullopt;  ///< default from the physical keys
};

/// Declaration of an integer field.
struct IntegerSpec {
  std::string key;   ///< YAML key, equal to the member's name
  std::string unit = {};  ///< "steps", or empty (may be left out)
  ValueRange range;  ///< the valid values (the member type's limits apply as well)
  std::string doc;   ///< one or two sentences: meaning, unit, why the default
};

/// A key that an earlier version read and this one does not, with the key that replaced it: a
/// file that still uses it fails with a message that names the new key (the value is not carried
/// over, since the unit changed: steps became seconds).
struct RetiredKey {
  std::string key;          ///< the old key ("candidate_timeout_steps")
  std::string replacement;  ///< the new key at the same level ("candidate_timeout_s")
  std::string how;          ///< how to convert a value ("seconds: the old value times dt_s")
};

/// Declaration of a boolean, choice or section field.
struct FieldSpec {
  std::string key;  ///< YAML key, equal to the member's name
  std::string doc;  ///< one or two sentences: meaning and why the default
};

class OptionsDescriptorBase;
template <typename T>
class OptionsDescriptor;

/// One field of a descriptor, without the options struct's type: generic code (io's YAML reader,
/// JSON writer and renderers) reads and writes it through a pointer to the struct that holds it.
class OptionField {
 public:
  /// Reads the field of the object at an address (a T* of the owning descriptor).
  using Getter = std::function<OptionValue(const void*)>;
  /// Writes the field of the object at an address.
  using Setter = std::function<void(void*, const OptionValue&)>;
  /// The address of a section's member inside the object at an address.
  using SectionAccess = std::function<void*(void*)>;

  /// What the field holds.
  [[nodiscard]] OptionKind kind() const { return kind_; }
  /// The YAML key (the member's name).
  [[nodiscard]] const std::string& key() const { return key_; }
  /// The unit of a number or integer ("" when it has none).
  [[nodiscard]] const std::string& unit() const { return unit_; }
  /// One or two sentences: meaning, unit, why the default.
  [[nodiscard]] const std::string& doc() const { return doc_; }
  /// The valid values of a number or integer.
  [[nodiscard]] const ValueRange& range() const { return range_; }
  /// The allowed names of a choice, in declaration order.
  [[nodiscard]] const std::vector<std::string>& choices() const { return choices_; }
  /// The derived default of a number, if it has one.
  [[nodiscard]] const std::optional<DerivedDefault>& derived() const { return derived_; }
  /// The descriptor of a section (null for other kinds).
  [[nodiscard]] const OptionsDescriptorBase* section() const { return section_.get(); }

  /// The field's value in `owner` (not for sections).
  [[nodiscard]] OptionValue Get(const void* owner) const;
  /// Writes `value` into `owner`. The value must be of the field's kind (an int64 for an
  /// integer, a name from choices() for a choice) and pass CheckValue(); not for sections.
  void Set(void* owner, const OptionValue& value) const;
  /// The section's member inside `owner` (sections only).
  [[nodiscard]] void* SectionIn(void* owner) const;
  /// The same for reading.
  [[nodiscard]] const void* SectionIn(const void* owner) const;

  /// What the field accepts, for messages: "a number > 0 m/s^2", "an integer in [0, 6]",
  /// "true or false", "one of: cir, ranges", "a map of keys".
  [[nodiscard]] std::string Expected() const;
  /// Why `value` is not valid for this field ("0 m/s^2 is out of range, expected a number
  /// > 0 m/s^2"), or empty when it is. A value of the wrong kind is a problem too.
  [[nodiscard]] std::optional<std::string> CheckValue(const OptionValue& value) const;
  /// The value as text with its unit ("0.05 m", "true", "cir").
  [[nodiscard]] std::string ValueText(const OptionValue& value) const;

 private:
  template <typename T>
  friend class OptionsDescriptor;
  OptionField() = default;

  OptionKind kind_ = OptionKind::kNumber;
  std::string key_;
  std::string unit_;
  std::string doc_;
  ValueRange range_;
  // The integer member type's limits (kInteger).
  std::int64_t integer_min_ = 0;
  std::int64_t integer_max_ = 0;
  std::vector<std::string> choices_;
  std::optional<DerivedDefault> derived_;
  std::shared_ptr<const OptionsDescriptorBase> section_;
  Getter get_;
  Setter set_;
  SectionAccess section_access_;
};

/// A check that involves several fields, with the text `mirage describe` prints for it.
struct CrossCheck {
  /// The rule in words ("search_step_m <= search_radius_m").
  std::string description;
  /// Problems of the object at the address, each "key.path: message".
  std::function<std::vector<std::string>(const void*)> check;
};

/// The descriptor of an options struct without its type (see OptionsDescriptor<T>).
class OptionsDescriptorBase {
 public:
  /// Called for each field with its key path ("motion.accel_sigma_mps2") and the object that
  /// holds it (for field.Get()).
  using FieldVisitor = std::function<void(const std::string& path, const OptionField& field, const void* owner)>;

  virtual ~OptionsDescriptorBase() = default;

  /// The struct's qualified name ("estimation::ConstantVelocityOptions").
  [[nodiscard]] const std::string& type_name() const { return type_name_; }
  /// The fields in declaration order.
  [[nodiscard]] const std::vector<OptionField>& fields() const { return fields_; }
  /// The cross-field checks in declaration order.
  [[nodiscard]] const std::vector<CrossCheck>& checks() const { return checks_; }
  /// The retired keys of this level (a reader fails on them, naming the replacement).
  [[nodiscard]] const std::vector<RetiredKey>& retired() const { return retired_; }
  /// A default-constructed object of the struct: the defaults of a top-level section.
  [[nodiscard]] const void* default_object() const { return defaults_.get(); }
  /// The field with this key at this level, or null.
  [[nodiscard]] const OptionField* Find(std::string_view key) const;

  /// Every field's range problem (sections recursively, prefixed with their key) and every
  /// cross-field problem of the object at the address; empty if valid.
  [[nodiscard]] std::vector<std::string> ValidateObject(const void* options) const;
  /// The cross-field problems of this level only (nested sections not included).
  [[nodiscard]] std::vector<std::string> CrossFieldProblems(const void* options) const;
  /// Visits every field depth first in declaration order; a section is visited before its fields.
  void ForEachField(const void* options, const FieldVisitor& visit) const;

 protected:
  OptionsDescriptorBase(std::string type_name, std::shared_ptr<const void> defaults)
      : type_name_(std::move(type_name)), defaults_(std::move(defaults)) {}
  /// Adds a field; keys are unique per level.
  void AddField(OptionField field);
  /// Adds a cross-field check.
  void AddCheck(CrossCheck check) { checks_.push_back(std::move(check)); }
  /// Adds a retired key; its replacement must be a field of this level.
  void AddRetired(RetiredKey retired) { retired_.push_back(std::move(retired)); }

 private:
  void ForEachField(const std::string& prefix, const void* options, const FieldVisitor& visit) const;

  std::string type_name_;
  std::shared_ptr<const void> defaults_;
  std::vector<OptionField> fields_;
  std::vector<CrossCheck> checks_;
  std::vector<RetiredKey> retired_;
};

/// The descriptor of options struct T, built once with the chained declarations below, e.g.
///
///   const OptionsDescriptor<GateOptions>& GateOptionsDescriptor() {
///     static const auto descriptor = [] {
///       OptionsDescriptor<GateOptions> d("estimation::GateOptions");
///       d.Number(&GateOptions::gate_m, {.key = "gate_m", .unit = "m", .range = ValueRange::Above(0.0),
///                                       .doc = "Half-width of the gate."});
///       return d;
///     }();
///     return descriptor;
///   }
template <typename T>
class OptionsDescriptor : public OptionsDescriptorBase {
 public:
  /// @param type_name the struct's qualified name, for describe and the docs.
  explicit OptionsDescriptor(std::string type_name)
      : OptionsDescriptorBase(std::move(type_name), std::make_shared<const T>()) {}

  /// A finite double member with unit, range and optionally a derived default.
  OptionsDescriptor& Number(double T::*member, NumberSpec spec) {
    OptionField f = NewField(OptionKind::kNumber, std::move(spec.key), std::move(spec.doc));
    f.unit_ = std::move(spec.unit);
    f.range_ = spec.range;
    f.derived_ = std::move(spec.derived);
    BindDirect(f, member);
    AddField(std::move(f));
    return *this;
  }

  /// An integral member (int, std::size_t, ...) with range; the type's own limits apply too
  /// (values above 2^63 - 1 are not supported).
  template <std::integral I>
    requires(!std::same_as<I, bool>)
  OptionsDescriptor& Integer(I T::*member, IntegerSpec spec) {
    constexpr std::int64_t kInt64Max = std::numeric_limits<std::int64_t>::max();
    OptionField f = NewField(OptionKind::kInteger, std::move(spec.key), std::move(spec.doc));
    f.unit_ = std::move(spec.unit);
    f.range_ = spec.range;
    f.integer_min_ = static_cast<std::int64_t>(std::numeric_limits<I>::min());
    f.integer_max_ = std::cmp_less(kInt64Max, std::numeric_limits<I>::max())
                         ? kInt64Max
                         : static_cast<std::int64_t>(std::numeric_limits<I>::max());
    f.get_ = [member](const void* o) { return OptionValue(static_cast<std::int64_t>(static_cast<const T*>(o)->*member)); };
    f.set_ = [member](void* o, const OptionValue& v) { static_cast<T*>(o)->*member = static_cast<I>(std::get<std::int64_t>(v)); };
    AddField(std::move(f));
    return *this;
  }

  /// A bool member.
  OptionsDescriptor& Boolean(bool T::*member, FieldSpec spec) {
    OptionField f = NewField(OptionKind::kBoolean, std::move(spec.key), std::move(spec.doc));
    BindDirect(f, member);
    AddField(std::move(f));
    return *this;
  }

  /// A std::string member that must be one of `names`.
  OptionsDescriptor& Choice(std::string T::*member, FieldSpec spec, std::vector<std::string> names) {
    OptionField f = NewField(OptionKind::kChoice, std::move(spec.key), std::move(spec.doc));
    f.choices_ = std::move(names);
    BindDirect(f, member);
    AddField(std::move(f));
    return *this;
  }

  /// An enum member, written in YAML as one of the names of `table` (name, value).
  template <typename E>
    requires std::is_enum_v<E>
  OptionsDescriptor& Choice(E T::*member, FieldSpec spec, std::vector<std::pair<std::string, E>> table) {
    OptionField f = NewField(OptionKind::kChoice, std::move(spec.key), std::move(spec.doc));
    for (const auto& entry : table) f.choices_.push_back(entry.first);
    f.get_ = [member, table](const void* o) {
      const E value = static_cast<const T*>(o)->*member;
      for (const auto& [name, e] : table) {
        if (e == value) return OptionValue(name);
      }
      // An enum value without a name: CheckValue() reports it.
      return OptionValue("(unnamed value " + std::to_string(static_cast<long long>(value)) + ")");
    };
    f.set_ = [member, table](void* o, const OptionValue& v) {
      for (const auto& [name, e] : table) {
        if (name == std::get<std::string>(v)) {
          static_cast<T*>(o)->*member = e;
          return;
        }
      }
      assert(false && "Set() with a name that is not a choice");
    };
    AddField(std::move(f));
    return *this;
  }

  /// A member that is itself an options struct, described by `sub`; its keys appear under
  /// `spec.key` (YAML) and with the prefix "key." (messages, describe).
  template <typename S>
  OptionsDescriptor& Section(S T::*member, FieldSpec spec, const OptionsDescriptor<S>& sub) {
    OptionField f = NewField(OptionKind::kSection, std::move(spec.key), std::move(spec.doc));
    f.section_ = std::make_shared<const OptionsDescriptor<S>>(sub);
    f.section_access_ = [member](void* o) -> void* { return &(static_cast<T*>(o)->*member); };
    AddField(std::move(f));
    return *this;
  }

  /// A cross-field check: `check` returns one problem "key: message" per violation (the key of
  /// the field to blame, relative to T). It should stay silent when a field it needs is out of its
  /// own range, which is reported already.
  OptionsDescriptor& Check(std::string description, std::function<std::vector<std::string>(const T&)> check) {
    AddCheck({std::move(description),
              [check = std::move(check)](const void* o) { return check(*static_cast<const T*>(o)); }});
    return *this;
  }

  /// A key no longer read (RetiredKey): a file that uses it fails with a message naming
  /// `replacement`, which must be declared at this level already.
  OptionsDescriptor& Retired(std::string key, std::string replacement, std::string how) {
    assert(Find(replacement) != nullptr && "a retired key's replacement must be a field");
    assert(Find(key) == nullptr && "a retired key cannot be a field");
    AddRetired({std::move(key), std::move(replacement), std::move(how)});
    return *this;
  }

  /// Every range and cross-field problem of `options` (sections included), each "key.path:
  /// message with value, unit and expected range"; empty if valid.
  [[nodiscard]] std::vector<std::string> Validate(const T& options) const { return ValidateObject(&options); }
  /// Visits every field of `options` (see OptionsDescriptorBase::ForEachField).
  void ForEach(const T& options, const FieldVisitor& visit) const { ForEachField(&options, visit); }
  /// A default-constructed T.
  [[nodiscard]] const T& defaults() const { return *static_cast<const T*>(default_object()); }

 private:
  static OptionField NewField(OptionKind kind, std::string key, std::string doc) {
    OptionField f;
    f.kind_ = kind;
    f.key_ = std::move(key);
    f.doc_ = std::move(doc);
    return f;
  }
  // Get and set of a member whose type is one of OptionValue's alternatives.
  template <typename M>
  static void BindDirect(OptionField& f, M T::*member) {
    f.get_ = [member](const void* o) { return OptionValue(static_cast<const T*>(o)->*member); };
    f.set_ = [member](void* o, const OptionValue& v) { static_cast<T*>(o)->*member = std::get<M>(v); };
  }
};

}  // namespace mirage::core
