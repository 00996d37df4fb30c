#include "libspread/physics/flight/spin_decay.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "libspread/physics/flight/flight.hpp"

namespace spread::flight {

double spin_decay_alpha(double spin_reynolds) {
  if (!std::isfinite(spin_reynolds) || spin_reynolds < 0.0) {
    throw std::invalid_argument("spin_decay_alpha: spin_reynolds must be finite and >= 0, got " +
                                std::to_string(spin_reynolds));
  }
  return detail::spin_decay_alpha_of(spin_reynolds);
}

}  // namespace spread::flight
