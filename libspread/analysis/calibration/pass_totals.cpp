#include "libspread/analysis/calibration/pass_totals.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "libspread/analysis/calibration/text_excerpt.hpp"

namespace spread::calibration {
namespace {

std::string grams(double kg) {
  char text[48];
  std::snprintf(text, sizeof text, "%.4g g", 1e3 * kg);
  return text;
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

// Near a factor of 1000 (within 3 either way): the unit the pass was likely typed in, for its column.
std::string unit_slip(double factor, double kg_per_unit) {
  if (!(std::abs(std::log10(factor) - 3.0) < std::log10(3.0) || std::abs(std::log10(factor) + 3.0) < std::log10(3.0))) {
    return {};
  }
  const bool heavy = factor > 1.0;
  const bool grams_column = kg_per_unit != 1.0;
  if (grams_column) {
    return heavy ? " — milligrams in a grams column? enter it in grams (÷ 1000)"
                 : " — kilograms in a grams column? enter it in grams (× 1000)";
  }
  return heavy ? " — grams in a kilograms column? enter it in kilograms (÷ 1000)"
               : " — tonnes in a kilograms column? enter it in kilograms (× 1000)";
}

}  // namespace

std::vector<double> pass_totals_kg(const TrayTest& test) {
  std::vector<double> totals(test.pass_mass_kg.size(), 0.0);
  for (std::size_t i = 0; i < test.position_m.size(); ++i) {
    bool in_every_pass = true;
    for (const auto& pass : test.pass_mass_kg) in_every_pass = in_every_pass && !std::isnan(pass[i]);
    if (!in_every_pass) continue;
    for (std::size_t p = 0; p < totals.size(); ++p) totals[p] += test.pass_mass_kg[p][i];
  }
  return totals;
}

std::string pass_totals_problem(const TrayTest& test, const std::vector<double>& kg_per_unit) {
  const std::vector<double> totals = pass_totals_kg(test);
  if (totals.size() < 2) return {};
  // The pass farthest from the others' median, by ratio. With two passes neither is "the others": the
  // lighter of a grams test (kilograms typed) or the heavier of a kilograms test (grams typed) is named.
  std::size_t worst = 0;
  double worst_factor = 1.0, worst_reference = 0.0;
  for (std::size_t p = 0; p < totals.size(); ++p) {
    std::vector<double> others;
    for (std::size_t q = 0; q < totals.size(); ++q) {
      if (q != p) others.push_back(totals[q]);
    }
    const double reference = median(others);
    if (!(reference > 0.0) || !(totals[p] > 0.0)) {
      // A pass with nothing in the trays read while the others hold mass (or the reverse).
      if (reference > 0.0 || totals[p] > 0.0) {
        worst = p;
        worst_factor = totals[p] > 0.0 ? INFINITY : 0.0;
        worst_reference = reference;
        break;
      }
      continue;
    }
    const double factor = totals[p] / reference;
    const bool farther = std::abs(std::log(factor)) > std::abs(std::log(worst_factor)) + 1e-12;
    const bool two_pass_tie = totals.size() == 2 && std::abs(std::log(factor)) == std::abs(std::log(worst_factor)) &&
                              ((kg_per_unit[p] != 1.0) == (factor < 1.0));
    if (farther || two_pass_tie) {
      worst = p;
      worst_factor = factor;
      worst_reference = reference;
    }
  }
  if (worst_factor <= kPassTotalFactor && worst_factor >= 1.0 / kPassTotalFactor) return {};
  std::string others;
  for (std::size_t q = 0; q < totals.size(); ++q) {
    if (q != worst) others += (others.empty() ? "" : ", ") + excerpt(test.mass_columns[q]);
  }
  char factor_text[96];
  if (worst_factor == 0.0 || std::isinf(worst_factor)) {
    std::snprintf(factor_text, sizeof factor_text, "against");
  } else {
    // "1025 times", "1/1025 of", "3.1 times": whole numbers once they are large.
    const double ratio = worst_factor > 1.0 ? worst_factor : 1.0 / worst_factor;
    std::snprintf(factor_text, sizeof factor_text, ratio >= 10.0 ? "%s%.0f%s" : "%s%.2g%s",
                  worst_factor > 1.0 ? "" : "1/", ratio, worst_factor > 1.0 ? " times" : " of");
  }
  std::string problem = excerpt(test.mass_columns[worst]) + " holds " + grams(totals[worst]) + " in the trays " +
                        "read in every pass, " + factor_text + " the " + grams(worst_reference) + " of " + others +
                        "; the passes of one tray test carry alike (within a factor of " +
                        std::to_string(static_cast<int>(kPassTotalFactor)) + ")";
  const std::string slip = worst_factor > 0.0 && std::isfinite(worst_factor) ? unit_slip(worst_factor, kg_per_unit[worst])
                                                                              : std::string();
  return problem + (slip.empty() ? " — a pass from another test, or a column typed in another unit?" : slip);
}

}  // namespace spread::calibration
