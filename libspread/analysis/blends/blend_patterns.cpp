#include "libspread/analysis/blends/blend_patterns.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace spread::blends {
namespace {

using metrics::Overlap;

// The component's own prediction at the request; its trays copied (a Prediction's trays are a view into
// the predictor's workspace, valid until the next predict()).
struct OwnPrediction {
  predict::PredictStatus status = predict::PredictStatus::kOk;
  metrics::TrayLayout trays;
  std::vector<double> tray_mass_fraction;
  double mean_radius_m = kNaN;
};

OwnPrediction predict_component(predict::Predictor& predictor, const ComponentPattern& c,
                                const predict::PredictionRequest& request) {
  if (!predictor.find_material(c.material))
    throw std::invalid_argument("blend: the table has no row \"" + c.material + "\" of the blend's component");
  predict::PredictionRequest own = request;
  own.material = c.material;  // a view into the ComponentPattern, which outlives the call
  predict::Prediction p;
  OwnPrediction out;
  out.status = predictor.predict(own, p);
  if (out.status != predict::PredictStatus::kOk) return out;
  out.trays = p.trays;
  out.tray_mass_fraction.assign(p.tray_mass_fraction.begin(), p.tray_mass_fraction.end());
  out.mean_radius_m = p.mean_radius_m;
  return out;
}

// `pattern` (of `from`, even tray count, centred) placed into the wider centred layout `into`, scaled.
std::vector<double> centred_into(const std::vector<double>& pattern, const metrics::TrayLayout& from,
                                 const metrics::TrayLayout& into, double scale) {
  std::vector<double> out(static_cast<std::size_t>(into.tray_count), 0.0);
  const int offset = (into.tray_count - from.tray_count) / 2;  // both even: the tray edges coincide
  for (int k = 0; k < from.tray_count; ++k) out[static_cast<std::size_t>(k + offset)] = scale * pattern[static_cast<std::size_t>(k)];
  return out;
}

// The components' patterns in one layout, each scaled to its share of the blend's mass.
void place_components(BlendPatterns& b, const std::vector<OwnPrediction>& own) {
  b.trays = own.front().trays;
  for (const OwnPrediction& p : own) b.trays.tray_count = std::max(b.trays.tray_count, p.trays.tray_count);
  b.tray_mass_fraction.assign(static_cast<std::size_t>(b.trays.tray_count), 0.0);
  for (std::size_t c = 0; c < own.size(); ++c) {
    ComponentPattern& component = b.components[c];
    component.mean_radius_m = own[c].mean_radius_m;
    component.tray_mass_fraction = centred_into(own[c].tray_mass_fraction, own[c].trays, b.trays, component.mass_fraction);
    for (std::size_t t = 0; t < b.tray_mass_fraction.size(); ++t) b.tray_mass_fraction[t] += component.tray_mass_fraction[t];
  }
}

// Each component's CV (to-and-fro) at every whole-tray bout from 2 trays to the layout's width.
std::vector<std::vector<double>> cv_curves(const BlendPatterns& b, std::vector<double>& widths_m) {
  widths_m.clear();
  for (int n = 2; n <= b.trays.tray_count; ++n) widths_m.push_back(n * b.trays.tray_width_m);
  std::vector<std::vector<double>> cv(b.components.size(), std::vector<double>(widths_m.size()));
  for (std::size_t c = 0; c < b.components.size(); ++c)
    metrics::cv_curve(b.components[c].tray_mass_fraction, b.trays, widths_m, Overlap::kToAndFro, cv[c]);
  return cv;
}

// The widest bout at which every component meets the target: the widest whole-tray bout where all do,
// extended to where the first of them crosses the target before the next whole tray (linear in CV, as
// metrics::working_width interpolates a band's end); limited by that component. When no bout suits every
// component, the one whose lowest CV is highest limits (there is no width).
void widest_common_bout(BlendPatterns& b, double cv_target) {
  std::vector<double> widths_m;
  const std::vector<std::vector<double>> cv = cv_curves(b, widths_m);
  for (std::size_t c = 0; c < b.components.size(); ++c)
    b.components[c].widest_width_m = metrics::working_width(b.components[c].tray_mass_fraction, b.trays, Overlap::kToAndFro, cv_target).width_m;
  const auto all_meet = [&](std::size_t k) {
    return std::all_of(cv.begin(), cv.end(), [&](const std::vector<double>& curve) { return curve[k] <= cv_target; });
  };
  std::size_t k = widths_m.size();
  while (k > 0 && !all_meet(k - 1)) --k;
  b.widest_common_bout_m = 0.0;
  b.limiting_component = -1;
  if (k == 0) {
    double worst = -1.0;
    for (std::size_t c = 0; c < cv.size(); ++c) {
      const double lowest = *std::min_element(cv[c].begin(), cv[c].end());
      if (lowest > worst) {
        worst = lowest;
        b.limiting_component = static_cast<int>(c);
      }
    }
    return;
  }
  const std::size_t at = k - 1;  // all meet the target here
  b.widest_common_bout_m = widths_m[at];
  if (at + 1 == widths_m.size()) {  // up to the layout's width: the component closest to the target limits
    for (std::size_t c = 0; c < cv.size(); ++c)
      if (b.limiting_component < 0 || cv[c][at] > cv[static_cast<std::size_t>(b.limiting_component)][at]) b.limiting_component = static_cast<int>(c);
    return;
  }
  double crossing = INFINITY;
  for (std::size_t c = 0; c < cv.size(); ++c) {
    if (!(cv[c][at + 1] > cv_target)) continue;
    const double rise = cv[c][at + 1] - cv[c][at];
    const double x = std::isfinite(rise) && rise > 0.0 ? (cv_target - cv[c][at]) / rise : 0.0;
    const double w = widths_m[at] + x * (widths_m[at + 1] - widths_m[at]);
    if (w < crossing) {
      crossing = w;
      b.limiting_component = static_cast<int>(c);
    }
  }
  b.widest_common_bout_m = crossing;
}

// Each component's share of the applied mass across the bout's trays (to-and-fro overlap): its mass-weighted
// coefficient of variation, the trays weighted by the mass they receive (and by 1/2 where the bout's edge
// cuts one, as in metrics::cv_at_trays), so that a tray receiving nothing carries no share and the mean
// share is the component's share of the bout's mass.
void separation(BlendPatterns& b) {
  const metrics::BoutTrays bout = metrics::bout_trays(b.trays, metrics::bout_tray_count(b.trays, b.bout_width_m));
  const std::size_t grid = static_cast<std::size_t>(bout.grid_trays);
  std::vector<double> total(grid, 0.0);
  std::vector<std::vector<double>> own(b.components.size(), std::vector<double>(grid, 0.0));
  for (std::size_t c = 0; c < b.components.size(); ++c) {
    metrics::overlapped_profile(b.components[c].tray_mass_fraction, b.trays, b.bout_width_m, Overlap::kToAndFro, own[c]);
    for (std::size_t j = 0; j < grid; ++j) total[j] += own[c][j];
  }
  const auto weight = [&](std::size_t j) { return (bout.cut_edges && (j == 0 || j + 1 == grid) ? 0.5 : 1.0) * total[j]; };
  double sum_w = 0.0;
  for (std::size_t j = 0; j < grid; ++j) sum_w += weight(j);
  b.separation_index = 0.0;
  for (std::size_t c = 0; c < b.components.size(); ++c) {
    double mean = 0.0, sum_sq = 0.0;
    for (std::size_t j = 0; j < grid; ++j)
      if (total[j] > 0.0) mean += weight(j) * own[c][j] / total[j];
    mean /= sum_w;
    for (std::size_t j = 0; j < grid; ++j)
      if (total[j] > 0.0) sum_sq += weight(j) * (own[c][j] / total[j] - mean) * (own[c][j] / total[j] - mean);
    const double cv = sum_w > 0.0 && mean > 0.0 ? std::sqrt(sum_sq / sum_w) / mean : 0.0;
    b.components[c].share_cv = cv;
    b.separation_index = std::max(b.separation_index, cv);
  }
}

// Each component's, the blend's and each nutrient's CV at the bout.
void cvs_at_bout(BlendPatterns& b) {
  const auto cv = [&](const std::vector<double>& p, Overlap overlap) { return metrics::cv_at_width(p, b.trays, b.bout_width_m, overlap); };
  for (ComponentPattern& c : b.components) {
    c.cv_to_and_fro = cv(c.tray_mass_fraction, Overlap::kToAndFro);
    c.cv_racetrack = cv(c.tray_mass_fraction, Overlap::kRacetrack);
  }
  b.cv_to_and_fro = cv(b.tray_mass_fraction, Overlap::kToAndFro);
  b.cv_racetrack = cv(b.tray_mass_fraction, Overlap::kRacetrack);
  for (int k = 0; k < tables::kNutrientCount; ++k) {
    NutrientPattern& nutrient = b.nutrients[static_cast<std::size_t>(k)];
    nutrient.name = tables::kNutrients[k].name;
    std::vector<double> mass(b.tray_mass_fraction.size(), 0.0);
    for (const ComponentPattern& c : b.components) {
      const double pct = c.nutrient_pct[static_cast<std::size_t>(k)];
      nutrient.carried = nutrient.carried || pct > 0.0;
      for (std::size_t t = 0; t < mass.size(); ++t) mass[t] += 0.01 * pct * c.tray_mass_fraction[t];
    }
    if (!nutrient.carried) continue;
    nutrient.cv_to_and_fro = cv(mass, Overlap::kToAndFro);
    nutrient.cv_racetrack = cv(mass, Overlap::kRacetrack);
  }
}

std::vector<ComponentPattern> components_of(const tables::Blend& blend) {
  std::vector<ComponentPattern> out;
  const std::string prefix = tables::blend_component_name(blend.name, "");
  for (const tables::BlendRowComponent& row : blend.components) {
    ComponentPattern c;
    c.material = row.material;
    c.name = row.material.rfind(prefix, 0) == 0 ? row.material.substr(prefix.size()) : row.material;
    c.mass_fraction = row.mass_fraction;
    c.nutrient_pct = {row.n_pct, row.p2o5_pct, row.k2o_pct};
    out.push_back(std::move(c));
  }
  return out;
}

}  // namespace

