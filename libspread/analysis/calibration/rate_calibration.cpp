#include "libspread/analysis/calibration/rate_calibration.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace spread::calibration {
namespace {

void require_positive(double value, const char* name) {
  if (!std::isfinite(value) || !(value > 0.0)) {
    throw std::invalid_argument(std::string(name) + " must be a finite number > 0, got " + std::to_string(value));
  }
}

void require_finite(double value, const char* name) {
  if (!std::isfinite(value)) throw std::invalid_argument(std::string(name) + " must be finite");
}

// 1 ha = 10 000 m², 1 km/h = 1/3.6 m/s: rate·W·v/3.6 kg/(ha·s)·m² → /10 000 → /36 000.
constexpr double kRateUnitsDivisor = 36000.0;

}  // namespace

double catch_mass_flow_kg_s(const CatchTest& test) {
  require_positive(test.mass_kg, "catch mass (kg)");
  require_positive(test.duration_s, "catch duration (s)");
  return test.mass_kg / test.duration_s;
}

MeteringModel metering_from_catch(const CatchTest& test) {
  require_positive(test.gate_opening, "gate opening");
  return {catch_mass_flow_kg_s(test) / test.gate_opening, 0.0};
}

MeteringModel metering_from_two_catches(const CatchTest& first, const CatchTest& second) {
  require_finite(first.gate_opening, "first gate opening");
  require_finite(second.gate_opening, "second gate opening");
  const double q1 = catch_mass_flow_kg_s(first);
  const double q2 = catch_mass_flow_kg_s(second);
  const double d_opening = second.gate_opening - first.gate_opening;
  if (d_opening == 0.0) throw std::invalid_argument("the two catches are at the same gate opening: cannot fit a line");
  const double factor = (q2 - q1) / d_opening;
  if (!(factor > 0.0)) {
    throw std::invalid_argument("the mass flow does not grow with the gate opening between the two catches "
                                "(check the masses, times and openings)");
  }
  // Q1 = f (o1 − o0)  →  o0 = o1 − Q1 / f.
  return {factor, first.gate_opening - q1 / factor};
}

double mass_flow_at_opening_kg_s(const MeteringModel& model, double gate_opening) {
  require_positive(model.flow_factor_kg_s_per_unit, "flow factor");
  require_finite(gate_opening, "gate opening");
  return gate_opening <= model.zero_opening ? 0.0 : model.flow_factor_kg_s_per_unit * (gate_opening - model.zero_opening);
}

double gate_opening_for_mass_flow(const MeteringModel& model, double mass_flow_kg_s) {
  require_positive(model.flow_factor_kg_s_per_unit, "flow factor");
  require_positive(mass_flow_kg_s, "mass flow (kg/s)");
  return model.zero_opening + mass_flow_kg_s / model.flow_factor_kg_s_per_unit;
}

double required_mass_flow_kg_s(double rate_kg_ha, double working_width_m, double speed_km_h) {
  require_positive(rate_kg_ha, "rate (kg/ha)");
  require_positive(working_width_m, "working width (m)");
  require_positive(speed_km_h, "speed (km/h)");
  return rate_kg_ha * working_width_m * speed_km_h / kRateUnitsDivisor;
}

double application_rate_kg_ha(double mass_flow_kg_s, double working_width_m, double speed_km_h) {
  require_finite(mass_flow_kg_s, "mass flow (kg/s)");
  if (mass_flow_kg_s < 0.0) throw std::invalid_argument("mass flow (kg/s) must be >= 0");
  require_positive(working_width_m, "working width (m)");
  require_positive(speed_km_h, "speed (km/h)");
  return mass_flow_kg_s * kRateUnitsDivisor / (working_width_m * speed_km_h);
}

RateSetting rate_setting(const MeteringModel& model, double target_rate_kg_ha, double working_width_m,
                         double speed_km_h, double current_gate_opening) {
  RateSetting s;
  s.required_mass_flow_kg_s = required_mass_flow_kg_s(target_rate_kg_ha, working_width_m, speed_km_h);
  s.required_gate_opening = gate_opening_for_mass_flow(model, s.required_mass_flow_kg_s);
  s.current_gate_opening = current_gate_opening;
  s.current_mass_flow_kg_s = mass_flow_at_opening_kg_s(model, current_gate_opening);
  s.current_rate_kg_ha = application_rate_kg_ha(s.current_mass_flow_kg_s, working_width_m, speed_km_h);
  s.rate_error = (s.current_rate_kg_ha - target_rate_kg_ha) / target_rate_kg_ha;
  return s;
}

}  // namespace spread::calibration
