#include "libspread/physics/flight/drag_coefficient.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "libspread/physics/flight/flight.hpp"

namespace spread::flight {

double drag_coefficient(double reynolds) {
  // C_D itself diverges as Re → 0 (Stokes 24/Re); callers asking for it at Re <= 0 made a mistake.
  if (!std::isfinite(reynolds) || reynolds <= 0.0) {
    throw std::invalid_argument("drag_coefficient: reynolds must be finite and > 0, got " +
                                std::to_string(reynolds));
  }
  return detail::drag_coefficient_times_reynolds(reynolds) / reynolds;
}

}  // namespace spread::flight
