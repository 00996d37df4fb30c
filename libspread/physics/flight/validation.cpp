#include "libspread/physics/flight/validation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "libspread/physics/flight/drag_coefficient.hpp"
#include "libspread/physics/flight/flight_parameters.hpp"

namespace spread::flight::detail {
namespace {

// Field names are C strings and the message is built only on failure: validating a good flight does
// not allocate (fly_to_ground promises no heap allocation).
struct Where {
  long index;  // batch element, or -1
};

[[noreturn]] void fail(Where where, const char* field, const char* suffix, const char* rule, double value) {
  std::ostringstream message;
  message.precision(17);
  message << "fly_to_ground: ";
  if (where.index >= 0) message << "element " << where.index << ": ";
  message << field << suffix << " must be " << rule << ", got " << value;
  throw std::invalid_argument(message.str());
}

inline void require_finite(Where w, const char* field, double value, const char* suffix = "") {
  if (!std::isfinite(value)) fail(w, field, suffix, "finite", value);
}
inline void require_positive(Where w, const char* field, double value) {
  if (!std::isfinite(value) || value <= 0.0) fail(w, field, "", "finite and > 0", value);
}
inline void require_non_negative(Where w, const char* field, double value) {
  if (!std::isfinite(value) || value < 0.0) fail(w, field, "", "finite and >= 0", value);
}
inline void require_finite_vector(Where w, const char* field, const Vec3& v) {
  require_finite(w, field, v.x(), ".x");
  require_finite(w, field, v.y(), ".y");
  require_finite(w, field, v.z(), ".z");
}

}  // namespace

void validate_shared_inputs(double ground_z_m, const Air& air, EffectSet effects, const Settings& settings) {
  const Where w{-1};
  require_finite(w, "ground_z_m", ground_z_m);
  require_non_negative(w, "air.density_kg_m3", air.density_kg_m3);
  require_positive(w, "air.viscosity_pa_s", air.viscosity_pa_s);
  require_finite_vector(w, "air.wind_m_s", air.wind_m_s);
  if ((effects & ~kAllEffects) != 0) {
    std::ostringstream message;
    message << "fly_to_ground: effects has unknown bits 0x" << std::hex << (effects & ~kAllEffects)
            << " (known: " << effect::names_of(kAllEffects) << ")";
    throw std::invalid_argument(message.str());
  }
  require_positive(w, "settings.dt_s", settings.dt_s);
  require_positive(w, "settings.rel_tol", settings.rel_tol);
  require_non_negative(w, "settings.abs_tol", settings.abs_tol);
  require_positive(w, "settings.max_time_s", settings.max_time_s);
  if (settings.max_steps <= 0) fail(w, "settings.max_steps", "", "> 0", settings.max_steps);
  require_positive(w, "settings.gravity_m_s2", settings.gravity_m_s2);
  const auto lift = static_cast<unsigned>(settings.lift);
  if (lift > static_cast<unsigned>(LiftModel::kOesterleBuiDinhAsPrinted)) {
    fail(w, "settings.lift", "", "a LiftModel enumerator", lift);
  }
  const auto scheme = static_cast<unsigned>(settings.scheme);
  if (scheme > static_cast<unsigned>(Scheme::kDormandPrince45)) {
    fail(w, "settings.scheme", "", "a Scheme enumerator", scheme);
  }
}

void validate_flight_inputs(const Granule& granule, const State& launch, double ground_z_m, long index) {
  const Where w{index};
  require_positive(w, "granule.diameter_m", granule.diameter_m);
  require_positive(w, "granule.density_kg_m3", granule.density_kg_m3);
  require_finite_vector(w, "launch.position_m", launch.position_m);
  require_finite_vector(w, "launch.velocity_m_s", launch.velocity_m_s);
  require_finite_vector(w, "launch.spin_rad_s", launch.spin_rad_s);
  if (launch.position_m.z() < ground_z_m) {
    std::ostringstream message;
    message.precision(17);
    message << "fly_to_ground: ";
    if (index >= 0) message << "element " << index << ": ";
    message << "launch.position_m.z (" << launch.position_m.z() << ") is below ground_z_m (" << ground_z_m << ")";
    throw std::invalid_argument(message.str());
  }
}

void validate_rk4_step(const Granule& granule, const State& launch, double ground_z_m, const Air& air,
                       EffectSet effects, const Settings& settings, long index) {
  if (settings.scheme != Scheme::kRk4) return;
  const double bound_s = rk4_stable_step_bound_s(granule, launch, ground_z_m, air, effects, settings);
  if (!(settings.dt_s > bound_s)) return;
  std::ostringstream message;
  message.precision(6);
  message << "fly_to_ground: ";
  if (index >= 0) message << "element " << index << ": ";
  message << "settings.dt_s = " << settings.dt_s << " s is above RK4's stable bound " << bound_s
          << " s for this granule (diameter " << granule.diameter_m << " m, density " << granule.density_kg_m3
          << " kg/m3: relaxation time tau = " << bound_s / kRk4StabilityLimit << " s, RK4 needs dt <= "
          << kRk4StabilityLimit << " tau); use a smaller step or Scheme::kDormandPrince45";
  throw std::invalid_argument(message.str());
}

}  // namespace spread::flight::detail

namespace spread::flight {

double rk4_stable_step_bound_s(const Granule& granule, const State& launch, double ground_z_m, const Air& air,
                               EffectSet effects, const Settings& settings) {
  const detail::FlightParameters p = detail::make_flight_parameters(granule, launch, air, settings);
  double rate_per_s = 0.0;
  if ((effects & kDrag) != 0) {
    const bool windy = (effects & kWind) != 0;
    const Vec3 relative = windy ? Vec3(launch.velocity_m_s - air.wind_m_s) : launch.velocity_m_s;
    double speed_sq = relative.squaredNorm() + 2.0 * settings.gravity_m_s2 * std::max(0.0, launch.position_m.z() - ground_z_m);
    if (windy) speed_sq += 2.0 * settings.gravity_m_s2 * std::abs(air.wind_m_s.z()) * settings.max_time_s;
    const double reynolds = p.reynolds_per_speed_s_m * std::sqrt(speed_sq);
    rate_per_s = std::max(rate_per_s, p.drag_rate_per_s * detail::drag_slope_factor(reynolds));
  }
  if ((effects & kSpinDecay) != 0) {
    // dω/dt = -R α(Re_s) ω with α = 2.01 (1 + 0.201 sqrt(Re_s)), Re_s ∝ |ω|: slope R (α + Re_s α').
    const double spin_reynolds = p.spin_reynolds_per_rad_s * launch.spin_rad_s.norm();
    rate_per_s = std::max(rate_per_s, p.spin_decay_rate_per_s * 2.01 * (1.0 + 1.5 * 0.201 * std::sqrt(spin_reynolds)));
  }
  rate_per_s = std::max(rate_per_s, detail::term_rate_per_s(effects, p.terms, launch));
  if (!(rate_per_s > 0.0)) return std::numeric_limits<double>::infinity();
  return kRk4StabilityLimit / rate_per_s;
}

}  // namespace spread::flight
