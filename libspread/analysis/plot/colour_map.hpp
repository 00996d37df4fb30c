#pragma once
// Perceptually ordered colour map for heat maps (dark blue → green → yellow, in the manner of
// viridis; a few anchor colours interpolated linearly), t in [0, 1].
#include "libspread/analysis/plot/axes.hpp"

namespace spread::plot::detail {

Rgb colour_at(double t);

}  // namespace spread::plot::detail
