// Public entry point: validate, derive the parameters once, and dispatch through a table to the
// integrator instantiated for exactly this effect combination (docs/design.md §7: "an effect that is off costs
// nothing").
#include <array>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>

#include "libspread/physics/flight/dormand_prince.hpp"
#include "libspread/physics/flight/dormand_prince_lanes.hpp"
#include "libspread/physics/flight/fly_unchecked.hpp"
#include "libspread/physics/flight/rk4.hpp"
#include "libspread/physics/flight/validation.hpp"

namespace spread::flight {
namespace detail {
namespace {

using FlyFunction = Landing (*)(const FlightParameters&, const State&, double, const Settings&,
                                const StepObserver&);

template <std::size_t... I>
constexpr std::array<FlyFunction, sizeof...(I)> make_rk4_table(std::index_sequence<I...>) {
  return {&fly_rk4<static_cast<EffectSet>(I)>...};
}
template <std::size_t... I>
constexpr std::array<FlyFunction, sizeof...(I)> make_dormand_prince_table(std::index_sequence<I...>) {
  return {&fly_dormand_prince<static_cast<EffectSet>(I)>...};
}

constexpr std::size_t kCombinations = static_cast<std::size_t>(kAllEffects) + 1;  // 2^(flight rows)
constexpr auto kRk4Table = make_rk4_table(std::make_index_sequence<kCombinations>{});
constexpr auto kDormandPrinceTable = make_dormand_prince_table(std::make_index_sequence<kCombinations>{});

}  // namespace

EffectSet effects_that_act(EffectSet effects, const State& launch) {
  // A granule launched without spin keeps none: Eq. 34 (dω/dt ∝ −ω) leaves ω = 0, and the Magnus force
  // (Eq. 28) is proportional to ω. Both would be evaluated as zeros; the instantiation without them is
  // the same flight for less work.
  if (launch.spin_rad_s.x() == 0.0 && launch.spin_rad_s.y() == 0.0 && launch.spin_rad_s.z() == 0.0) {
    effects &= ~(kMagnus | kSpinDecay);
  }
  return effects & kAllEffects;
}

Landing fly_unchecked(const Granule& granule, const State& launch, double ground_z_m, const Air& air,
                      EffectSet effects, const Settings& settings, const StepObserver& observer) {
  // A launch on the ground that is not rising has already landed (the crossing test needs z > ground
  // at the start of a step).
  if (launch.position_m.z() == ground_z_m && launch.velocity_m_s.z() <= 0.0) {
    Landing landing;
    landing.state = launch;
    landing.landed = true;
    if (observer.on_step != nullptr) observer.on_step(observer.context, 0.0, launch);
    return landing;
  }
  if (observer.on_step != nullptr) observer.on_step(observer.context, 0.0, launch);
  const FlightParameters params = make_flight_parameters(granule, launch, air, settings);
  const auto& table = settings.scheme == Scheme::kRk4 ? kRk4Table : kDormandPrinceTable;
  return table[effects_that_act(effects, launch)](params, launch, ground_z_m, settings, observer);
}

}  // namespace detail

Landing fly_to_ground(const Granule& granule, const State& launch, double ground_z_m, const Air& air,
                      EffectSet effects, const Settings& settings, const StepObserver& observer) {
  detail::validate_shared_inputs(ground_z_m, air, effects, settings);
  detail::validate_flight_inputs(granule, launch, ground_z_m, -1);
  detail::validate_rk4_step(granule, launch, ground_z_m, air, effects, settings, -1);
  return detail::fly_unchecked(granule, launch, ground_z_m, air, effects, settings, observer);
}

void fly_many(std::span<const Granule> granules, std::span<const State> launches, double ground_z_m,
              const Air& air, EffectSet effects, const Settings& settings, std::span<Landing> out) {
  const std::size_t count = launches.size();
  if ((granules.size() != count && granules.size() != 1) || out.size() != count) {
    throw std::invalid_argument("fly_many: granules.size() must be 1 or launches.size(), out.size() launches.size()");
  }
  detail::validate_shared_inputs(ground_z_m, air, effects, settings);
  for (std::size_t i = 0; i < count; ++i) {
    const Granule& granule = granules.size() == 1 ? granules[0] : granules[i];
    detail::validate_flight_inputs(granule, launches[i], ground_z_m, static_cast<long>(i));
    detail::validate_rk4_step(granule, launches[i], ground_z_m, air, effects, settings, static_cast<long>(i));
  }
  if (settings.scheme == Scheme::kDormandPrince45) {
    switch (effects & kAllEffects) {
      case 0: return detail::fly_dormand_prince_lanes<0>(granules, launches, ground_z_m, air, settings, out);
      case kDrag: return detail::fly_dormand_prince_lanes<kDrag>(granules, launches, ground_z_m, air, settings, out);
      case kWind: return detail::fly_dormand_prince_lanes<kWind>(granules, launches, ground_z_m, air, settings, out);
      case kDrag | kWind:
        return detail::fly_dormand_prince_lanes<kDrag | kWind>(granules, launches, ground_z_m, air, settings, out);
      default: break;
    }
  }
  const StepObserver no_observer{};
  for (std::size_t i = 0; i < count; ++i) {
    const Granule& granule = granules.size() == 1 ? granules[0] : granules[i];
    out[i] = detail::fly_unchecked(granule, launches[i], ground_z_m, air, effects, settings, no_observer);
  }
}

Landing fly_to_ground(const Granule& granule, const State& launch, double ground_z_m, const Air& air,
                      EffectSet effects, const Settings& settings) {
  return fly_to_ground(granule, launch, ground_z_m, air, effects, settings, StepObserver{});
}

}  // namespace spread::flight
