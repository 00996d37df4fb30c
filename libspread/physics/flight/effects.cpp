// Flight effect lists ↔ bits, through the effect registry (docs/design.md §7: unknown → error).
#include <stdexcept>
#include <string>
#include <string_view>

#include "libspread/physics/flight/flight.hpp"

namespace spread::flight {
namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

}  // namespace

EffectSet parse_effects(std::string_view comma_separated) {
  const std::string_view all = trim(comma_separated);
  // "none": how tables written before the empty list was canonical record a drag-free flight.
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
    const effect::Effect* row = effect::find(token);
    if (row == nullptr) {
      throw std::invalid_argument("effects: unknown effect \"" + std::string(token) +
                                  "\" (known: " + effect::names_of(kAllEffects) + ")");
    }
    if (row->domain != effect::Domain::kFlight) {
      throw std::invalid_argument("effects: \"" + std::string(token) +
                                  "\" acts on the disc, not in flight (flight effects: " +
                                  effect::names_of(kAllEffects) + ")");
    }
    effects |= row->bit;
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return effects;
}

std::string effects_to_string(EffectSet effects) { return effect::to_string(effects & kAllEffects); }

}  // namespace spread::flight
