// Effect names ↔ bits. Names are the ones scenes and the CLI use (DESIGN.md §7: unknown → error).
#include <array>
#include <stdexcept>
#include <string>
#include <string_view>

#include "libspread/flight/flight.hpp"

namespace spread::flight {
namespace {

struct EffectName {
  Effect bit;
  std::string_view name;
};
constexpr std::array<EffectName, 4> kEffectNames{{
    {kDrag, "drag"}, {kMagnus, "magnus"}, {kSpinDecay, "spin_decay"}, {kWind, "wind"}}};

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

}  // namespace

EffectSet parse_effects(std::string_view comma_separated) {
  const std::string_view all = trim(comma_separated);
  if (all.empty() || all == "none") return 0;
  EffectSet effects = 0;
  std::size_t start = 0;
  while (start <= all.size()) {
    const std::size_t comma = all.find(',', start);
    const std::size_t end = comma == std::string_view::npos ? all.size() : comma;
    const std::string_view token = trim(all.substr(start, end - start));
    if (token.empty()) {
      throw std::invalid_argument("effects: empty effect name in \"" + std::string(all) + "\"");
    }
    bool known = false;
    for (const auto& entry : kEffectNames) {
      if (token == entry.name) {
        effects |= entry.bit;
        known = true;
      }
    }
    if (!known) {
      throw std::invalid_argument("effects: unknown effect \"" + std::string(token) +
                                  "\" (known: drag, magnus, spin_decay, wind)");
    }
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return effects;
}

std::string effects_to_string(EffectSet effects) {
  std::string out;
  for (const auto& entry : kEffectNames) {
    if ((effects & entry.bit) == 0) continue;
    if (!out.empty()) out += ',';
    out += entry.name;
  }
  return out.empty() ? std::string("none") : out;
}

}  // namespace spread::flight
