#pragma once
// PNG of one study plot (error against cost), 900 × 600 px.
#include <string>

#include "libspread/analysis/accuracy/accuracy.hpp"

namespace spread::accuracy::detail {

// Throws std::runtime_error naming the path when it cannot be written.
void write_error_cost_plot(const Plot& plot, const std::string& path);

}  // namespace spread::accuracy::detail
