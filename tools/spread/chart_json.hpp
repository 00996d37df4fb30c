#pragma once
// The numbers a report page's chart prints — the bout it overlaps, its CV and its mean per tray in the
// legend's unit — for a command's --json, from the page itself (plot/transverse_bout.hpp), so the JSON
// holds every number of the page.
#include <nlohmann/json.hpp>

#include "libspread/analysis/plot/report_pdf.hpp"

namespace spread::cli {

// {"bout_width_m", "cv_percent" (null: none), "bout_mean", "bout_mean_unit"}; null when the chart
// overlaps no bout.
nlohmann::json chart_json(const plot::PatternReport& page);

}  // namespace spread::cli
