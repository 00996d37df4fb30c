#include "libspread/control/ecu_parameters.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace spread::firmware {
namespace {

void require(bool ok, const char* field, const std::string& what) {
  if (!ok) throw std::invalid_argument(std::string("EcuParameters.") + field + ": " + what);
}

bool positive_finite(double v) { return std::isfinite(v) && v > 0.0; }

}  // namespace

void validate(const EcuParameters& p) {
  require(positive_finite(p.disc_time_constant_s), "disc_time_constant_s", "must be > 0 s");
  require(std::isfinite(p.gate_full_travel_s) && p.gate_full_travel_s >= 0.0, "gate_full_travel_s", "must be >= 0 s");
  require(positive_finite(p.rpm_max), "rpm_max", "must be > 0 r/min");
  require(std::isfinite(p.auto_rpm_min) && p.auto_rpm_min >= 0.0, "auto_rpm_min", "must be >= 0 r/min");
  require(std::isfinite(p.auto_rpm_max) && p.auto_rpm_max > p.auto_rpm_min && p.auto_rpm_max <= p.rpm_max,
          "auto_rpm_max", "must lie in (auto_rpm_min, rpm_max]");
  require(positive_finite(p.rate_max_kg_ha), "rate_max_kg_ha", "must be > 0 kg/ha");
  require(positive_finite(p.width_max_m), "width_max_m", "must be > 0 m");
  require(positive_finite(p.speed_max_m_s), "speed_max_m_s", "must be > 0 m/s");
  require(positive_finite(p.wind_max_m_s), "wind_max_m_s", "must be > 0 m/s");
  require(p.section_count >= 1 && p.section_count <= kMaxSections, "section_count",
          "must be 1.." + std::to_string(kMaxSections) + ", got " + std::to_string(p.section_count));
  require(p.disc_count == 1 || p.disc_count == 2, "disc_count", "must be 1 or 2, got " + std::to_string(p.disc_count));
  require(std::isfinite(p.section_max_beyond_percent) && p.section_max_beyond_percent > 0.0 &&
              p.section_max_beyond_percent <= 100.0,
          "section_max_beyond_percent", "must lie in (0, 100] %");
  require(std::isfinite(p.section_on_rate_percent) && p.section_on_rate_percent > 0.0 &&
              p.section_on_rate_percent <= 100.0,
          "section_on_rate_percent", "must lie in (0, 100] %");
  require(p.fault_hold >= Nanoseconds::zero(), "fault_hold", "must be >= 0");
  require(p.command_timeout >= Nanoseconds::zero(), "command_timeout", "must be >= 0 (0 = off)");
  require(p.task_controller_timeout > Nanoseconds::zero(), "task_controller_timeout", "must be > 0");
  require(std::isfinite(p.spreading_rpm_min) && p.spreading_rpm_min >= 0.0, "spreading_rpm_min",
          "must be >= 0 r/min");
  require(std::isfinite(p.disc_speed_tolerance) && p.disc_speed_tolerance > 0.0 && p.disc_speed_tolerance < 1.0,
          "disc_speed_tolerance", "must lie in (0, 1)");
  require(p.sequence_max_jump >= 1, "sequence_max_jump", "must be >= 1");
  require(std::isfinite(p.reprediction_rpm_step) && p.reprediction_rpm_step >= 0.0, "reprediction_rpm_step",
          "must be >= 0 r/min");
  require(p.sequence_reorder_window >= 0, "sequence_reorder_window", "must be >= 0");
}

}  // namespace spread::firmware
