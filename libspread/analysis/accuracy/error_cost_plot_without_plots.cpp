// write_error_cost_plot in a build configured with SPREAD_WITH_PLOTS=OFF: the study's CSV files and report
// text need no cairo; its PNG plots refuse with the plot module's message.
#include <stdexcept>

#include "libspread/analysis/accuracy/error_cost_plot.hpp"
#include "libspread/analysis/plot/plot.hpp"

namespace spread::accuracy::detail {

void write_error_cost_plot(const Plot&, const std::string& path) {
  throw std::runtime_error("cannot write " + path + ": " + plot::kWithoutPlots);
}

}  // namespace spread::accuracy::detail
