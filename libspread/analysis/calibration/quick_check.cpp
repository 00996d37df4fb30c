#include "libspread/analysis/calibration/quick_check.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace spread::calibration {

TrayCsvOptions quick_check_csv_options() {
  TrayCsvOptions options;
  options.minimum_trays = kQuickCheckMinimumTrays;
  options.centre_line_grid = false;
  return options;
}

const char* to_string(QuickCheckVerdict verdict) {
  switch (verdict) {
    case QuickCheckVerdict::kMeetsTarget: return "meets_target";
    case QuickCheckVerdict::kFailsTarget: return "fails_target";
    case QuickCheckVerdict::kUndecided: return "undecided";
  }
  return "?";
}

QuickCheck quick_check(const TrayTest& test, double cv_target, double confidence) {
  if (!(cv_target > 0.0 && cv_target <= 1.0)) throw std::invalid_argument("quick check: the CV target must be in (0, 100] %");
  QuickCheck q;
  q.cv_target = cv_target;
  double sum = 0.0;
  for (std::size_t k = 0; k < test.mass_kg.size(); ++k) {
    if (test.missing[k]) continue;
    sum += test.mass_kg[k];
    ++q.trays;
  }
  if (q.trays < kQuickCheckMinimumTrays) {
    throw std::invalid_argument("quick check: " + std::to_string(q.trays) + " tray(s) read; need at least " +
                                std::to_string(kQuickCheckMinimumTrays));
  }
  q.mean_kg = sum / q.trays;
  if (!(q.mean_kg > 0.0)) throw std::invalid_argument("quick check: no mass in any tray");
  double squares = 0.0;
  for (std::size_t k = 0; k < test.mass_kg.size(); ++k) {
    if (!test.missing[k]) squares += (test.mass_kg[k] - q.mean_kg) * (test.mass_kg[k] - q.mean_kg);
  }
  q.sd_kg = std::sqrt(squares / (q.trays - 1));
  q.cv = q.sd_kg / q.mean_kg;
  q.interval = cv_interval(q.cv, q.trays, confidence);
  q.verdict = q.interval.high <= cv_target ? QuickCheckVerdict::kMeetsTarget
              : q.interval.low > cv_target ? QuickCheckVerdict::kFailsTarget
                                           : QuickCheckVerdict::kUndecided;
  return q;
}

}  // namespace spread::calibration
