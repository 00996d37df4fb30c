#include "libspread/control/disc_speed_model.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace spread::firmware {

DiscSpeedModel::DiscSpeedModel(double time_constant_s, double initial_rpm)
    : time_constant_s_(time_constant_s), rpm_(initial_rpm) {
  if (!(time_constant_s > 0.0) || !std::isfinite(time_constant_s)) {
    throw std::invalid_argument("DiscSpeedModel: disc time constant must be a finite value > 0 s, got " +
                                std::to_string(time_constant_s));
  }
  if (!std::isfinite(initial_rpm)) throw std::invalid_argument("DiscSpeedModel: initial rpm must be finite");
}

void DiscSpeedModel::step(double setpoint_rpm, double dt_s) {
  if (!(dt_s > 0.0)) return;
  const double blend = -std::expm1(-dt_s / time_constant_s_);  // 1 - exp(-dt/tau), accurate for small dt
  rpm_ += (setpoint_rpm - rpm_) * blend;
}

}  // namespace spread::firmware