BlendPatterns blend_patterns(predict::Predictor& predictor, const tables::Blend& blend,
                             const predict::PredictionRequest& request) {
  BlendPatterns b;
  b.blend = blend.name;
  b.components = components_of(blend);
  if (b.components.empty()) throw std::invalid_argument("blend " + blend.name + ": no components");
  std::vector<OwnPrediction> own;
  for (ComponentPattern& c : b.components) {
    own.push_back(predict_component(predictor, c, request));
    c.status = own.back().status;
    if (c.status != predict::PredictStatus::kOk && b.status == predict::PredictStatus::kOk) b.status = c.status;
  }
  if (b.status != predict::PredictStatus::kOk) return b;
  place_components(b, own);
  widest_common_bout(b, request.cv_target);
  b.bout_width_m = request.bout_width_m;
  // By default the widest whole-tray bout inside the common one: the CVs are evaluated on whole trays,
  // where every component meets the target.
  const double tray_m = b.trays.tray_width_m;
  if (!(b.bout_width_m > 0.0)) b.bout_width_m = std::floor(b.widest_common_bout_m / tray_m + 1e-9) * tray_m;
  if (!(b.bout_width_m > 0.0))
    b.bout_width_m = metrics::working_width(b.tray_mass_fraction, b.trays, Overlap::kToAndFro, request.cv_target).width_m;
  if (!(b.bout_width_m > 0.0)) b.bout_width_m = b.trays.tray_width_m;  // nothing meets the target: one tray
  cvs_at_bout(b);
  separation(b);
  return b;
}

}  // namespace spread::blends
