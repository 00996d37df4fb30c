// The drawing entry points of a build configured with SPREAD_WITH_PLOTS=OFF (no cairo): each throws the
// one message that says why, so `spread plot`, `--report` and the scene outputs fail clearly and alike.
#include <stdexcept>
#include <string>

#include "libspread/analysis/plot/plot.hpp"
#include "libspread/analysis/plot/report_pdf.hpp"

namespace spread::plot {
namespace {

[[noreturn]] void refuse(const std::string& path) {
  throw std::runtime_error("cannot write " + path + ": " + kWithoutPlots);
}

}  // namespace
}  // namespace spread::plot

// Qualified definitions: one whose signature drifts from plot.hpp or report_pdf.hpp is a compile error here
// (C++ [dcl.meaning]: a qualified name must name an earlier declaration), not a link error in a later target.
void spread::plot::write_ground_pattern_png(const metrics::GroundPattern&, const std::string& path, const std::string&,
                                            const metrics::MachineLayout&, MassUnits) {
  refuse(path);
}

void spread::plot::write_transverse_png(std::span<const double>, const metrics::TrayLayout&, const std::string& path,
                                        const std::string&, const TransverseOptions&) {
  refuse(path);
}

void spread::plot::write_cv_curve_png(std::span<const double>, std::span<const double>, std::span<const double>,
                                      double, const std::string& path, const std::string&, const CvCurveOptions&) {
  refuse(path);
}

void spread::plot::write_report_pdf(const std::string& path, const PatternReport*, const TablePage*) { refuse(path); }
