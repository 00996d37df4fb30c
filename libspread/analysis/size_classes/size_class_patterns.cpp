#include "libspread/analysis/size_classes/size_class_patterns.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace spread::size_classes {
namespace {

std::span<const tables::LaunchSample> samples_of(const tables::TableContents& c, std::size_t run) {
  if (c.pooled_offset.empty()) return c.runs[run].samples;
  return std::span(c.pooled_samples).subspan(c.pooled_offset[run], c.pooled_offset[run + 1] - c.pooled_offset[run]);
}

std::vector<tables::LaunchSample> material_samples(const tables::TableContents& c, const std::string& material) {
  std::vector<tables::LaunchSample> all;
  for (std::size_t k = 0; k < c.runs.size(); ++k) {
    if (c.runs[k].material != material) continue;
    const auto s = samples_of(c, k);
    all.insert(all.end(), s.begin(), s.end());
  }
  return all;
}

bool within(const tables::LaunchSample& s, double lower_mm, double upper_mm) {
  const double d_mm = 1e3 * double{s.diameter_m};
  return d_mm >= lower_mm && d_mm < upper_mm;
}

// The class's share of the material's mass and its sample count, over the pooled samples.
void count_class(std::span<const tables::LaunchSample> all, ClassPattern& c) {
  double total = 0.0, in_class = 0.0;
  for (const tables::LaunchSample& s : all) {
    total += double{s.mass_kg};
    if (within(s, c.lower_mm, c.upper_mm)) {
      in_class += double{s.mass_kg};
      ++c.sample_count;
    }
  }
  c.mass_fraction = total > 0.0 ? in_class / total : 0.0;
}

// The class predicted alone at the request's bout; its trays scaled to its share of the whole mass.
void predict_class(const tables::TableContents& contents, const predict::PredictionRequest& request, ClassPattern& c) {
  const std::string material(request.material);
  tables::TableContents own = class_contents(contents, material, c.lower_mm, c.upper_mm);
  if (own.runs.empty()) {
    c.status = predict::PredictStatus::kRpmOutsideTable;
    return;
  }
  predict::Predictor predictor(std::move(own));
  predict::Prediction p;
  c.status = predictor.predict(request, p);
  if (c.status != predict::PredictStatus::kOk) return;
  c.mean_radius_m = p.mean_radius_m;
  c.cv_to_and_fro = p.cv_to_and_fro;
  c.cv_to_and_fro_se = p.cv_to_and_fro_se;
  c.cv_racetrack = p.cv_racetrack;
  c.trays = p.trays;
  c.tray_mass_fraction.assign(p.tray_mass_fraction.begin(), p.tray_mass_fraction.end());
  for (double& m : c.tray_mass_fraction) m *= c.mass_fraction;
}

ClassPattern one_class(const tables::TableContents& contents, const predict::PredictionRequest& request,
                       std::span<const tables::LaunchSample> all, double lower_mm, double upper_mm) {
  ClassPattern c;
  c.lower_mm = lower_mm;
  c.upper_mm = upper_mm;
  count_class(all, c);
  if (c.sample_count > 0) predict_class(contents, request, c);
  else c.status = predict::PredictStatus::kRpmOutsideTable;
  return c;
}

}  // namespace

tables::TableContents class_contents(const tables::TableContents& contents, const std::string& material,
                                     double lower_mm, double upper_mm) {
  tables::TableContents own;
  own.machine = contents.machine;
  for (const tables::Material& m : contents.materials) {
    if (m.name == material) own.materials.push_back(m);
  }
  own.drop_point_turn_validated_rad = contents.drop_point_turn_validated_rad;
  own.runs_listed = contents.runs_listed;
  for (std::size_t k = 0; k < contents.runs.size(); ++k) {
    const tables::Run& run = contents.runs[k];
    if (run.material != material) continue;
    tables::Run kept = run;
    kept.samples.clear();
    for (const tables::LaunchSample& s : samples_of(contents, k)) {
      if (within(s, lower_mm, upper_mm)) kept.samples.push_back(s);
    }
    if (!kept.samples.empty()) own.runs.push_back(std::move(kept));
  }
  return own;
}

SizeClassPatterns size_class_patterns(const tables::TableContents& contents, const predict::PredictionRequest& request,
                                      std::span<const double> boundaries_mm) {
  if (!(request.bout_width_m > 0.0)) throw std::invalid_argument("size classes: the bout width must be > 0");
  for (std::size_t i = 0; i < boundaries_mm.size(); ++i) {
    if (!(boundaries_mm[i] > 0.0) || !std::isfinite(boundaries_mm[i]) || (i > 0 && !(boundaries_mm[i] > boundaries_mm[i - 1])))
      throw std::invalid_argument("size classes: the class boundaries (mm) must be > 0 and increasing");
  }
  const std::string material(request.material);
  const std::vector<tables::LaunchSample> all = material_samples(contents, material);
  if (all.empty()) throw std::invalid_argument("size classes: no launch samples of material '" + material + "'");
  SizeClassPatterns out;
  out.bout_width_m = request.bout_width_m;
  out.sizes = launch_sizes(all);
  double lower = 0.0;
  for (std::size_t i = 0; i <= boundaries_mm.size(); ++i) {
    const double upper = i < boundaries_mm.size() ? boundaries_mm[i] : kNoBound_mm;
    out.classes.push_back(one_class(contents, request, all, lower, upper));
    lower = upper;
  }
  out.fine = one_class(contents, request, all, 0.0, out.sizes.d50_mm);
  out.coarse = one_class(contents, request, all, out.sizes.d50_mm, kNoBound_mm);
  return out;
}

}  // namespace spread::size_classes
