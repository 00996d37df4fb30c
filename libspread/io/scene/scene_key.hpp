#pragma once
// One row per scene key: its name (= the struct member's name = the docs' row), the member it fills, its
// unit, its range and the effect it belongs to. The default is the member's value in a default-constructed
// owner, so it is written once, in the struct. One reading path (read_keys) and one checking path
// (check_keys) serve every section of the spreader's scene and of the drum's; the docs' key tables are
// checked against the rows (tests/scene/test_parameter_schema.cpp). Relations between keys (the inlet
// inside the rim, two discs at least 2R apart) are not a single key's range: the readers check them after.
#include <array>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <variant>
#include <vector>

#include "libspread/core/effect_registry.hpp"
#include "libspread/io/scene/toml_document.hpp"
#include "libspread/io/tables/material_schema.hpp"

namespace spread::scene {

using tables::Bounds;
inline constexpr double kInfinity = std::numeric_limits<double>::infinity();
inline constexpr Bounds kAnyValue{-kInfinity, true, kInfinity, true};
inline constexpr Bounds kPositive{0.0, true, kInfinity, true};      // > 0
inline constexpr Bounds kNonNegative{0.0, false, kInfinity, true};  // >= 0
constexpr Bounds closed(double low, double high) { return {low, false, high, false}; }
constexpr Bounds positive_at_most(double high) { return {0.0, true, high, false}; }

// One spelling of an enumerated value; several spellings may give one value (an older name kept as an
// alias), the first one is the value's own name.
struct ChoiceName {
  std::string_view name;
  int value;
};

// An enumerated string key: its spellings and how the owner's member is read and written as an int.
template <typename Owner>
struct Choice {
  std::span<const ChoiceName> names;
  int (*get)(const Owner&);
  void (*set)(Owner&, int);
};

namespace key_detail {
template <typename T>
struct MemberOf;
template <typename Owner, typename Value>
struct MemberOf<Value Owner::*> {
  using owner = Owner;
  using value = Value;
};
}  // namespace key_detail

// choice<&Numerics::integrator>(kIntegratorNames): the Choice of an enum member.
template <auto Member>
constexpr Choice<typename key_detail::MemberOf<decltype(Member)>::owner> choice(std::span<const ChoiceName> names) {
  using Owner = typename key_detail::MemberOf<decltype(Member)>::owner;
  using Enum = typename key_detail::MemberOf<decltype(Member)>::value;
  return {names, [](const Owner& o) { return static_cast<int>(o.*Member); },
          [](Owner& o, int v) { o.*Member = static_cast<Enum>(v); }};
}

template <typename Owner>
using Field = std::variant<double Owner::*, int Owner::*, std::uint64_t Owner::*, bool Owner::*, std::string Owner::*,
                           std::vector<double> Owner::*, std::vector<std::string> Owner::*,
                           std::array<double, 2> Owner::*, Choice<Owner>>;

// What a key is to a table run built from the scene (Scene::run_inputs_text, whose hash lookup_builder
// compares before it extends a table): a value that can change the run's samples — for every run
// (kAlways) or only for runs of one launch source (kDem, kAnalytic) — or none of its inputs (kNone:
// outputs, threads, the sweep's lists, the `simulate` command's own keys).
enum class RunInput { kAlways, kDem, kAnalytic, kNone };

template <typename Owner>
struct Key {
  std::string_view name;
  Field<Owner> field;
  std::string_view unit;  // "–" when dimensionless or not a number
  Bounds bounds;          // numbers and integers (each element of a list); kAnyValue otherwise
  effect::EffectSet effect;  // the key acts only with one of these effects on (0: always); a scene that
                             // sets it away from its default with all of them off is refused
  std::string_view meaning;
  std::string_view alias = {};  // an older name still accepted (never both in one table)
  // A new key is an input of every run unless its row says otherwise: a key forgotten here then makes
  // lookup_builder rebuild rather than mix runs of other inputs into a table.
  RunInput run_input = RunInput::kAlways;
  bool (*input_when)(const Owner&) = nullptr;  // an input only when this holds (nullptr: whenever its role says)
};

// A material quantity's name, unit and bounds as a key of another owner (the drum's contact section):
// one name and one range per quantity wherever it is read.
template <typename Owner>
constexpr Key<Owner> material_key(std::string_view name, double Owner::* member, std::string_view meaning,
                                  std::string_view alias = {}) {
  for (const tables::MaterialQuantity& q : tables::kMaterialQuantities) {
    if (q.name == name) return {q.name, member, q.unit, q.scene_bounds, 0, meaning, alias};
  }
  throw "material_key: no such material quantity";  // a compile-time error in a constexpr table
}

// ---- reading and checking (shared by every section) -----------------------------------------------

// "1.5", "-3", "1e-05" (the shortest stream form): numbers in messages.
std::string format_number(double value);
// SceneError "<source>: <key>: must be …, got <value>" unless value is within b.
void check_within(const std::string& source, const std::string& key, double value, const Bounds& b);
// SceneError "<source>: <key>: is <value> but the `<effect>` effect is off: …".
[[noreturn]] void fail_effect_off(const std::string& source, const std::string& key, const std::string& value,
                                  effect::EffectSet effect);
// The spellings of a choice, for messages and docs: "\"a\", \"b\"".
std::string choice_list(std::span<const ChoiceName> names);
// The value's own (first) spelling.
std::string_view choice_name(std::span<const ChoiceName> names, int value);

namespace key_detail {

inline std::string text_of(double value) { return format_number(value); }
inline std::string text_of(int value) { return std::to_string(value); }
inline std::string text_of(std::uint64_t value) { return std::to_string(value); }
inline std::string text_of(bool value) { return value ? "true" : "false"; }
inline std::string text_of(const std::string& value) { return "\"" + value + "\""; }
template <typename Range>
std::string list_text(const Range& values) {
  std::string text = "[";
  for (const auto& v : values) text += (text.size() > 1 ? ", " : "") + text_of(v);
  return text + "]";
}
inline std::string text_of(const std::vector<double>& value) { return list_text(value); }
inline std::string text_of(const std::vector<std::string>& value) { return list_text(value); }
inline std::string text_of(const std::array<double, 2>& value) { return list_text(value); }

// Which spelling of the key the table uses: its name, its alias, or "" when neither.
inline std::string spelling_used(const TomlSection& s, std::string_view name, std::string_view alias) {
  const std::string own(name);
  if (alias.empty() || !s.present(std::string(alias))) return own;
  if (s.present(own)) s.fail(own, "given twice: as `" + own + "` and as its older name `" + std::string(alias) + "`");
  return std::string(alias);
}

}  // namespace key_detail

// Reads one key into its member when the table has it (under its name or alias); absent keys keep the
// owner's value. Types are checked here, ranges by check_keys once the whole scene is read.
template <typename Owner>
void read_key(TomlSection& s, Owner& owner, const Key<Owner>& key) {
  const std::string name = key_detail::spelling_used(s, key.name, key.alias);
  std::visit(
      [&](const auto& field) {
        using F = std::decay_t<decltype(field)>;
        if constexpr (std::is_same_v<F, double Owner::*>) {
          if (auto v = s.number(name)) owner.*field = *v;
        } else if constexpr (std::is_same_v<F, int Owner::*>) {
          if (auto v = s.integer(name)) {
            if (*v < -1'000'000'000 || *v > 1'000'000'000) s.fail(name, "out of range, got " + std::to_string(*v));
            owner.*field = static_cast<int>(*v);
          }
        } else if constexpr (std::is_same_v<F, std::uint64_t Owner::*>) {
          if (auto v = s.integer(name)) {
            if (*v < 0) s.fail(name, "must be >= 0, got " + std::to_string(*v));
            owner.*field = static_cast<std::uint64_t>(*v);
          }
        } else if constexpr (std::is_same_v<F, bool Owner::*>) {
          if (auto v = s.boolean(name)) owner.*field = *v;
        } else if constexpr (std::is_same_v<F, std::string Owner::*>) {
          if (auto v = s.string(name)) owner.*field = *v;
        } else if constexpr (std::is_same_v<F, std::vector<double> Owner::*>) {
          if (auto v = s.numbers(name)) owner.*field = *v;
        } else if constexpr (std::is_same_v<F, std::vector<std::string> Owner::*>) {
          if (auto v = s.strings(name)) owner.*field = *v;
        } else if constexpr (std::is_same_v<F, std::array<double, 2> Owner::*>) {
          if (auto v = s.numbers(name)) {
            if (v->size() != 2) s.fail(name, "expected [vx, vy], got " + std::to_string(v->size()) + " values");
            owner.*field = {(*v)[0], (*v)[1]};
          }
        } else {
          if (auto v = s.string(name)) {
            for (const ChoiceName& c : field.names) {
              if (c.name == *v) return field.set(owner, c.value);
            }
            s.fail(name, "unknown value \"" + *v + "\" (expected one of " + choice_list(field.names) + ")");
          }
        }
      },
      key.field);
}

template <typename Owner>
void read_keys(TomlSection& s, Owner& owner, std::span<const Key<Owner>> keys) {
  for (const Key<Owner>& key : keys) read_key(s, owner, key);
}

// The key's value in `owner` as a docs/messages text ("0.29", "\"analytic\"", "[0, 0]", "false").
template <typename Owner>
std::string value_text(const Owner& owner, const Key<Owner>& key) {
  return std::visit(
      [&](const auto& field) -> std::string {
        using F = std::decay_t<decltype(field)>;
        if constexpr (std::is_same_v<F, Choice<Owner>>) {
          return "\"" + std::string(choice_name(field.names, field.get(owner))) + "\"";
        } else {
          return key_detail::text_of(owner.*field);
        }
      },
      key.field);
}

// The key's default: its value in a default-constructed owner.
template <typename Owner>
std::string default_text(const Key<Owner>& key) {
  return value_text(Owner{}, key);
}

// Each key's range (every element of a list), and no key away from its default while its effect is off.
// `path` is the section's dotted path ("machine", "species[1]").
template <typename Owner>
void check_keys(const std::string& source, const std::string& path, const Owner& owner,
                std::span<const Key<Owner>> keys, effect::EffectSet effects_on) {
  const Owner defaults{};
  for (const Key<Owner>& key : keys) {
    const std::string where = path + "." + std::string(key.name);
    std::visit(
        [&](const auto& field) {
          using F = std::decay_t<decltype(field)>;
          if constexpr (std::is_same_v<F, double Owner::*> || std::is_same_v<F, int Owner::*> ||
                        std::is_same_v<F, std::uint64_t Owner::*>) {
            check_within(source, where, static_cast<double>(owner.*field), key.bounds);
          } else if constexpr (std::is_same_v<F, std::vector<double> Owner::*> ||
                               std::is_same_v<F, std::array<double, 2> Owner::*>) {
            const auto& values = owner.*field;
            for (std::size_t i = 0; i < values.size(); ++i) {
              check_within(source, where + "[" + std::to_string(i) + "]", values[i], key.bounds);
            }
          }
        },
        key.field);
    if (key.effect != 0 && (effects_on & key.effect) == 0) {
      const std::string value = value_text(owner, key);
      if (value != value_text(defaults, key)) fail_effect_off(source, where, value, key.effect);
    }
  }
}

}  // namespace spread::scene
