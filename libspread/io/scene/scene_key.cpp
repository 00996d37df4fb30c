#include "libspread/io/scene/scene_key.hpp"

#include <sstream>

#include "libspread/io/scene/scene.hpp"

namespace spread::scene {

std::string format_number(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

void check_within(const std::string& source, const std::string& key, double value, const Bounds& b) {
  const bool low_ok = b.low_open ? value > b.low : value >= b.low;
  const bool high_ok = b.high_open ? value < b.high : value <= b.high;
  if (low_ok && high_ok) return;
  const auto fail = [&](const std::string& problem) { throw SceneError(source + ": " + key + ": " + problem); };
  // A closed interval reads as one range; otherwise the bound that is broken.
  if (!b.low_open && !b.high_open) {
    fail("must be in [" + format_number(b.low) + ", " + format_number(b.high) + "], got " + format_number(value));
  }
  if (!low_ok) fail(std::string(b.low_open ? "must be > " : "must be >= ") + format_number(b.low) + ", got " + format_number(value));
  fail(std::string(b.high_open ? "must be < " : "must be <= ") + format_number(b.high) + ", got " + format_number(value));
}

void fail_effect_off(const std::string& source, const std::string& key, const std::string& value,
                     effect::EffectSet effect) {
  // docs/design.md §7: a value set for an effect that is off would be recorded as provenance yet never act.
  const bool one = (effect & (effect - 1)) == 0;
  const std::string names = effect::names_of(effect);
  const std::string off = one ? "the `" + names + "` effect is off" : "none of the effects `" + names + "` is on";
  const std::string first = names.substr(0, names.find(','));
  throw SceneError(source + ": " + key + ": is " + value + " but " + off + ": add \"" + first +
                   "\" to effects.enabled or remove the key");
}

std::string choice_list(std::span<const ChoiceName> names) {
  std::string list;
  for (const ChoiceName& c : names) list += (list.empty() ? "\"" : ", \"") + std::string(c.name) + "\"";
  return list;
}

std::string_view choice_name(std::span<const ChoiceName> names, int value) {
  for (const ChoiceName& c : names) {
    if (c.value == value) return c.name;
  }
  return "?";
}

}  // namespace spread::scene
