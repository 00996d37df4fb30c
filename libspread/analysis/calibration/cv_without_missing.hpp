#pragma once
// CV of a tray test with missing trays left out (docs/field-calibration.md, "Missing trays").
//
// The overlapped distribution of a bout (metrics.hpp, "Overlap on true trays") is a sum over the passes
// of the pattern shifted by whole trays, so each pattern tray lands in one bout tray per pass that
// reaches the bout. A bout tray fed by a missing pattern tray has no value: it is left out, and the CV
// is taken over the bout trays that remain, with the weights of metrics::cv_at_trays (1, or 1/2 for the
// two trays a bout edge cuts):
//     x̄ = Σ w_j P_j / Σ w_j,   s² = Σ w_j (P_j − x̄)² / (Σ w_j − 1),   CV = s / x̄.
// With no tray missing this is metrics::cv_at_trays exactly (Σ w_j = n). Counting a missing tray as 0
// instead puts a hole into every pass that crosses it: on the example tray test
// (scenes/field/tray_test_3passes.csv) its fullest tray entered as 0 moves the to-and-fro CV at 3.5 m
// from 15.1 to 32.3 %; left out, the CV is 16.1 %.
#include <vector>

#include "libspread/analysis/metrics/metrics.hpp"

namespace spread::calibration {

// CV (fraction) at a bout of `bout_tray_count` trays; `missing` has one flag per pattern tray.
// +infinity for a bout without mass (as metrics::cv_at_trays), NaN when fewer than two trays' weight
// of the bout remain measured (no spread can be estimated), 0 for a one-tray bout.
// Throws std::invalid_argument when the sizes differ from the layout.
double cv_without_missing(const std::vector<double>& tray_mass_kg, const std::vector<bool>& missing,
                          const metrics::TrayLayout& trays, int bout_tray_count, metrics::Overlap overlap);

}  // namespace spread::calibration
