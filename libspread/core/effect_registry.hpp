#pragma once
// The effects a scene can turn on, one row each (docs/design.md §7: exactly the effects a scene calls for
// run; an effect that is off is not evaluated). Everything that knows an effect by name or bit reads it
// from this table: the scene reader (names, defaults, requirements), the flight's right-hand-side table
// (one instantiation per subset of the flight bits), the DEM's configuration, the tables' provenance
// strings, the C header's SPREAD_EFFECT_* bits (static_asserts in capi/src/predict.cpp) and the
// docs (tests/scene/test_effect_registry.cpp checks docs/scene-format.md lists every row, and the C header
// defines every flight bit). Adding an effect: its bit and row here, its evaluator, its doc line; a flight
// effect also its SPREAD_EFFECT_* bit (docs/design.md §7 gives the recipe, and what fails if a step is
// missed).
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace spread::effect {

using EffectSet = std::uint32_t;

enum class Domain : std::uint8_t {
  kDem,     // acts while the granule is on the disc (libspread/physics/dem)
  kFlight,  // acts after launch-off (libspread/physics/flight)
};

// Bits of one set for the whole scene. The flight effects are the low bits, contiguous from bit 0: they
// index the flight's instantiation table, and they are the C API's SPREAD_EFFECT_* values, which are
// public ABI — never renumber a row. The flight bits have a namespace of their own, which
// libspread/physics/flight/flight.hpp brings into spread::flight whole: a new one needs no line there.
inline namespace flight_bits {
inline constexpr EffectSet kDrag = 1u << 0;
inline constexpr EffectSet kMagnus = 1u << 1;
inline constexpr EffectSet kSpinDecay = 1u << 2;
inline constexpr EffectSet kWind = 1u << 3;
}  // namespace flight_bits
inline constexpr EffectSet kParticleContact = 1u << 8;
inline constexpr EffectSet kWallContact = 1u << 9;
inline constexpr EffectSet kRotation = 1u << 10;
inline constexpr EffectSet kRolling = 1u << 11;

struct Effect {
  std::string_view name;  // in effects.enabled, in provenance, in the CLI's --effects
  Domain domain;
  EffectSet bit;
  EffectSet requires_effects;  // effects that must be on with this one (checked by the scene reader)
  bool on_by_default;          // on when a scene has no effects.enabled
  std::string_view model;      // what is evaluated, with its source (docs)
};

// Canonical order: the order of every list written (provenance, messages). The size follows the rows.
inline constexpr auto kRegistry = std::to_array<Effect>({
    {"particle_contact", Domain::kDem, kParticleContact, 0, true,
     "particle–particle contacts with the scene's contact law (seed 000 Eqs. 1–24)"},
    {"wall_contact", Domain::kDem, kWallContact, 0, true,
     "particle–wall contacts: disc, vanes, mesh or STL walls (same law, the material's wall friction)"},
    {"rotation", Domain::kDem, kRotation, 0, true, "particle spin state: contact moments (seed 000 Eq. 15)"},
    {"rolling", Domain::kDem, kRolling, kRotation, false,
     "rolling resistance, constant torque μ_r R* F_n against the relative spin (needs rotation)"},
    {"drag", Domain::kFlight, kDrag, 0, true, "air drag, seed 000 Eq. 27 with the Haider–Levenspiel C_D, Eq. 32"},
    {"magnus", Domain::kFlight, kMagnus, 0, true, "Magnus lift, seed 000 Eq. 28 (lift model in docs/physics-flight.md)"},
    {"spin_decay", Domain::kFlight, kSpinDecay, 0, true, "spin decay in flight, seed 000 Eqs. 34–36"},
    {"wind", Domain::kFlight, kWind, 0, false,
     "uniform horizontal wind: the relative air velocity replaces the granule velocity in every air term"},
});

constexpr EffectSet mask(Domain domain) {
  EffectSet set = 0;
  for (const Effect& e : kRegistry) set |= e.domain == domain ? e.bit : 0u;
  return set;
}
inline constexpr EffectSet kFlightEffects = mask(Domain::kFlight);
inline constexpr EffectSet kDemEffects = mask(Domain::kDem);
inline constexpr EffectSet kAll = kFlightEffects | kDemEffects;

constexpr EffectSet default_effects() {
  EffectSet set = 0;
  for (const Effect& e : kRegistry) set |= e.on_by_default ? e.bit : 0u;
  return set;
}
inline constexpr EffectSet kDefault = default_effects();

// nullptr when no row has this name.
constexpr const Effect* find(std::string_view name) {
  for (const Effect& e : kRegistry) {
    if (e.name == name) return &e;
  }
  return nullptr;
}
constexpr const Effect& row(EffectSet bit) {
  for (const Effect& e : kRegistry) {
    if (e.bit == bit) return e;
  }
  return kRegistry[0];  // unreachable for a registry bit (checked below)
}

// The requirements of `set` that `set` lacks (0 when every effect has what it needs).
constexpr EffectSet unmet_requirements(EffectSet set) {
  EffectSet missing = 0;
  for (const Effect& e : kRegistry) {
    if ((set & e.bit) != 0) missing |= e.requires_effects & ~set;
  }
  return missing;
}

// Comma-separated names of `set` in canonical order; "" for the empty set.
inline std::string to_string(EffectSet set, std::string_view separator = ",") {
  std::string list;
  for (const Effect& e : kRegistry) {
    if ((set & e.bit) == 0) continue;
    if (!list.empty()) list += separator;
    list += e.name;
  }
  return list;
}

// The names of `set` in canonical order (JSON lists, the DEM's report of what ran).
inline std::vector<std::string> names_in(EffectSet set) {
  std::vector<std::string> names;
  for (const Effect& e : kRegistry) {
    if ((set & e.bit) != 0) names.emplace_back(e.name);
  }
  return names;
}

// "a, b, c": the names of a domain, for messages listing what is known.
inline std::string names_of(EffectSet set) { return to_string(set, ", "); }

namespace detail {
constexpr bool rows_consistent() {
  EffectSet seen = 0;
  for (const Effect& e : kRegistry) {
    if (e.bit == 0 || (e.bit & (e.bit - 1)) != 0) return false;  // one bit per row
    if ((seen & e.bit) != 0) return false;                         // no bit twice
    seen |= e.bit;
    if ((e.requires_effects & ~mask(e.domain)) != 0) return false;  // requirements within the domain
    for (const Effect& other : kRegistry) {
      if (&other != &e && other.name == e.name) return false;
    }
  }
  return true;
}
}  // namespace detail
static_assert(detail::rows_consistent(), "effect registry: one distinct bit and one distinct name per row");
// The flight's table has one instantiation per subset of the flight bits: they must be bits 0..n−1.
static_assert((kFlightEffects & (kFlightEffects + 1)) == 0, "flight effects must be the low bits");
static_assert(unmet_requirements(kDefault) == 0, "the default effects must meet their own requirements");

}  // namespace spread::effect
