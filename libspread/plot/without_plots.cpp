// The drawing entry points of a build configured with SPREAD_WITH_PLOTS=OFF (no cairo): each throws the
// one message that says why, so `spread plot`, `--report` and the scene outputs fail clearly and alike.
#include <stdexcept>
#include <string>

#include "libspread/plot/plot.hpp"
#include "libspread/plot/report_pdf.hpp"

namespace spread::plot {
namespace {

[[noreturn]] void refuse(const std::string& path) {
  throw std::runtime_error("cannot write " + path + ": " + kWithoutPlots);
}

}  // namespace

void write_ground_pattern_png(const metrics::GroundPattern&, const std::string& path, const std::string&,
                              const metrics::MachineLayout&, MassUnits) {
  refuse(path);
}

void write_transverse_png(std::span<const double>, const metrics::TrayLayout&, const std::string& path,
                          const std::string&, const TransverseOptions&) {
  refuse(path);
}

void write_cv_curve_png(std::span<const double>, std::span<const double>, std::span<const double>, double,
                        const std::string& path, const std::string&) {
  refuse(path);
}

void write_report_pdf(const std::string& path, const PatternReport*, const TablePage*) { refuse(path); }

}  // namespace spread::plot
