#pragma once
// The flight terms (flight_terms.hpp) as a table over the registry's flight bits, built at compile time:
// every flight row must have its Term (else the build fails here), each term of its own gets a slot for
// its parameters, and the right-hand side of effect set E adds the accelerations of exactly the terms in E.
// The flight bits are bits 0..n−1 (checked in effect_registry.hpp), so slot I holds bit 1 << I.
#include <algorithm>
#include <bit>
#include <concepts>
#include <cstddef>
#include <tuple>
#include <utility>

#include "libspread/physics/flight/flight_terms.hpp"

namespace spread::flight::detail {

template <EffectSet Bit>
concept InAirBlock = requires { requires Term<Bit>::kInAirBlock; };

template <EffectSet Bit>
concept OwnTerm = requires(const typename Term<Bit>::Parameters& p, const Granule& granule, const State& launch,
                           const Air& air, const Settings& settings, const double* y, double& a) {
  { Term<Bit>::derive(granule, launch, air, settings) } -> std::same_as<typename Term<Bit>::Parameters>;
  Term<Bit>::accelerate(p, y, a, a, a);
  { Term<Bit>::rate_per_s(p, launch) } -> std::same_as<double>;
};

inline constexpr std::size_t kFlightBitCount = static_cast<std::size_t>(std::popcount(kAllEffects));
using FlightSlots = std::make_index_sequence<kFlightBitCount>;
template <std::size_t I>
inline constexpr EffectSet kBitOf = EffectSet{1} << I;

// The error names the bit: "... in instantiation of has_term<Bit>() [with Bit = ...]".
template <EffectSet Bit>
constexpr bool has_term() {
  static_assert(InAirBlock<Bit> || OwnTerm<Bit>,
                "a flight row of the effect registry has no evaluator: Term<bit> in flight_terms.hpp, with "
                "Parameters, derive, accelerate and rate_per_s");
  return true;
}
template <std::size_t... I>
constexpr bool every_flight_row_has_term(std::index_sequence<I...>) {
  return (has_term<kBitOf<I>>() && ...);
}
static_assert(every_flight_row_has_term(FlightSlots{}));

template <std::size_t... I>
constexpr EffectSet air_block_effects(std::index_sequence<I...>) {
  return ((InAirBlock<kBitOf<I>> ? kBitOf<I> : EffectSet{0}) | ... | EffectSet{0});
}
// The effects flight_rhs's air block evaluates (right_hand_side.hpp checks it knows each of them).
inline constexpr EffectSet kAirBlockEffects = air_block_effects(FlightSlots{});

// Slot I: the parameters of the term of bit 1 << I, empty for an air-block effect.
template <EffectSet Bit>
struct TermSlot {};
template <EffectSet Bit>
  requires OwnTerm<Bit>
struct TermSlot<Bit> {
  typename Term<Bit>::Parameters value;
};
template <class Slots>
struct TermSlotTuple;
template <std::size_t... I>
struct TermSlotTuple<std::index_sequence<I...>> {
  using type = std::tuple<TermSlot<kBitOf<I>>...>;
};
using TermParameters = typename TermSlotTuple<FlightSlots>::type;

template <std::size_t... I>
void derive_slots(TermParameters& terms, const Granule& granule, const State& launch, const Air& air,
                  const Settings& settings, std::index_sequence<I...>) {
  const auto derive = [&]<std::size_t J>(std::integral_constant<std::size_t, J>) {
    if constexpr (OwnTerm<kBitOf<J>>) std::get<J>(terms).value = Term<kBitOf<J>>::derive(granule, launch, air, settings);
  };
  (derive(std::integral_constant<std::size_t, I>{}), ...);
}
// Every term's parameters, whether its effect is on or not (cheap, once per flight; validated inputs).
inline TermParameters derive_term_parameters(const Granule& granule, const State& launch, const Air& air,
                                             const Settings& settings) {
  TermParameters terms;
  derive_slots(terms, granule, launch, air, settings, FlightSlots{});
  return terms;
}

template <EffectSet E, std::size_t... I>
[[gnu::always_inline]] inline void add_slots(const TermParameters& terms, const double* y, double& ax, double& ay,
                                             double& az, std::index_sequence<I...>) {
  const auto add = [&]<std::size_t J>(std::integral_constant<std::size_t, J>) {
    if constexpr ((E & kBitOf<J>) != 0 && OwnTerm<kBitOf<J>>) {
      Term<kBitOf<J>>::accelerate(std::get<J>(terms).value, y, ax, ay, az);
    }
  };
  (add(std::integral_constant<std::size_t, I>{}), ...);
}
// Adds the accelerations of the terms of their own in E, in bit order; nothing at all when E has none.
template <EffectSet E>
[[gnu::always_inline]] inline void add_term_accelerations(const TermParameters& terms, const double* y, double& ax,
                                                          double& ay, double& az) {
  add_slots<E>(terms, y, ax, ay, az, FlightSlots{});
}

template <std::size_t... I>
double slot_rates(EffectSet effects, const TermParameters& terms, const State& launch, std::index_sequence<I...>) {
  double rate_per_s = 0.0;
  const auto rate = [&]<std::size_t J>(std::integral_constant<std::size_t, J>) {
    if constexpr (OwnTerm<kBitOf<J>>) {
      if ((effects & kBitOf<J>) != 0) {
        rate_per_s = std::max(rate_per_s, Term<kBitOf<J>>::rate_per_s(std::get<J>(terms).value, launch));
      }
    }
  };
  (rate(std::integral_constant<std::size_t, I>{}), ...);
  return rate_per_s;
}
// The stiffest rate of the terms of their own in `effects` (0 when there are none).
inline double term_rate_per_s(EffectSet effects, const TermParameters& terms, const State& launch) {
  return slot_rates(effects, terms, launch, FlightSlots{});
}

}  // namespace spread::flight::detail
