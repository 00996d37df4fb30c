#pragma once
// The pattern of each size class of a material's granules and the CV each class alone has at the
// product's bout: where the fine and the coarse granules of one product land (size segregation in
// flight: drag decelerates a small granule more, d v/dt ∝ ρ_air v² / (ρ d), so at one launch speed the
// larger granules fly further).
//
// Built on the predictor's public API alone: the launch records carry each granule's diameter
// (docs/table-format.md "Launch record") but a Prediction's landings do not, so each class is predicted
// from the table's rows with only that class's launch samples (the same material row, machine and
// request): its landings are the same flights the whole product's prediction makes of those samples, up to
// the kernel's half-width (the automatic rule follows the class's sample count) and, between DEM rows
// interpolated by quantile cells, the cells of the class's own samples.
#include <cstddef>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "libspread/analysis/metrics/metrics.hpp"
#include "libspread/analysis/predict/predictor.hpp"
#include "libspread/analysis/size_classes/launch_sizes.hpp"
#include "libspread/io/tables/table_reader.hpp"

namespace spread::size_classes {

inline constexpr double kNoBound_mm = std::numeric_limits<double>::infinity();

struct ClassPattern {
  double lower_mm = 0.0;                 // the class is [lower_mm, upper_mm) of the launch diameters
  double upper_mm = kNoBound_mm;
  double mass_fraction = 0.0;            // of the material's launched mass, its rows' samples pooled
  std::size_t sample_count = 0;          // launch samples in the class over the material's rows
  // The class's own prediction: kOk, or why there is none (a row without granules of the class narrows
  // its rpm range, and a class without granules has no rows: kRpmOutsideTable, sample_count 0). The
  // figures below are NaN without one.
  predict::PredictStatus status = predict::PredictStatus::kOk;
  double mean_radius_m = std::numeric_limits<double>::quiet_NaN();  // R̄ of its landings, left disc (Eq. 51)
  double cv_to_and_fro = std::numeric_limits<double>::quiet_NaN();  // the class alone at the bout (fraction)
  double cv_to_and_fro_se = std::numeric_limits<double>::quiet_NaN();
  double cv_racetrack = std::numeric_limits<double>::quiet_NaN();
  metrics::TrayLayout trays;
  std::vector<double> tray_mass_fraction;  // per tray, of the material's whole discharged mass
};

struct SizeClassPatterns {
  double bout_width_m = 0.0;
  LaunchSizes sizes;                     // of the material's launch samples, all rows pooled
  std::vector<ClassPattern> classes;     // below the first boundary, between each two, above the last
  ClassPattern fine, coarse;             // below and above the launched mass's d50: each half of the mass
};

// Throws std::invalid_argument when the material has no rows, the boundaries are not positive and
// increasing, or request.bout_width_m is not > 0 (the classes are judged at one bout, the product's).
SizeClassPatterns size_class_patterns(const tables::TableContents& contents, const predict::PredictionRequest& request,
                                      std::span<const double> boundaries_mm);

// The table's contents with only the material's launch samples of diameter in [lower_mm, upper_mm): its
// rows that keep some, the machine, the material row and the validated drop-point turns; no landing data
// (a reader derives it for these samples).
tables::TableContents class_contents(const tables::TableContents& contents, const std::string& material,
                                     double lower_mm, double upper_mm);

}  // namespace spread::size_classes
