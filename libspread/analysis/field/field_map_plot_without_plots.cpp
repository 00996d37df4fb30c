// write_field_map_png and write_field_maps_png in a build configured with SPREAD_WITH_PLOTS=OFF: the field's numbers and its grid
// CSV need no cairo; the map refuses with the plot module's message.
#include <stdexcept>

#include "libspread/analysis/field/field_map_plot.hpp"
#include "libspread/analysis/plot/plot.hpp"

namespace spread::field {

void write_field_map_png(const std::string& path, const RateGrid&, const Boundary&, const std::vector<Pass>&, double,
                         const std::string&) {
  throw std::runtime_error("cannot write " + path + ": " + plot::kWithoutPlots);
}

void write_field_maps_png(const std::string& path, const std::vector<MapPanel>&, const Boundary&, double,
                          const std::string&) {
  throw std::runtime_error("cannot write " + path + ": " + plot::kWithoutPlots);
}

}  // namespace spread::field
