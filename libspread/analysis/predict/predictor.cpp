#include "libspread/analysis/predict/predictor.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>

#include "libspread/analysis/predict/flight_defaults.hpp"
#include "libspread/analysis/predict/landing_data_codec.hpp"
#include "libspread/analysis/predict/prediction_context.hpp"
#include "libspread/analysis/predict/run_flight_effects.hpp"

namespace spread::predict {

Predictor::Predictor(tables::TableContents contents, PredictorLimits limits, std::pmr::memory_resource* memory)
    : contents_(std::move(contents)),
      limits_(limits),
      settings_(default_flight_settings()),
      samples_(memory),
      cell_of_sample_(memory),
      cell_mean_(memory) {
  check_contents();
  group_runs();
  gather_samples();
  prepare_landing_data(memory);
  own_workspace_.emplace(*this, memory);
}

std::span<const tables::LaunchSample> Predictor::contents_samples(std::size_t run) const {
  if (contents_.pooled_offset.empty()) return contents_.runs[run].samples;
  return std::span(contents_.pooled_samples)
      .subspan(contents_.pooled_offset[run], contents_.pooled_offset[run + 1] - contents_.pooled_offset[run]);
}

void Predictor::check_contents() {
  if (!(limits_.min_tray_width_m > 0.0) || !(limits_.max_half_extent_m >= limits_.min_tray_width_m) ||
      !std::isfinite(limits_.max_half_extent_m)) {
    throw std::invalid_argument("Predictor: limits need 0 < min_tray_width_m <= max_half_extent_m < inf");
  }
  for (double bound : {limits_.max_bout_width_m, limits_.max_disc_height_m, limits_.max_wind_m_s, limits_.max_cv_target}) {
    if (!(bound > 0.0 && std::isfinite(bound))) throw std::invalid_argument("Predictor: request bounds must be finite and > 0");
  }
  // The same plausibility rules as the table reader, for contents that did not come from a file: a NaN,
  // Inf or non-positive mass/diameter must never reach the flight code.
  std::string problem = tables::machine_problem(contents_.machine);
  for (const auto& m : contents_.materials) {
    if (problem.empty()) problem = tables::material_problem(m);
  }
  const auto& runs = contents_.runs;
  if (contents_.drop_point_turn_validated_rad) {
    const auto& [low, high] = *contents_.drop_point_turn_validated_rad;
    if (!(low >= -kPi && low <= 0.0 && high >= 0.0 && high <= kPi)) {
      throw std::invalid_argument("Predictor: the validated drop-point turns must be [low, high] with -pi <= low <= 0 <= high <= pi");
    }
    turn_range_ = TurnRange{low, high};
  }
  if (!runs.empty() && std::all_of(runs.begin(), runs.end(), [](const tables::Run& r) { return r.source == "analytic"; })) {
    turn_range_ = TurnRange{-kPi, kPi};  // exact for the analytic model, whatever the scene validated for DEM
  }
  const auto& offset = contents_.pooled_offset;
  if (!offset.empty() && (offset.size() != runs.size() + 1 || offset.front() != 0 ||
                          offset.back() != contents_.pooled_samples.size() || !std::is_sorted(offset.begin(), offset.end()) ||
                          std::any_of(runs.begin(), runs.end(), [](const tables::Run& r) { return !r.samples.empty(); }))) {
    throw std::invalid_argument("Predictor: the pooled samples' offsets do not match the runs (or a run has "
                                "samples of its own besides)");
  }
  for (std::size_t k = 0; k < runs.size() && problem.empty(); ++k) {
    problem = tables::run_record_problem(runs[k]);
    if (problem.empty()) problem = tables::samples_problem(contents_samples(k));
    if (!problem.empty()) problem = "run " + runs[k].material + ": " + problem;
  }
  if (!problem.empty()) throw tables::TableError(tables::TableErrorKind::kCorrupt, "Predictor: " + problem);
}

void Predictor::group_runs() {
  const auto& runs = contents_.runs;
  run_rpm_.reserve(runs.size());
  std::size_t largest_pair = 0;  // samples of the widest interpolation (by quantile cells: n_a + n_b)
  std::size_t i = 0;
  while (i < runs.size()) {
    std::size_t j = i;
    while (j < runs.size() && runs[j].material == runs[i].material) ++j;
    const auto found = std::find_if(contents_.materials.begin(), contents_.materials.end(),
                                    [&](const tables::Material& m) { return m.name == runs[i].material; });
    if (found == contents_.materials.end()) {
      throw tables::TableError(tables::TableErrorKind::kCorrupt,
                               "run of material '" + runs[i].material + "' has no material row");
    }
    materials_.push_back(MaterialRows{static_cast<std::size_t>(found - contents_.materials.begin()), i, j - i});
    for (std::size_t k = i; k < j; ++k) {
      if (k > i && !(runs[k].rpm > runs[k - 1].rpm)) {
        throw tables::TableError(tables::TableErrorKind::kCorrupt,
                                 "runs of material '" + runs[i].material + "' not in ascending rpm order");
      }
      const std::size_t next = k + 1 < j ? contents_samples(k + 1).size() : 0;
      largest_pair = std::max(largest_pair, contents_samples(k).size() + next);
      for (const auto& s : contents_samples(k)) lowest_sample_z_m_ = std::min(lowest_sample_z_m_, double{s.z_m});
    }
    i = j;
  }
  std::sort(materials_.begin(), materials_.end(), [&](const MaterialRows& a, const MaterialRows& b) {
    return contents_.materials[a.material].name < contents_.materials[b.material].name;
  });
  for (const auto& run : runs) {
    run_rpm_.push_back(run.rpm);
    try {
      run_effects_.push_back(run_flight_effects(run));
    } catch (const std::invalid_argument& e) {
      throw tables::TableError(tables::TableErrorKind::kCorrupt,
                               "run " + run.material + " @ " + std::to_string(run.rpm) + " rpm: " + e.what());
    }
  }
  largest_pair_ = largest_pair;
}

void Predictor::gather_samples() {
  const auto& runs = contents_.runs;
  run_offset_.assign(runs.size() + 1, 0);
  for (std::size_t k = 0; k < runs.size(); ++k) run_offset_[k + 1] = run_offset_[k] + contents_samples(k).size();
  // The samples in one block from the Predictor's memory; the runs keep their other records. Pooled ones
  // from the same memory are that block already (a move); others are copied in.
  if (!contents_.pooled_offset.empty()) {
    samples_ = std::move(contents_.pooled_samples);
    contents_.pooled_samples.clear();
    contents_.pooled_samples.shrink_to_fit();
    contents_.pooled_offset.clear();
  } else {
    samples_.reserve(run_offset_.back());
    for (auto& run : contents_.runs) {
      samples_.insert(samples_.end(), run.samples.begin(), run.samples.end());
      std::vector<tables::LaunchSample>().swap(run.samples);
    }
  }
}

void Predictor::prepare_landing_data(std::pmr::memory_resource* memory) {
  const auto& runs = contents_.runs;
  cell_of_sample_.assign(run_offset_.back(), 0);
  cell_offset_.assign(runs.size() + 1, 0);
  for (const auto& rows : materials_) {
    const auto cells = static_cast<std::size_t>(cell_counts(rows).cells());
    for (std::size_t k = rows.first_run; k < rows.first_run + rows.run_count; ++k) {
      cell_offset_[k + 1] = needs_cells(rows, k) ? cells : 0;
    }
  }
  for (std::size_t k = 0; k < runs.size(); ++k) cell_offset_[k + 1] += cell_offset_[k];
  cell_mean_.assign(cell_offset_.back(), tables::LaunchSample{});
  domain_ = landing_domain_for(contents_.machine.disc_height_m);
  for (std::size_t m = 0; m < contents_.materials.size(); ++m) grids_.emplace_back(memory);
  // Each material's grid and cells: read from the table's landing data where it holds them for this
  // model, otherwise derived (flown) here.
  const std::string model = landing_data_model(domain_, grid_flight_settings(), default_flight_settings());
  landing_data_from_table_.assign(materials_.size(), false);
  for (std::size_t r = 0; r < materials_.size(); ++r) {
    const MaterialRows& rows = materials_[r];
    const std::string& name = contents_.materials[rows.material].name;
    const std::string key = landing_source_key(rows);
    const auto stored = std::find_if(contents_.landing_data.begin(), contents_.landing_data.end(), [&](const tables::LandingData& d) {
      return d.material == name && d.model == model && d.source_key == key;
    });
    if (stored != contents_.landing_data.end()) {
      restore_landing_data(rows, stored->data);
      landing_data_from_table_[r] = true;
      continue;
    }
    assign_cells(rows);
    build_landing_grid(rows);
  }
  std::vector<tables::LandingData>().swap(contents_.landing_data);
}

std::size_t Predictor::most_cells() const {
  std::size_t most = 0;
  for (std::size_t k = 0; k + 1 < cell_offset_.size(); ++k) most = std::max(most, cell_offset_[k + 1] - cell_offset_[k]);
  return most;
}

const tables::Material& Predictor::material(std::size_t index) const {
  return contents_.materials.at(materials_.at(index).material);
}
std::span<const double> Predictor::row_rpm(std::size_t index) const {
  const MaterialRows& rows = materials_.at(index);
  return std::span(run_rpm_).subspan(rows.first_run, rows.run_count);
}
double Predictor::min_rpm(std::size_t index) const { return contents_.runs[materials_.at(index).first_run].rpm; }
double Predictor::max_rpm(std::size_t index) const {
  const auto& rows = materials_.at(index);
  return contents_.runs[rows.first_run + rows.run_count - 1].rpm;
}

std::optional<std::size_t> Predictor::find_material(std::string_view name) const {
  for (std::size_t k = 0; k < materials_.size(); ++k) {
    if (contents_.materials[materials_[k].material].name == name) return k;
  }
  return std::nullopt;
}

int Predictor::tray_capacity(double tray_width_m) const {
  if (!(tray_width_m >= limits_.min_tray_width_m) || !(tray_width_m <= limits_.max_half_extent_m)) return 0;
  return metrics::tray_layout_covering(limits_.max_half_extent_m, tray_width_m).tray_count;
}

PredictStatus Predictor::predict(const PredictionRequest& request, Prediction& out) {
  return predict(request, out, *own_workspace_);
}

PredictStatus Predictor::predict(const PredictionRequest& request, Prediction& out, PredictorWorkspace& w) const {
  if (w.sample_capacity_ < largest_pair_ ||
      w.tray_capacity_ < static_cast<std::size_t>(tray_capacity(limits_.min_tray_width_m))) {
    throw std::invalid_argument("Predictor::predict: the workspace was made for a smaller table");
  }
  // The stages one after another (predictor.hpp); a refusal leaves `out` unchanged (only measure_pattern
  // and those after it write it).
  Context c{request, out, w};
  if (const PredictStatus s = check_request(c); s != PredictStatus::kOk) return s;
  c.return_pass = return_pass_of(c);
  if (c.return_pass == ReturnPass::kFlown) {
    if (const PredictStatus s = fly_return_pass(c); s != PredictStatus::kOk) return s;
  }
  land_discs(c);
  bin_transverse(c);
  align_return_pass(c);
  measure_pattern(c);
  sample_standard_errors(c);
  choose_headline(c);
  if (request.standard_errors && request.interpolation_error) add_interpolation_error(c);
  return PredictStatus::kOk;
}

}  // namespace spread::predict
