// write_regime_map_png in a build configured with SPREAD_WITH_PLOTS=OFF: refuses with the plot module's
// message, so `spread drum --map` says why without a build switch of its own.
#include <stdexcept>

#include "libspread/physics/drum/regime_map_plot.hpp"
#include "libspread/analysis/plot/plot.hpp"

namespace spread::drum {

void write_regime_map_png(const std::vector<RegimeEvidence>&, const std::string& path, const std::string&) {
  throw std::runtime_error("cannot write " + path + ": " + plot::kWithoutPlots);
}

}  // namespace spread::drum
