#pragma once
// Field-side quick check (docs/field-calibration.md, "Quick check"): 4–8 trays laid across one bout
// between two tramlines, the field driven as usual on both sides, so the trays catch the overlapped
// distribution itself — no overlap is computed. CV = s / x̄ over the trays read (sample standard
// deviation), and how uncertain a CV from so few trays is: McKay's interval (cv_interval.hpp), and
// whether the CV target lies above, inside or below it.
#include "libspread/analysis/calibration/cv_interval.hpp"
#include "libspread/analysis/calibration/tray_csv.hpp"

namespace spread::calibration {

inline constexpr int kQuickCheckMinimumTrays = 4;

// The tray-file rules of a quick check: at least 4 trays read, positions on any uniform spacing.
TrayCsvOptions quick_check_csv_options();

enum class QuickCheckVerdict {
  kMeetsTarget,  // the interval's top is within the target
  kFailsTarget,  // the interval's bottom is above the target
  kUndecided,    // the target lies inside the interval: these trays cannot tell
};
const char* to_string(QuickCheckVerdict verdict);

struct QuickCheck {
  int trays = 0;            // trays read (missing ones left out)
  double mean_kg = 0.0;     // per tray, mean of the passes
  double sd_kg = 0.0;       // sample standard deviation over the trays
  double cv = 0.0;          // fraction
  CvInterval interval;
  double cv_target = 0.15;  // fraction
  QuickCheckVerdict verdict = QuickCheckVerdict::kUndecided;
};

// Throws std::invalid_argument when fewer than kQuickCheckMinimumTrays trays were read, the trays hold
// no mass, or cv_target / confidence are outside (0, 1].
QuickCheck quick_check(const TrayTest& test, double cv_target, double confidence = 0.95);

}  // namespace spread::calibration
