#pragma once
// A CV as a page, the terminal and a legend print it: one decimal, but never a value above the target
// rounded onto it. 15.05 % against a 15 % target is "15.05 %", not "15.0 %" — a reader compares the
// printed number with the target, and "15.0 %" reads as within it while the verdict says above.
#include <cmath>
#include <cstdio>
#include <string>

namespace spread::plot {

// `cv` and `target` fractions (a NaN target: plain one decimal). NaN cv: "none"; +inf: "empty".
inline std::string cv_percent_text(double cv, double target) {
  if (std::isnan(cv)) return "none";
  if (std::isinf(cv)) return "empty";
  char text[48];
  for (int decimals = 1; decimals <= 4; ++decimals) {
    std::snprintf(text, sizeof text, "%.*f %%", decimals, 100.0 * cv);
    const double shown = std::strtod(text, nullptr);
    // Above the target, the shown value must be above the target's too.
    if (!(cv > target) || shown > 100.0 * target + 1e-9) break;
  }
  return text;
}

}  // namespace spread::plot
