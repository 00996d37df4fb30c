#pragma once
// A blend's answer: each component's transverse pattern and CV at the bout, the blend's total CV, each
// nutrient's CV, how the components separate across the bout, and the widest bout at which every
// component meets the CV target (the component that limits it named).
//
// A table stores each component as a material row of its own (docs/table-format.md "blend_components"):
// the launches of that component from the blend's runs, where the components met on the disc. Each
// component is predicted from its row through the predictor's public API at one request (its own
// density and sizes in flight: the landing grid and stored landing data are a material's), and the
// patterns are added by mass fraction: each component's tray_mass_fraction is of its own discharged mass,
// so the blend's tray t holds Σ_c w_c p_c(t), and a nutrient's Σ_c w_c (content_c / 100) p_c(t).
//
// Separation index (docs/products.md "Separation index"): in the overlapped distribution at the bout
// (to-and-fro), the share s_c(j) = m_c(j) / M(j) of component c in bout tray j, M(j) = Σ_k m_k(j); the
// index is the largest over the components of the mass-weighted coefficient of variation of s_c across the
// bout's trays, each tray weighted by the mass M(j) it receives (half for a tray the bout's edge cuts):
//   s̄_c = Σ_j M(j) s_c(j) / Σ_j M(j),   CV_c = sqrt(Σ_j M(j) (s_c(j) − s̄_c)² / Σ_j M(j)) / s̄_c,
// s̄_c being the component's share of the bout's mass (its mass fraction). 0: every tray receives the
// recipe; 0.2: a component's share is off the recipe by about 20 % of itself, mass-weighted. A tray that
// receives nothing carries no share. Field and lab work on bulk blends reports the nutrient ratio varying
// across the swath (Jensen & Pesek 1962, SSSAJ 26(2):178–182; Wells et al. 1992, Commun. Soil Sci. Plant
// Anal. 23:1731–1751) but fixes no index: this one is this library's definition.
#include <array>
#include <limits>
#include <string>
#include <vector>

#include "libspread/analysis/metrics/metrics.hpp"
#include "libspread/analysis/predict/predictor.hpp"
#include "libspread/io/tables/table_format.hpp"

namespace spread::blends {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct ComponentPattern {
  std::string material;                  // the component's row (blend_component_name)
  std::string name;                      // the component's own name
  double mass_fraction = 0.0;
  std::array<double, tables::kNutrientCount> nutrient_pct{};
  predict::PredictStatus status = predict::PredictStatus::kOk;  // of its own prediction
  double mean_radius_m = kNaN;           // R̄ of its landings, left disc (Eq. 51)
  double cv_to_and_fro = kNaN;           // the component alone at the bout (fraction)
  double cv_racetrack = kNaN;
  double widest_width_m = kNaN;          // its own working width alone: the widest bout it meets the target at
                                         // (metrics::working_width, to-and-fro; 0: none)
  double share_cv = kNaN;                // mass-weighted CV of its share of the applied mass across the bout's trays
  std::vector<double> tray_mass_fraction;  // per tray of BlendPatterns::trays, of the blend's discharged mass
};

struct NutrientPattern {
  const char* name = "";                 // tables::kNutrients
  bool carried = false;                  // some component carries it (a content > 0)
  double cv_to_and_fro = kNaN;           // of the nutrient's mass at the bout
  double cv_racetrack = kNaN;
};

struct BlendPatterns {
  std::string blend;
  // kOk, or the first component's status that is not (then nothing below is filled).
  predict::PredictStatus status = predict::PredictStatus::kOk;
  metrics::TrayLayout trays;             // covering every component's layout
  std::vector<ComponentPattern> components;
  std::vector<double> tray_mass_fraction;  // the blend's pattern
  // The widest bout at which every component meets the target (to-and-fro): the widest whole-tray bout
  // where all do, extended (linear in CV) to where the first of them crosses the target before the next
  // tray; and that component (the limiting one). 0 when no bout suits every component (then the limiting
  // component is the one whose lowest CV is highest).
  double widest_common_bout_m = 0.0;
  int limiting_component = -1;
  double bout_width_m = 0.0;             // where the CVs below are evaluated
  double cv_to_and_fro = kNaN;           // the blend's total
  double cv_racetrack = kNaN;
  std::array<NutrientPattern, tables::kNutrientCount> nutrients;
  double separation_index = kNaN;        // the largest component share_cv
};

// Predicts each component of `blend` (its rows in the predictor's table) at `request` (whose material is
// ignored) and evaluates the blend at request.bout_width_m, or, when that is 0, at the widest whole-tray
// bout within widest_common_bout_m (the blend total's working width when no common bout exists). Throws std::invalid_argument when a
// component's row is not in the table.
BlendPatterns blend_patterns(predict::Predictor& predictor, const tables::Blend& blend,
                             const predict::PredictionRequest& request);

}  // namespace spread::blends
