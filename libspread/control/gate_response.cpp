#include "libspread/control/gate_response.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace spread::firmware {

GateResponse::GateResponse(double full_travel_s) : full_travel_s_(full_travel_s) {
  if (!(full_travel_s >= 0.0) || !std::isfinite(full_travel_s)) {
    throw std::invalid_argument("GateResponse: full travel time must be a finite value >= 0 s, got " +
                                std::to_string(full_travel_s));
  }
}

void GateResponse::step(double target_fraction, double dt_s) {
  if (!(dt_s > 0.0)) return;
  if (full_travel_s_ == 0.0) {
    opening_ = target_fraction;
    return;
  }
  const double most = dt_s / full_travel_s_;
  opening_ += std::clamp(target_fraction - opening_, -most, most);
}

}  // namespace spread::firmware
