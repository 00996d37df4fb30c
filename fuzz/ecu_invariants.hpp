#pragma once
// What must hold for the simulated ECU whatever arrived on its links: no NaN or infinity in its commanded
// or derived state (predicted fields may be NaN = "no prediction", by contract), set-points inside the
// configured ranges, sections inside the installed count.
#include <cmath>
#include <string>

#include "libspread/control/ecu.hpp"
#include "fuzz/fuzz_input.hpp"

namespace spread::fuzz {

// `after_step`: the status was taken right after a loop step. The fail-safe rules are evaluated at each
// step; between steps a set-value may already have moved a set-point the last step's metering was based on.
inline void check_ecu_status(const char* harness, const firmware::Ecu& ecu, bool after_step = true) {
  const firmware::EcuStatus s = ecu.status();
  const firmware::EcuParameters& p = ecu.parameters();
  const auto finite_in = [&](double value, double low, double high, const char* what) {
    if (!std::isfinite(value) || value < low || value > high) {
      fail(harness, std::string(what) + " = " + std::to_string(value) + " outside [" + std::to_string(low) + ", " +
                        std::to_string(high) + "]");
    }
  };
  finite_in(s.rate_setpoint_kg_ha, 0.0, p.rate_max_kg_ha, "rate_setpoint_kg_ha");
  finite_in(s.width_setpoint_m, 0.0, p.width_max_m, "width_setpoint_m");
  finite_in(s.ground_speed_m_s, 0.0, p.speed_max_m_s, "ground_speed_m_s");
  finite_in(s.rpm_target, 0.0, p.rpm_max, "rpm_target");
  // The disc follows its target with a first-order lag: it never overshoots the largest set-point.
  finite_in(s.rpm_actual, 0.0, p.rpm_max, "rpm_actual");
  finite_in(s.rate_actual_kg_ha, 0.0, 1e9, "rate_actual_kg_ha");
  finite_in(s.width_actual_m, 0.0, 1e6, "width_actual_m");
  finite_in(s.mass_flow_kg_s, 0.0, 1e9, "mass_flow_kg_s");
  if (s.section_count < 1 || s.section_count > p.section_count) {
    fail(harness, "section_count " + std::to_string(s.section_count) + " beyond the installed " +
                      std::to_string(p.section_count));
  }
  // Fail-safe: metering only with the master switch on, a section open, the disc at its spreading speed
  // and the tractor moving forward at a valid speed.
  if (s.work_state_actual && after_step) {
    if (!s.work_state_setpoint) fail(harness, "metering with the work state set-point off");
    if (s.section_mask == 0 || !(s.width_actual_m > 0.0)) fail(harness, "metering with no open section width");
    if (!(s.ground_speed_m_s > 0.0)) fail(harness, "metering without a valid ground speed");
    if (!(s.rpm_target >= p.spreading_rpm_min) ||
        !(std::abs(s.rpm_actual - s.rpm_target) <= p.disc_speed_tolerance * s.rpm_target)) {
      fail(harness, "metering with the disc at " + std::to_string(s.rpm_actual) + " r/min for a target of " +
                        std::to_string(s.rpm_target));
    }
  } else if (!s.work_state_actual && (s.mass_flow_kg_s != 0.0 || s.rate_actual_kg_ha != 0.0)) {
    fail(harness, "mass flow or actual rate while not metering");
  }
  if (s.section_count < firmware::kMaxSections && (s.section_mask >> s.section_count) != 0) {
    fail(harness, "section_mask has bits above section_count");
  }
}

}  // namespace spread::fuzz
