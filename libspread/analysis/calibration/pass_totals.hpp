#pragma once
// The passes of one tray test carry alike. Each pass drives the same setting over the same trays, so
// their totals differ only by the forward speed and flow the technician holds steady (a few per cent)
// and by the trays' own scatter (pass_scatter.hpp: 0.3 % of a pass per tray over the example's 72 trays,
// about 3 % of its total). The scatter itself cannot see a pass that is off as a whole: it compares
// passes normalised to their own totals, so a pass typed in kilograms under a `_g` header — a thousand
// times too light — leaves the CVs almost as they were while the total and the rate are a third wrong.
// A pass more than kPassTotalFactor away from the others' median is therefore refused before any
// arithmetic, naming the pass and, near a factor of 1000, the unit it was likely typed in.
#include <string>
#include <vector>

#include "libspread/analysis/calibration/tray_csv.hpp"

namespace spread::calibration {

// A factor of two between passes of one setting is far beyond speed, flow and scatter together (≤ 10 %
// in a test worth a CV), yet well short of the factor of 1000 of a unit slip.
inline constexpr double kPassTotalFactor = 2.0;

// The total of each pass over the trays read in every pass, kg (a tray missing in one pass would
// otherwise lower that pass alone).
std::vector<double> pass_totals_kg(const TrayTest& test);

// "" when the passes agree; otherwise the refusal naming the pass. `kg_per_unit` is each mass column's
// unit as read (1 for `_kg`, 1e-3 for `_g`), for the likely unit.
std::string pass_totals_problem(const TrayTest& test, const std::vector<double>& kg_per_unit);

}  // namespace spread::calibration
