#include "libspread/physics/flight/lift_coefficient.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace spread::flight {

double lift_coefficient(LiftModel model, double spin_ratio, double reynolds) {
  if (!std::isfinite(spin_ratio) || spin_ratio < 0.0) {
    throw std::invalid_argument("lift_coefficient: spin_ratio must be finite and >= 0, got " +
                                std::to_string(spin_ratio));
  }
  if (!std::isfinite(reynolds) || reynolds < 0.0) {
    throw std::invalid_argument("lift_coefficient: reynolds must be finite and >= 0, got " +
                                std::to_string(reynolds));
  }
  return detail::lift_coefficient_of(model, spin_ratio, reynolds);
}

}  // namespace spread::flight
