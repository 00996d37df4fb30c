#include "libspread/analysis/predict/predictor.hpp"

#include <algorithm>
#include <memory>
#include <cmath>
#include <new>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>

#include "libspread/analysis/predict/flight_defaults.hpp"
#include "libspread/analysis/predict/landing_data_codec.hpp"
#include "libspread/analysis/predict/launch_interpolation.hpp"
#include "libspread/analysis/predict/launch_landing_keys.hpp"
#include "libspread/analysis/predict/launch_quantile_cells.hpp"
#include "libspread/analysis/predict/run_flight_effects.hpp"
#include "libspread/analysis/predict/sample_influence.hpp"
#include "libspread/analysis/metrics/wide_kernel.hpp"
#include "libspread/io/tables/row_checksum.hpp"
#include "libspread/io/tables/sample_codec.hpp"

namespace spread::predict {

const char* to_string(PredictStatus status) {
  switch (status) {
    case PredictStatus::kOk: return "ok";
    case PredictStatus::kNotFinite: return "argument not finite";
    case PredictStatus::kOutOfRange: return "argument out of range";
    case PredictStatus::kUnknownEffect: return "unknown effect bits";
    case PredictStatus::kUnknownMaterial: return "unknown material";
    case PredictStatus::kRpmOutsideTable: return "rpm outside the table";
    case PredictStatus::kOutsideDomain: return "outside the landing grid's domain";
  }
  return "unknown status";
}

double kernel_half_width_for(double sd_x_m, std::size_t sample_count) {
  if (sample_count == 0 || !(sd_x_m > 0.0)) return 0.0;
  return kKernelScale * sd_x_m * std::pow(static_cast<double>(sample_count), -0.2);
}

Predictor::Predictor(tables::TableContents contents, PredictorLimits limits, std::pmr::memory_resource* memory)
    : contents_(std::move(contents)),
      limits_(limits),
      settings_(default_flight_settings()),
      samples_(memory),
      cell_of_sample_(memory),
      cell_mean_(memory) {
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
  auto& runs = contents_.runs;
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
  const bool pooled = !contents_.pooled_offset.empty();
  if (pooled && (contents_.pooled_offset.size() != runs.size() + 1 || contents_.pooled_offset.front() != 0 ||
                 contents_.pooled_offset.back() != contents_.pooled_samples.size() ||
                 !std::is_sorted(contents_.pooled_offset.begin(), contents_.pooled_offset.end()) ||
                 std::any_of(runs.begin(), runs.end(), [](const tables::Run& r) { return !r.samples.empty(); }))) {
    throw std::invalid_argument("Predictor: the pooled samples' offsets do not match the runs (or a run has "
                                "samples of its own besides)");
  }
  // Run k's samples, wherever the contents keep them.
  const auto samples_of = [&](std::size_t k) -> std::span<const tables::LaunchSample> {
    if (!pooled) return runs[k].samples;
    return std::span(contents_.pooled_samples)
        .subspan(contents_.pooled_offset[k], contents_.pooled_offset[k + 1] - contents_.pooled_offset[k]);
  };
  for (std::size_t k = 0; k < runs.size() && problem.empty(); ++k) {
    problem = tables::run_record_problem(runs[k]);
    if (problem.empty()) problem = tables::samples_problem(samples_of(k));
    if (!problem.empty()) problem = "run " + runs[k].material + ": " + problem;
  }
  if (!problem.empty()) throw tables::TableError(tables::TableErrorKind::kCorrupt, "Predictor: " + problem);
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
      const std::size_t next = k + 1 < j ? samples_of(k + 1).size() : 0;
      largest_pair = std::max(largest_pair, samples_of(k).size() + next);
      for (const auto& s : samples_of(k)) lowest_sample_z_m_ = std::min(lowest_sample_z_m_, double{s.z_m});
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
  run_offset_.assign(runs.size() + 1, 0);
  for (std::size_t k = 0; k < runs.size(); ++k) run_offset_[k + 1] = run_offset_[k] + samples_of(k).size();
  // The samples in one block from `memory`; the runs keep their other records. Pooled ones from the same
  // memory are that block already (a move); others are copied in.
  if (pooled) {
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

  own_workspace_.emplace(*this, memory);
}

std::size_t Predictor::interpolated_count(std::size_t lower_run, std::size_t upper_run) const {
  if (lower_run == upper_run || pairwise(lower_run, upper_run)) return run_samples(lower_run).size();
  return run_samples(lower_run).size() + run_samples(upper_run).size();
}

CelledRow Predictor::celled(std::size_t run) const {
  return CelledRow{run_samples(run), std::span(cell_of_sample_).subspan(run_offset_[run], run_samples(run).size()),
                   std::span(cell_mean_).subspan(cell_offset_[run], cell_offset_[run + 1] - cell_offset_[run])};
}

std::size_t Predictor::most_cells() const {
  std::size_t most = 0;
  for (std::size_t k = 0; k + 1 < cell_offset_.size(); ++k) most = std::max(most, cell_offset_[k + 1] - cell_offset_[k]);
  return most;
}

std::span<const tables::LaunchSample> Predictor::cell_targets(PredictorWorkspace& w, std::size_t lower_run,
                                                              std::size_t upper_run, double t) const {
  if (lower_run == upper_run || pairwise(lower_run, upper_run)) return {};
  const std::span<tables::LaunchSample> targets = std::span(w.cell_target_).first(cell_offset_[lower_run + 1] - cell_offset_[lower_run]);
  quantile_cell_targets(celled(lower_run), celled(upper_run), t, targets);
  return targets;
}

void Predictor::interpolate(std::size_t lower_run, std::size_t upper_run, double t, std::size_t first,
                            std::span<tables::LaunchSample> samples, std::span<double> weight_kg,
                            std::span<const tables::LaunchSample> cell_target) const {
  const std::size_t count = samples.size();
  if (lower_run == upper_run || pairwise(lower_run, upper_run)) {
    interpolate_launch_samples(run_samples(lower_run).subspan(first, count),
                               run_samples(upper_run).subspan(lower_run == upper_run ? 0 : first,
                                                              lower_run == upper_run ? 0 : count),
                               lower_run == upper_run ? 0.0 : t, samples, weight_kg);
    return;
  }
  // The cells were checked against their rows at construction (assign_cells, restore_landing_data).
  interpolate_by_quantile_cells(celled(lower_run), celled(upper_run), t, first, samples, weight_kg, cell_target);
}

namespace {
// Relative and absolute tolerance (m, m/s) of the landing grid's flights: flown once, tighter than a
// flight in predict() at little cost, so that the interpolation is the grid's only error.
constexpr double kGridTolerance = 1e-7;
}  // namespace

flight::Settings Predictor::grid_flight_settings() const {
  flight::Settings settings = default_flight_settings();
  settings.rel_tol = std::min(settings.rel_tol, kGridTolerance);
  settings.abs_tol = std::min(settings.abs_tol, kGridTolerance);
  return settings;
}

bool Predictor::grid_effects(const MaterialRows& rows, flight::EffectSet& effects, double& max_rim_speed_m_s) const {
  // Drag alone or nothing (wind is a condition of the day), the same for every row: the only flights
  // the grid's four numbers describe.
  effects = run_effects_[rows.first_run] & ~flight::EffectSet{flight::kWind};
  bool held = LandingGrid::holds(effects);
  max_rim_speed_m_s = 0.0;
  for (std::size_t k = rows.first_run; k < rows.first_run + rows.run_count; ++k) {
    held = held && (run_effects_[k] & ~flight::EffectSet{flight::kWind}) == effects;
    max_rim_speed_m_s = std::max(max_rim_speed_m_s, run_rpm_[k] * 2.0 * kPi / 60.0 * contents_.machine.disc_radius_m);
  }
  return held;
}

LandingGrid::Axes Predictor::grid_axes(const MaterialRows& rows, double max_rim_speed_m_s) const {
  const std::span<const tables::LaunchSample> samples(samples_.data() + run_offset_[rows.first_run],
                                                      run_offset_[rows.first_run + rows.run_count] - run_offset_[rows.first_run]);
  return landing_grid_axes(samples, max_rim_speed_m_s, domain_);
}

void Predictor::build_landing_grid(const MaterialRows& rows) {
  flight::EffectSet effects = 0;
  double max_rim_speed_m_s = 0.0;
  if (!grid_effects(rows, effects, max_rim_speed_m_s)) return;
  grids_[rows.material].build(grid_axes(rows, max_rim_speed_m_s), contents_.materials[rows.material].density_kg_m3,
                              effects, grid_flight_settings(), flight::Air{});
}

std::string Predictor::landing_source_key(const MaterialRows& rows) const {
  // Everything the grid and the cells are derived from besides the model: the machine (radius, height,
  // the domain), the material (density), and per row its rpm, source (pairwise or by cells), flight
  // effects and launch samples (their bytes in this host's order: a host of the other byte order derives
  // afresh).
  static_assert(sizeof(tables::LaunchSample) == 4 * tables::kSampleFloats, "LaunchSample without padding");
  tables::Crc64 crc;
  crc.text(tables::machine_checksum(contents_.machine));
  crc.text(tables::material_checksum(contents_.materials[rows.material]));
  for (std::size_t k = rows.first_run; k < rows.first_run + rows.run_count; ++k) {
    const std::span<const tables::LaunchSample> samples = run_samples(k);
    crc.real(run_rpm_[k]);
    crc.text(contents_.runs[k].source);
    crc.integer(static_cast<std::int64_t>(run_effects_[k]));
    crc.integer(static_cast<std::int64_t>(samples.size()));
    crc.bytes({reinterpret_cast<const std::uint8_t*>(samples.data()), samples.size_bytes()});
  }
  return crc.hex();
}

tables::LandingData Predictor::encode_landing_data(const MaterialRows& rows) const {
  LandingDataWriter out;
  const LandingGrid& grid = grids_[rows.material];
  out.u32(grid.empty() ? 0 : 1);
  if (!grid.empty()) {
    out.u32(grid.effects());
    for (const GridAxis& axis : grid.axes()) {
      out.f64(axis.first);
      out.f64(axis.step);
      out.u32(axis.count);
    }
    out.f32s(grid.values());
  }
  std::uint32_t celled = 0;
  for (std::size_t k = rows.first_run; k < rows.first_run + rows.run_count; ++k) celled += needs_cells(rows, k) ? 1 : 0;
  out.u32(celled);
  for (std::size_t k = rows.first_run; k < rows.first_run + rows.run_count; ++k) {
    if (!needs_cells(rows, k)) continue;
    const std::size_t n = run_samples(k).size(), cells = cell_offset_[k + 1] - cell_offset_[k];
    out.u32(static_cast<std::uint32_t>(n));
    out.u32(static_cast<std::uint32_t>(cells));
    out.bytes(std::span(cell_of_sample_).subspan(run_offset_[k], n));
    out.bytes(tables::encode_samples(std::span(cell_mean_).subspan(cell_offset_[k], cells)));
  }
  return tables::LandingData{contents_.materials[rows.material].name,
                             landing_data_model(domain_, grid_flight_settings(), default_flight_settings()),
                             landing_source_key(rows), out.take()};
}

void Predictor::restore_landing_data(const MaterialRows& rows, std::span<const std::uint8_t> data) {
  const std::string& name = contents_.materials[rows.material].name;
  const auto damaged = [&](const std::string& what) {
    return tables::TableError(tables::TableErrorKind::kCorrupt,
                              "Predictor: the landing data of " + name + " does not fit its rows: " + what +
                                  "; rebuild the table with lookup_builder");
  };
  LandingDataReader in(data);
  std::uint32_t has_grid = 0;
  if (!in.u32(has_grid) || has_grid > 1) throw damaged("no grid flag");
  flight::EffectSet effects = 0;
  double max_rim_speed_m_s = 0.0;
  const bool held = grid_effects(rows, effects, max_rim_speed_m_s);
  if ((has_grid == 1) != held) throw damaged(held ? "no grid for drag-only rows" : "a grid for rows that fly more than drag");
  if (held) {
    std::uint32_t stored_effects = 0;
    LandingGrid::Axes axes{};
    bool ok = in.u32(stored_effects);
    for (GridAxis& axis : axes) ok = ok && in.f64(axis.first) && in.f64(axis.step) && in.u32(axis.count);
    if (!ok) throw damaged("truncated grid");
    // The axes follow from the rows and the model: stored ones that differ were flown for other samples.
    if (stored_effects != effects || axes != grid_axes(rows, max_rim_speed_m_s)) throw damaged("grid axes or effects");
    std::vector<float> values(LandingGrid::value_count(axes));  // construction only: may allocate
    if (!in.f32s(values) || !grids_[rows.material].restore(axes, effects, values)) throw damaged("grid values");
  }
  std::uint32_t celled = 0;
  if (!in.u32(celled)) throw damaged("no row count");
  std::uint32_t expected = 0;
  for (std::size_t k = rows.first_run; k < rows.first_run + rows.run_count; ++k) expected += needs_cells(rows, k) ? 1 : 0;
  if (celled != expected) throw damaged("cells for " + std::to_string(celled) + " rows, expected " + std::to_string(expected));
  for (std::size_t k = rows.first_run; k < rows.first_run + rows.run_count; ++k) {
    if (!needs_cells(rows, k)) continue;
    const std::size_t n = run_samples(k).size(), cells = cell_offset_[k + 1] - cell_offset_[k];
    std::uint32_t stored_n = 0, stored_cells = 0;
    if (!in.u32(stored_n) || !in.u32(stored_cells) || stored_n != n || stored_cells != cells) {
      throw damaged("cell counts of the " + std::to_string(contents_.runs[k].rpm) + " rpm row");
    }
    std::span<const std::uint8_t> cell_of_sample, means;
    if (!in.bytes(n, cell_of_sample) || !in.bytes(cells * tables::kSampleBytes, means)) throw damaged("truncated cells");
    for (CellIndex c : cell_of_sample) {
      if (c >= cells) throw damaged("a cell index out of range");
    }
    std::copy(cell_of_sample.begin(), cell_of_sample.end(), cell_of_sample_.begin() + static_cast<std::ptrdiff_t>(run_offset_[k]));
    const std::vector<tables::LaunchSample> decoded = tables::decode_samples(means);
    std::copy(decoded.begin(), decoded.end(), cell_mean_.begin() + static_cast<std::ptrdiff_t>(cell_offset_[k]));
  }
  if (!in.at_end()) throw damaged("trailing bytes");
}

std::vector<tables::LandingData> Predictor::derived_landing_data() const {
  std::vector<tables::LandingData> out;
  for (std::size_t r = 0; r < materials_.size(); ++r) {
    if (!landing_data_from_table_[r]) out.push_back(encode_landing_data(materials_[r]));
  }
  return out;
}

bool Predictor::has_landing_grid(std::size_t index) const {
  return landing_grid_enabled_ && !grids_[materials_.at(index).material].empty();
}

std::size_t Predictor::landing_grid_bytes() const {
  if (!landing_grid_enabled_) return 0;
  std::size_t bytes = 0;
  for (const auto& grid : grids_) bytes += grid.bytes();
  return bytes;
}

const LandingGrid* Predictor::landing_grid_for(const MaterialRows& rows, double height_m, flight::EffectSet effects,
                                               const flight::Air& air) const {
  const LandingGrid& grid = grids_[rows.material];
  if (!landing_grid_enabled_ || grid.empty() || (effects & ~flight::EffectSet{flight::kWind}) != grid.effects()) {
    return nullptr;
  }
  const bool windy = (effects & flight::kWind) != 0;
  if (windy && air.wind_m_s.z() != 0.0) return nullptr;
  if (!domain_.covers(height_m, windy ? air.wind_m_s.x() : 0.0, windy ? air.wind_m_s.y() : 0.0)) return nullptr;
  return &grid;
}

PredictorWorkspace::PredictorWorkspace(const Predictor& predictor, std::pmr::memory_resource* memory)
    : samples_(memory),
      sample_weight_kg_(memory),
      granules_(memory),
      launches_(memory),
      landings_(memory),
      landing_x_m_(memory),
      landing_y_m_(memory),
      landing_weight_(memory),
      tray_mass_(memory),
      gradients_(memory),
      gradient_scratch_(memory),
      metrics_scratch_(memory),
      chunk_landing_x_m_(memory),
      chunk_landing_y_m_(memory),
      stencil_block_(memory),
      cell_target_(memory),
      search_buffer_(memory) {
  const std::size_t pair = predictor.largest_pair();
  const PredictorLimits& limits = predictor.limits();
  sample_capacity_ = pair;
  samples_.resize(kFlightChunk);
  sample_weight_kg_.resize(kFlightChunk);
  // Two discs, each flown (lateral wind) or mirrored: at most two landings per sample.
  landing_x_m_.resize(2 * pair);
  landing_y_m_.resize(2 * pair);
  landing_weight_.resize(2 * pair);
  granules_.resize(kFlightChunk);
  launches_.resize(kFlightChunk);
  landings_.resize(kFlightChunk);
  chunk_landing_x_m_.resize(kFlightChunk);
  chunk_landing_y_m_.resize(kFlightChunk);
  stencil_block_.resize(1);
  cell_target_.resize(predictor.most_cells());
  const int widest = predictor.tray_capacity(limits.min_tray_width_m);
  tray_capacity_ = static_cast<std::size_t>(widest);
  tray_mass_.resize(tray_capacity_);
  gradients_.resize(tray_capacity_);
  gradient_scratch_.resize(tray_capacity_);
  // The widest bout a request may ask for, in the narrowest trays, plus its cut edge tray: cv_gradient's
  // scratch, at the metrics scratch's end.
  const auto widest_bout = static_cast<std::size_t>(std::ceil(limits.max_bout_width_m / limits.min_tray_width_m)) + 2;
  cv_scratch_size_ = widest_bout;
  // Also a wide kernel's difference arrays (wide_kernel.hpp), which working_widths' FFT scratch exceeds;
  // and during the standard errors' passes (InfluencePass) the prefix sums of their gradients before
  // cv_gradient's tail: SampleInfluence::kMaxGradients gradients of up to ~800 trays in one pass (a wider
  // layout takes more), in the room a buffer of each gradient would take otherwise.
  const metrics::TrayLayout widest_layout{limits.min_tray_width_m, widest};
  metrics_scratch_.resize(std::max({metrics::working_widths_scratch_size(widest), widest_bout, tray_capacity_ + 2,
                                    metrics::wide_kernel_scratch_size(widest_layout)}) +
                          (SampleInfluence::kMaxGradients - 1) * tray_capacity_);
  search_buffer_.resize(4 * tray_capacity_ + widest_bout);
}

std::size_t PredictorWorkspace::bytes() const {
  return samples_.size() * sizeof(tables::LaunchSample) + granules_.size() * sizeof(flight::Granule) +
         launches_.size() * sizeof(flight::State) + landings_.size() * sizeof(flight::Landing) +
         sizeof(double) * (sample_weight_kg_.size() + landing_x_m_.size() + landing_y_m_.size() +
                           landing_weight_.size() + tray_mass_.size() + gradients_.size() +
                           gradient_scratch_.size() + metrics_scratch_.size() + chunk_landing_x_m_.size() +
                           chunk_landing_y_m_.size() + search_buffer_.size()) +
         sizeof(LandingGrid::StencilBlock) * stencil_block_.size() +
         sizeof(tables::LaunchSample) * cell_target_.size();
}

bool Predictor::pairwise(std::size_t run_a, std::size_t run_b) const {
  const auto& a = contents_.runs[run_a];
  const auto& b = contents_.runs[run_b];
  return a.source == "analytic" && b.source == "analytic" && run_samples(run_a).size() == run_samples(run_b).size();
}

bool Predictor::needs_cells(const MaterialRows& rows, std::size_t run) const {
  const std::size_t first = rows.first_run, end = rows.first_run + rows.run_count;
  return (run > first && !pairwise(run - 1, run)) || (run + 1 < end && !pairwise(run, run + 1));
}

QuantileCellCounts Predictor::cell_counts(const MaterialRows& rows) const {
  // One cell count for all rows of the material, so that neighbours are cut into the same cells.
  std::size_t smallest = std::numeric_limits<std::size_t>::max();
  for (std::size_t k = rows.first_run; k < rows.first_run + rows.run_count; ++k) {
    smallest = std::min(smallest, run_samples(k).size());
  }
  return quantile_cells_for(smallest);
}

void Predictor::assign_cells(const MaterialRows& rows) {
  const QuantileCellCounts counts = cell_counts(rows);
  const double density_kg_m3 = contents_.materials[rows.material].density_kg_m3;
  std::vector<double> transverse_x_m, radius_m, mass_kg;  // construction only: may allocate
  std::vector<std::uint32_t> order;
  for (std::size_t k = rows.first_run; k < rows.first_run + rows.run_count; ++k) {
    if (!needs_cells(rows, k)) continue;
    const auto& run = contents_.runs[k];
    const std::span<const tables::LaunchSample> samples = run_samples(k);
    const std::size_t n = samples.size();
    transverse_x_m.resize(n);
    radius_m.resize(n);
    mass_kg.resize(n);
    order.resize(n);
    landing_rank_keys(samples, run.rpm, contents_.machine.disc_radius_m, contents_.machine.disc_height_m,
                      density_kg_m3, default_flight_settings(), radius_m, transverse_x_m);
    for (std::size_t i = 0; i < n; ++i) mass_kg[i] = static_cast<double>(samples[i].mass_kg);
    const std::span<CellIndex> cell_of_sample = std::span(cell_of_sample_).subspan(run_offset_[k], n);
    assign_quantile_cells(radius_m, transverse_x_m, mass_kg, counts, order, cell_of_sample);
    quantile_cell_means(samples, cell_of_sample,
                        std::span(cell_mean_).subspan(cell_offset_[k], cell_offset_[k + 1] - cell_offset_[k]));
  }
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

PredictStatus Predictor::validate(const PredictionRequest& r, double& height_m, RequestProblem* problem) const {
  RequestProblem found;
  // Records the first problem (the field, its value and its range) and returns its status.
  const auto refuse = [&](PredictStatus status, RequestField field, double value, double lower, double upper,
                          const char* rule = "") {
    found = RequestProblem{status, field, value, lower, upper, rule};
    if (problem != nullptr) *problem = found;
    return status;
  };
  const double inf = std::numeric_limits<double>::infinity();
  height_m = std::isnan(r.disc_height_m) ? contents_.machine.disc_height_m : r.disc_height_m;
  const std::pair<RequestField, double> finite_fields[] = {
      {RequestField::kRpm, r.rpm},           {RequestField::kDiscHeight, height_m},   {RequestField::kWindX, r.wind_x_m_s},
      {RequestField::kWindY, r.wind_y_m_s},  {RequestField::kCvTarget, r.cv_target}, {RequestField::kBoutWidth, r.bout_width_m},
      {RequestField::kTrayWidth, r.tray_width_m}, {RequestField::kDropPointTurn, r.drop_point_turn_rad}};
  for (const auto& [field, v] : finite_fields) {
    if (!std::isfinite(v)) return refuse(PredictStatus::kNotFinite, field, v, -inf, inf);
  }
  // Every field's domain, before any is used (docs/c-api.md, PredictorLimits).
  const double lowest_height_m = std::max(0.0, -lowest_sample_z_m_);
  if (height_m < lowest_height_m || height_m > limits_.max_disc_height_m) {
    return refuse(PredictStatus::kOutOfRange, RequestField::kDiscHeight, height_m, lowest_height_m,
                  limits_.max_disc_height_m);
  }
  if (std::abs(r.wind_x_m_s) > limits_.max_wind_m_s) {
    return refuse(PredictStatus::kOutOfRange, RequestField::kWindX, r.wind_x_m_s, -limits_.max_wind_m_s, limits_.max_wind_m_s);
  }
  if (std::abs(r.wind_y_m_s) > limits_.max_wind_m_s) {
    return refuse(PredictStatus::kOutOfRange, RequestField::kWindY, r.wind_y_m_s, -limits_.max_wind_m_s, limits_.max_wind_m_s);
  }
  if (!(r.cv_target > 0.0) || r.cv_target > limits_.max_cv_target) {
    return refuse(PredictStatus::kOutOfRange, RequestField::kCvTarget, r.cv_target, 0.0, limits_.max_cv_target,
                  "above");
  }
  if (r.bout_width_m < 0.0 || r.bout_width_m > limits_.max_bout_width_m) {
    return refuse(PredictStatus::kOutOfRange, RequestField::kBoutWidth, r.bout_width_m, 0.0, limits_.max_bout_width_m);
  }
  if (std::abs(r.drop_point_turn_rad) > kPi) {
    return refuse(PredictStatus::kOutOfRange, RequestField::kDropPointTurn, r.drop_point_turn_rad, -kPi, kPi);
  }
  // Each disc's own setting: NaN is "as both discs"; an infinity is not finite.
  const RequestField disc_rpm_field[2] = {RequestField::kLeftDiscRpm, RequestField::kRightDiscRpm};
  const RequestField disc_turn_field[2] = {RequestField::kLeftDiscDropPointTurn, RequestField::kRightDiscDropPointTurn};
  for (std::size_t d = 0; d < 2; ++d) {
    const double rpm = r.disc_rpm[d], turn_rad = r.disc_drop_point_turn_rad[d];
    if (std::isinf(rpm)) return refuse(PredictStatus::kNotFinite, disc_rpm_field[d], rpm, -inf, inf);
    if (std::isinf(turn_rad)) return refuse(PredictStatus::kNotFinite, disc_turn_field[d], turn_rad, -inf, inf);
    if (std::abs(turn_rad) > kPi) return refuse(PredictStatus::kOutOfRange, disc_turn_field[d], turn_rad, -kPi, kPi);
    if (d == kRightDisc && contents_.machine.disc_count < 2 && (!std::isnan(rpm) || !std::isnan(turn_rad))) {
      return refuse(PredictStatus::kOutOfRange, std::isnan(rpm) ? disc_turn_field[d] : disc_rpm_field[d],
                    std::isnan(rpm) ? turn_rad : rpm, 0.0, 0.0, "given on a one-disc machine (only [0], the left disc, may be set)");
    }
  }
  const std::size_t discs = contents_.machine.disc_count < 2 ? 1 : 2;
  const auto all_given = [&](const std::array<double, 2>& values) {
    for (std::size_t d = 0; d < discs; ++d) {
      if (std::isnan(values[d])) return false;
    }
    return true;
  };
  // A both-discs value that no disc would use is refused, not dropped.
  if (all_given(r.disc_rpm) && r.rpm != 0.0) {
    return refuse(PredictStatus::kOutOfRange, RequestField::kRpm, r.rpm, 0.0, 0.0,
                  "given while every disc has its own speed (set it to 0)");
  }
  if (all_given(r.disc_drop_point_turn_rad) && r.drop_point_turn_rad != 0.0) {
    return refuse(PredictStatus::kOutOfRange, RequestField::kDropPointTurn, r.drop_point_turn_rad, 0.0, 0.0,
                  "given while every disc has its own drop point (set it to 0)");
  }
  if (tray_capacity(r.tray_width_m) == 0) {
    return refuse(PredictStatus::kOutOfRange, RequestField::kTrayWidth, r.tray_width_m, limits_.min_tray_width_m,
                  limits_.max_half_extent_m);
  }
  if (!std::isnan(r.kernel_half_width_m)) {
    if (!std::isfinite(r.kernel_half_width_m)) {
      return refuse(PredictStatus::kNotFinite, RequestField::kKernelHalfWidth, r.kernel_half_width_m, -inf, inf);
    }
    if (r.kernel_half_width_m < 0.0 || r.kernel_half_width_m > limits_.max_kernel_half_width_m) {
      return refuse(PredictStatus::kOutOfRange, RequestField::kKernelHalfWidth, r.kernel_half_width_m, 0.0,
                    limits_.max_kernel_half_width_m);
    }
  }
  if ((r.effects & ~(flight::kAllEffects | kTableEffects)) != 0) {
    return refuse(PredictStatus::kUnknownEffect, RequestField::kEffects, static_cast<double>(r.effects), 0.0, 0.0);
  }
  return PredictStatus::kOk;
}

RequestProblem Predictor::request_problem(const PredictionRequest& request) const {
  RequestProblem problem;
  double height_m = 0.0;
  validate(request, height_m, &problem);
  return problem;
}

DiscSetting disc_setting(const PredictionRequest& request, int disc) {
  const double rpm = request.disc_rpm[static_cast<std::size_t>(disc)];
  const double turn_rad = request.disc_drop_point_turn_rad[static_cast<std::size_t>(disc)];
  return {std::isnan(rpm) ? request.rpm : rpm, std::isnan(turn_rad) ? request.drop_point_turn_rad : turn_rad};
}

void Predictor::disc_samples(PredictorWorkspace& w, const DiscRows& rows, double drop_point_turn_rad, std::size_t first,
                             std::size_t count, std::span<const tables::LaunchSample> cell_target) const {
  interpolate(rows.lower_run, rows.upper_run, rows.t, first, std::span(w.samples_).first(count),
              std::span(w.sample_weight_kg_).first(count), cell_target);
  // The drop point turned by Δ about the disc axis turns the fan of launches by Δ (a disc the same all
  // round, fed continuously, has no phase of its own: test LookupDem.TurningTheFeedTurnsTheLaunchFan).
  // The table's frame is the left disc's, centred on its axis; the right disc is its mirror image, so its
  // drop point turns by Δ mirrored. Positions, velocities and spins turn alike (the landing grid reads
  // the turned horizontal launch as any other).
  if (drop_point_turn_rad != 0.0) {
    const double c = std::cos(drop_point_turn_rad), s = std::sin(drop_point_turn_rad);
    const auto turn = [&](float& x, float& y) {
      const double x0 = x, y0 = y;
      x = static_cast<float>(c * x0 - s * y0);
      y = static_cast<float>(s * x0 + c * y0);
    };
    for (std::size_t i = 0; i < count; ++i) {
      tables::LaunchSample& sample = w.samples_[i];
      turn(sample.x_m, sample.y_m);
      turn(sample.vx_norm, sample.vy_norm);
      turn(sample.wx_norm, sample.wy_norm);
    }
  }
}

std::size_t Predictor::fly_launches(PredictorWorkspace& w, const DiscRows& rows, double drop_point_turn_rad,
                                    double omega_rad_s, double height_m, const flight::Air& air,
                                    flight::EffectSet effects, DiscFlights discs, std::size_t right_offset,
                                    double density_kg_m3, const LandingGrid* grid) const {
  const auto& machine = contents_.machine;
  const bool two_discs = machine.disc_count == 2;
  const double half_spacing_m = two_discs ? 0.5 * machine.disc_spacing_m : 0.0;
  const double rim_speed_m_s = omega_rad_s * machine.disc_radius_m;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::size_t n = interpolated_count(rows.lower_run, rows.upper_run);

  // mirror = +1: the left disc as stored; −1: its mirror image x → −x, the right disc. Spin is an axial
  // vector: under the reflection its x component keeps its sign and y, z change sign.
  auto launch_of = [&](const tables::LaunchSample& s, double mirror, std::size_t slot) {
    flight::Granule& granule = w.granules_[slot];
    granule.diameter_m = s.diameter_m;
    granule.density_kg_m3 = density_kg_m3;
    flight::State& launch = w.launches_[slot];
    launch.position_m = Vec3(mirror * s.x_m, s.y_m, s.z_m + height_m);
    launch.velocity_m_s = rim_speed_m_s * Vec3(mirror * s.vx_norm, s.vy_norm, s.vz_norm);
    launch.spin_rad_s = omega_rad_s * Vec3(s.wx_norm, mirror * s.wy_norm, mirror * s.wz_norm);
  };
  const bool left_flown = discs != DiscFlights::kRightOnly;
  const bool right_flown = discs == DiscFlights::kLeftAndRightFlown || discs == DiscFlights::kRightOnly;
  const double wind_x_m_s = (effects & flight::kWind) != 0 ? air.wind_m_s.x() : 0.0;
  const double wind_y_m_s = (effects & flight::kWind) != 0 ? air.wind_m_s.y() : 0.0;
  // Where the landing of left-disc sample i (or of the right disc's mirror of it, flown) goes: the machine
  // frame, and the mirrored right disc when it is not flown.
  const auto record_left = [&](std::size_t i, double weight, bool landed, double x, double y) {
    if (!landed) x = y = nan;
    w.landing_x_m_[i] = x - half_spacing_m;
    w.landing_y_m_[i] = y;
    w.landing_weight_[i] = weight;
    if (discs == DiscFlights::kLeftOnly) return;
    if (discs == DiscFlights::kLeftAndMirror) {  // the right disc is the left one's mirror image
      w.landing_x_m_[right_offset + i] = half_spacing_m - x;
      w.landing_y_m_[right_offset + i] = y;
    }
    w.landing_weight_[right_offset + i] = weight;
  };
  const auto record_right = [&](std::size_t i, double weight, bool landed, double x, double y) {
    w.landing_x_m_[right_offset + i] = landed ? x + half_spacing_m : nan;
    w.landing_y_m_[right_offset + i] = landed ? y : nan;
    if (!left_flown) w.landing_weight_[right_offset + i] = weight;
  };
  // The samples are interpolated a chunk at a time into the workspace (kFlightChunk flights: half as many
  // samples when both discs are flown), so no buffer holds them all. flight::fly_many flies several at once
  // in SIMD lanes where the effects allow and gives fly_to_ground's landings bit for bit, so the chunking
  // changes no result (a workspace per thread stays small: docs/c-api.md).
  const std::size_t chunk = left_flown && right_flown ? kFlightChunk / 2 : kFlightChunk;
  std::size_t flights = 0;
  const std::span<const tables::LaunchSample> cell_target = cell_targets(w, rows.lower_run, rows.upper_run, rows.t);
  for (std::size_t first = 0; first < n; first += chunk) {
    const std::size_t count = std::min(chunk, n - first);
    disc_samples(w, rows, drop_point_turn_rad, first, count, cell_target);
    if (grid != nullptr) {
      // A block of samples at a time, both discs at once where both are landed (a sample's two landings
      // share the stencil's diameter, vertical speed and height). Only the launch's horizontal motion,
      // height, vertical speed and diameter are needed (no spin, no full state).
      const std::span<const tables::LaunchSample> chunk_samples = std::span(w.samples_).first(count);
      const std::span<double> xs = std::span(w.chunk_landing_x_m_), ys = std::span(w.chunk_landing_y_m_);
      if (left_flown && right_flown) {
        grid->sample_landings(chunk_samples, rim_speed_m_s, height_m, wind_x_m_s, wind_y_m_s,
                              LandingGrid::Sides::kBoth, w.stencil_block_[0], xs, ys);
        for (std::size_t c = 0; c < count; ++c) {
          record_left(first + c, w.sample_weight_kg_[c], true, xs[c], ys[c]);
          record_right(first + c, w.sample_weight_kg_[c], true, xs[count + c], ys[count + c]);
        }
        continue;
      }
      grid->sample_landings(chunk_samples, rim_speed_m_s, height_m, wind_x_m_s, wind_y_m_s,
                            left_flown ? LandingGrid::Sides::kAsStored : LandingGrid::Sides::kMirrored,
                            w.stencil_block_[0], xs, ys);
      for (std::size_t c = 0; c < count; ++c) {
        if (left_flown) {
          record_left(first + c, w.sample_weight_kg_[c], true, xs[c], ys[c]);
        } else {
          record_right(first + c, w.sample_weight_kg_[c], true, xs[c], ys[c]);
        }
      }
      continue;
    }
    // Slots [0, count): the left disc's flights; then the right disc's mirror of each sample, when flown.
    const std::size_t right_slot = left_flown ? count : 0;
    for (std::size_t c = 0; c < count; ++c) {
      if (left_flown) launch_of(w.samples_[c], 1.0, c);
      if (right_flown) launch_of(w.samples_[c], -1.0, right_slot + c);
    }
    const std::size_t slots = right_flown ? right_slot + count : count;
    flight::fly_many(std::span(w.granules_).first(slots), std::span(w.launches_).first(slots), 0.0, air, effects,
                     settings_, std::span(w.landings_).first(slots));
    flights += slots;
    for (std::size_t c = 0; c < count; ++c) {
      const double weight = w.sample_weight_kg_[c];
      if (left_flown) {
        const flight::Landing& landing = w.landings_[c];
        record_left(first + c, weight, landing.landed, landing.state.position_m.x(), landing.state.position_m.y());
      }
      if (right_flown) {
        const flight::Landing& landing = w.landings_[right_slot + c];
        record_right(first + c, weight, landing.landed, landing.state.position_m.x(), landing.state.position_m.y());
      }
    }
  }
  if (left_flown) {
    // R̄ and ξ of the left disc about its centre, from its landings in the machine frame.
    const auto stats = metrics::radial_statistics(std::span(w.landing_x_m_).first(n), std::span(w.landing_y_m_).first(n),
                                                  std::span(w.landing_weight_).first(n), -half_spacing_m, 0.0);
    w.radial_mean_m_ = stats.mean_radius_m;
    w.radial_width_m_ = stats.radial_width_m;
  }
  return flights;
}

namespace {
// values[k] and values[T − 1 − k] both become their sum (T even).
void fold_mirror(std::span<double> values) {
  const std::size_t count = values.size();
  for (std::size_t k = 0; k < count / 2; ++k) {
    const double sum = values[k] + values[count - 1 - k];
    values[k] = sum;
    values[count - 1 - k] = sum;
  }
}
}  // namespace

Predictor::Landed Predictor::land_discs(PredictorWorkspace& w, const MaterialRows& rows, const DiscRows (&disc_rows)[2],
                                         const DiscSetting (&settings)[2], bool per_disc, double height_m,
                                         const flight::Air& air, flight::EffectSet effects, bool fly_right_disc) const {
  // Launch samples at each disc's setting (normalised, scaled during the flight loop), flights, machine
  // frame. The sample blocks say which landings each launch sample of the table owns (the standard
  // errors' samples, SampleInfluence); empty when the discs are alike (sample s owns s and n + s).
  const bool two_discs = contents_.machine.disc_count == 2;
  const DiscSetting& left = settings[kLeftDisc];
  const double density_kg_m3 = contents_.materials[rows.material].density_kg_m3;
  const auto omega_of = [](double rpm) { return rpm * 2.0 * kPi / 60.0; };
  int flights = 0;
  std::size_t n = 0;  // left-disc landings; the right disc's start at n
  std::size_t landings = 0;
  SampleBlock* const blocks = w.sample_blocks_.data();
  std::size_t& block_count = w.sample_block_count_;
  block_count = 0;
  std::size_t sample_total = 0;  // independent launch samples behind the pattern
  if (!per_disc) {
    const DiscRows& r = disc_rows[0];
    const LandingGrid* grid = landing_grid_for(rows, height_m, effects, air);
    n = interpolated_count(r.lower_run, r.upper_run);
    const DiscFlights discs = !two_discs        ? DiscFlights::kLeftOnly
                              : fly_right_disc ? DiscFlights::kLeftAndRightFlown
                                               : DiscFlights::kLeftAndMirror;
    flights = static_cast<int>(fly_launches(w, r, left.drop_point_turn_rad, omega_of(left.rpm), height_m, air, effects,
                                            discs, n, density_kg_m3, grid));
    landings = two_discs ? 2 * n : n;
    sample_total = n;
  } else {
    // One disc after the other through the same sample buffers; each disc's landings carry half of the
    // machine's mass (both discs are fed alike), whatever the count of its samples.
    std::size_t disc_count[2] = {0, 0};
    for (int d = 0; d < 2; ++d) {
      const DiscRows& r = disc_rows[d];
      const LandingGrid* grid = landing_grid_for(rows, height_m, effects, air);
      const std::size_t count = interpolated_count(r.lower_run, r.upper_run);
      disc_count[d] = count;
      if (d == kLeftDisc) n = count;
      flights += static_cast<int>(fly_launches(w, r, settings[d].drop_point_turn_rad, omega_of(settings[d].rpm), height_m,
                                               air, effects,
                                               d == kLeftDisc ? DiscFlights::kLeftOnly : DiscFlights::kRightOnly, n,
                                               density_kg_m3, grid));
      double disc_kg = 0.0;
      const std::span<double> disc_weights = std::span(w.landing_weight_).subspan(d == kLeftDisc ? 0 : n, count);
      for (double weight : disc_weights) disc_kg += weight;
      for (double& weight : disc_weights) weight = disc_kg > 0.0 ? 0.5 * weight / disc_kg : 0.0;
    }
    landings = disc_count[0] + disc_count[1];
    // A launch sample of the table is one sample however many discs it feeds: the discs' blocks by source
    // row (interpolate(): a row alone or rows pairwise is one block of the lower row's samples, quantile
    // cells the lower row's then the upper row's), a source both discs draw on shared.
    struct RowBlock {
      std::size_t run, count, first_landing;
    };
    // Rows that interpolate pairwise draw the same granules (the analytic builder's sample k is one
    // granule in every row): such a chain of rows is one source, named by its first row.
    const auto source_of = [&](std::size_t run) {
      while (run > rows.first_run && pairwise(run - 1, run)) --run;
      return run;
    };
    RowBlock row_blocks[2][2];
    std::size_t row_block_count[2] = {0, 0};
    for (int d = 0; d < 2; ++d) {
      const DiscRows& r = disc_rows[d];
      const std::size_t first = d == kLeftDisc ? 0 : n;
      const std::size_t lower_count = run_samples(r.lower_run).size();
      row_blocks[d][row_block_count[d]++] = {source_of(r.lower_run), lower_count, first};
      if (r.lower_run != r.upper_run && !pairwise(r.lower_run, r.upper_run)) {
        row_blocks[d][row_block_count[d]++] = {source_of(r.upper_run), run_samples(r.upper_run).size(),
                                               first + lower_count};
      }
    }
    bool right_shared[2] = {false, false};
    for (std::size_t i = 0; i < row_block_count[0]; ++i) {
      SampleBlock block{row_blocks[0][i].count, {row_blocks[0][i].first_landing, SampleBlock::kNoLanding}};
      for (std::size_t j = 0; j < row_block_count[1]; ++j) {
        if (row_blocks[1][j].run == row_blocks[0][i].run && row_blocks[1][j].count == row_blocks[0][i].count) {
          block.first_landing[kRightDisc] = row_blocks[1][j].first_landing;
          right_shared[j] = true;
        }
      }
      blocks[block_count++] = block;
    }
    for (std::size_t j = 0; j < row_block_count[1]; ++j) {
      if (!right_shared[j]) {
        blocks[block_count++] = SampleBlock{row_blocks[1][j].count, {SampleBlock::kNoLanding, row_blocks[1][j].first_landing}};
      }
    }
    for (std::size_t b = 0; b < block_count; ++b) sample_total += blocks[b].count;
  }
  Landed landed;
  landed.left_landings = n;
  landed.landings = landings;
  landed.samples = sample_total;
  landed.flights = flights;
  // Each disc's landings by source row: quantile cells write the lower row's granules, then the upper
  // row's (interpolate()); a row alone or rows interpolated pairwise are one part.
  int interpolating = 0;
  for (int d = 0; d < (two_discs ? 2 : 1); ++d) {
    const DiscRows& r = disc_rows[per_disc ? d : 0];
    const std::size_t first = d == kLeftDisc ? 0 : n;
    DiscRowParts& parts = landed.row_parts[d];
    parts.lower_first = first;
    parts.lower_count = interpolated_count(r.lower_run, r.upper_run);
    if (r.lower_run != r.upper_run && !pairwise(r.lower_run, r.upper_run)) {
      parts.lower_count = run_samples(r.lower_run).size();
      parts.upper_first = first + parts.lower_count;
      parts.upper_count = run_samples(r.upper_run).size();
      landed.upper_weight += r.t;
      ++interpolating;
    }
  }
  if (interpolating > 0) landed.upper_weight /= interpolating;
  return landed;
}

PredictStatus Predictor::predict(const PredictionRequest& request, Prediction& out) {
  return predict(request, out, *own_workspace_);
}

PredictStatus Predictor::predict(const PredictionRequest& request, Prediction& out, PredictorWorkspace& w) const {
  if (w.sample_capacity_ < largest_pair_ ||
      w.tray_capacity_ < static_cast<std::size_t>(tray_capacity(limits_.min_tray_width_m))) {
    throw std::invalid_argument("Predictor::predict: the workspace was made for a smaller table");
  }
  double height_m = 0.0;
  if (const PredictStatus s = validate(request, height_m); s != PredictStatus::kOk) return s;
  const auto material_index = find_material(request.material);
  if (!material_index) return PredictStatus::kUnknownMaterial;
  const MaterialRows& rows = materials_[*material_index];
  const bool two_discs = contents_.machine.disc_count == 2;
  const DiscSetting left = disc_setting(request, kLeftDisc);
  const DiscSetting right = two_discs ? disc_setting(request, kRightDisc) : left;
  // Discs at their own settings each get their own samples, flights and landings; alike, the right disc
  // is the left one's mirror image (flown as such only in a lateral wind).
  const bool per_disc = two_discs && !(left == right);
  DiscRows disc_rows[2];
  const DiscSetting settings[2] = {left, right};
  for (int d = 0; d < (per_disc ? 2 : 1); ++d) {
    const auto bracket = bracket_rpm(std::span(run_rpm_).subspan(rows.first_run, rows.run_count), settings[d].rpm);
    if (!bracket) return PredictStatus::kRpmOutsideTable;
    // On a row (t = 0) that row alone.
    disc_rows[d].lower_run = rows.first_run + bracket->lower;
    disc_rows[d].upper_run = bracket->upper_weight == 0.0 ? disc_rows[d].lower_run : rows.first_run + bracket->upper;
    disc_rows[d].t = bracket->upper_weight;
  }
  if (!per_disc) disc_rows[1] = disc_rows[0];

  flight::EffectSet effects = 0;
  flight::Air air;
  flight_conditions(request, disc_rows, effects, air);
  if (limits_.refuse_outside_domain && !request.fly_outside_domain &&
      landing_grid_for(rows, height_m, effects, air) == nullptr && landing_domain_miss(request) != DomainMiss::kNone) {
    return PredictStatus::kOutsideDomain;
  }
  const bool windy = (effects & flight::kWind) != 0;
  const bool fly_right_disc = two_discs && (per_disc || (windy && request.wind_x_m_s != 0.0));

  // 1–4. Launch samples at each disc's setting, flights, machine frame (a function of its own: its
  // bookkeeping is off the stack by the time the standard errors' passes run).
  const Landed landed = land_discs(w, rows, disc_rows, settings, per_disc, height_m, air, effects, fly_right_disc);
  measure(request, landed, per_disc, fly_right_disc, effects, height_m, settings, out, w);
  // After measure() has returned: its frame is off the stack (the C API's stack budget holds unoptimised too).
  if (request.standard_errors && request.interpolation_error) {
    const bool mirrored = two_discs && !fly_right_disc && out.kernel_half_width_m > 0.0;
    add_interpolation_error(request, landed, mirrored, out, w);
  }
  return PredictStatus::kOk;
}

void Predictor::flight_conditions(const PredictionRequest& request, const DiscRows (&disc_rows)[2],
                                  flight::EffectSet& effects, flight::Air& air) const {
  // Wind: a zero wind is no wind (the still-air right-hand side is cheaper). Only a lateral component
  // breaks the left/right mirror symmetry; wind along y is symmetric under x → −x.
  effects = request.effects & flight::kAllEffects;
  if ((request.effects & kTableEffects) != 0) {
    for (const DiscRows& r : disc_rows) effects |= run_effects_[r.lower_run] | run_effects_[r.upper_run];
    if (request.wind_x_m_s != 0.0 || request.wind_y_m_s != 0.0) effects |= flight::kWind;
  }
  air = flight::Air{};
  const bool windy = (effects & flight::kWind) != 0 && (request.wind_x_m_s != 0.0 || request.wind_y_m_s != 0.0);
  if (windy) {
    air.wind_m_s = Vec3(request.wind_x_m_s, request.wind_y_m_s, 0.0);
  } else {
    effects &= ~flight::EffectSet{flight::kWind};
  }
}

Predictor::DomainMiss Predictor::landing_domain_miss(const PredictionRequest& request) const {
  const auto material_index = find_material(request.material);
  if (!material_index) return DomainMiss::kNone;
  const MaterialRows& rows = materials_[*material_index];
  const LandingGrid& grid = grids_[rows.material];
  if (!landing_grid_enabled_ || grid.empty()) return DomainMiss::kNone;
  // A grid's material flies the same still-air effects in every row (grid_effects), so the first
  // row stands for any the request falls between.
  const DiscRows first_row[2] = {{rows.first_run, rows.first_run, 0.0}, {rows.first_run, rows.first_run, 0.0}};
  flight::EffectSet effects = 0;
  flight::Air air;
  flight_conditions(request, first_row, effects, air);
  if ((effects & ~flight::EffectSet{flight::kWind}) != grid.effects()) return DomainMiss::kEffects;
  const double height_m = std::isnan(request.disc_height_m) ? contents_.machine.disc_height_m : request.disc_height_m;
  if (!(height_m >= domain_.min_disc_height_m && height_m <= domain_.max_disc_height_m)) return DomainMiss::kHeight;
  if (!domain_.covers(height_m, air.wind_m_s.x(), air.wind_m_s.y())) return DomainMiss::kWind;
  return DomainMiss::kNone;
}

void Predictor::measure(const PredictionRequest& request, const Landed& landed, bool per_disc, bool fly_right_disc,
                        flight::EffectSet effects, double height_m, const DiscSetting (&settings)[2], Prediction& out,
                        PredictorWorkspace& w) const {
  // Step 5, from the landings in the workspace.
  const bool two_discs = contents_.machine.disc_count == 2;
  const DiscSetting& left = settings[kLeftDisc];
  const DiscSetting& right = settings[kRightDisc];
  const int flights = landed.flights;
  const std::size_t n = landed.left_landings, landings = landed.landings, sample_total = landed.samples;
  const std::span<const double> xs = std::span(w.landing_x_m_).first(landings);
  const std::span<const double> ys = std::span(w.landing_y_m_).first(landings);
  const std::span<double> weights = std::span(w.landing_weight_).first(landings);

  // 5. Kernel, trays fitted to the landings plus the kernel (symmetric about the centre line), capped at
  // the widest layout.
  if (!per_disc) {
    double total_kg = 0.0;
    for (double weight : weights) total_kg += weight;
    // Weights as fractions of the machine's discharged mass: the tray contents then read directly as the
    // share of the application rate per tray.
    const double scale = total_kg > 0.0 ? 1.0 / total_kg : 0.0;
    for (double& weight : weights) weight *= scale;
  }
  double kernel_m = request.kernel_half_width_m;
  if (std::isnan(kernel_m)) {
    // One disc's lateral spread; with two discs the root mean square of both, so that the choice is the
    // same for the wind from the left and its mirror image from the right.
    double sd_m = lateral_sd_m(xs.first(n), weights.first(n));
    if (two_discs) {
      const double right_sd_m = lateral_sd_m(xs.subspan(n), weights.subspan(n));
      sd_m = std::sqrt(0.5 * (sd_m * sd_m + right_sd_m * right_sd_m));
    }
    // Discs at their own settings: the samples per disc on average.
    kernel_m = kernel_half_width_for(sd_m, per_disc ? (landings + 1) / 2 : n);
  }
  double half_extent_m = request.tray_width_m;
  for (double x : xs) {
    if (std::isfinite(x)) half_extent_m = std::max(half_extent_m, std::abs(x) + kernel_m);
  }
  half_extent_m = std::min(half_extent_m, limits_.max_half_extent_m);
  metrics::TrayLayout trays = metrics::tray_layout_covering(half_extent_m, request.tray_width_m);
  // Always an even number of trays: the tray edges then sit at whole multiples of the tray width from the
  // centre line wherever the outermost landing falls, so the grid never shifts by half a tray between two
  // predictions whose landings reach a little further or less far (a shift moves every tray, every CV and
  // the throw width by a fraction of a tray at once).
  const int capacity = tray_capacity(request.tray_width_m);
  if (trays.tray_count % 2 != 0) ++trays.tray_count;
  if (trays.tray_count > capacity) trays.tray_count = capacity - capacity % 2;
  const auto tray_count = static_cast<std::size_t>(trays.tray_count);
  const std::span<double> tray_mass = std::span(w.tray_mass_).first(tray_count);
  std::fill(tray_mass.begin(), tray_mass.end(), 0.0);
  // The right disc mirrored (x_right = −x_left exactly: both are differences of the same two numbers) on a
  // layout symmetric about the centre line: its kernel mass is the left disc's, tray k's going to tray
  // T − 1 − k, so only the left disc's landings are spread and the trays are then folded. (Not with
  // point masses: a landing on a tray edge belongs to the tray to its right on both sides, which is not
  // mirror symmetric.)
  const bool mirrored = two_discs && !fly_right_disc && kernel_m > 0.0;
  double lost = 0.0;
  if (mirrored) {
    lost = 2.0 * metrics::accumulate_transverse_kernel(xs.first(n), weights.first(n), trays, kernel_m, tray_mass,
                                                       w.metrics_scratch_);
    fold_mirror(tray_mass);
  } else {
    lost = metrics::accumulate_transverse_kernel(xs, weights, trays, kernel_m, tray_mass, w.metrics_scratch_);
  }

  // Written into `out` in place (every request check is behind us): a Prediction with its bands is over
  // a kilobyte, and the C API's stack budget has no room for a second one.
  Prediction& p = out;
  std::construct_at(&p);  // reset in place: no temporary Prediction on the stack, also unoptimised
  p.trays = trays;
  p.flights = flights;
  p.disc_height_m = height_m;
  p.lost_mass_fraction = std::clamp(lost, 0.0, 1.0);
  p.sample_count = sample_total;
  p.discs[kLeftDisc] = left;
  p.discs[kRightDisc] = two_discs ? right : DiscSetting{std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};
  p.effects = effects;
  p.kernel_half_width_m = kernel_m;
  const metrics::ThrowExtent extent = metrics::throw_extent(tray_mass, trays, 0.99);
  p.throw_width_m = extent.right_m - extent.left_m;
  // Both working widths in O(T log T) (metrics::working_widths): the whole-tray scan is O(T²), 0.13 s at
  // 4,000 trays of 5 cm.
  const std::span<double> metrics_scratch(w.metrics_scratch_);
  // In the workspace, as the bookkeeping of the standard errors below: the bands make them hundreds of bytes,
  // and the C API's stack budget holds in an unoptimised build too.
  ::new (static_cast<void*>(&w.widths_))
      metrics::WorkingWidths(metrics::working_widths(tray_mass, trays, request.cv_target, metrics_scratch));
  const metrics::WorkingWidths& widths = w.widths_;
  const metrics::WorkingWidth& to_and_fro = widths.to_and_fro;
  const metrics::WorkingWidth& racetrack = widths.racetrack;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // The bands (metrics::WorkingWidth) with the standard errors the headline rule needs
  // (docs/metrics.md "Effective working width"): per band the CV at its widest whole-tray bout, its
  // lowest CV and its upper end; per to-and-fro band also the racetrack CV at that bout (the CVs a
  // request without a bout width reports are at the headline band's widest bout). All standard errors
  // share passes over the landings of SampleInfluence::kMaxGradients gradients each (one pass for a
  // pattern with one band per overlap).
  // Per band beside its PredictedBand (written in place into p): to-and-fro bands also carry the racetrack
  // CV at their bout and its standard error.
  using BandExtra = PredictorWorkspace::BandExtra;
  const auto extras = [&w](int o) { return &w.band_extras_[static_cast<std::size_t>(o) * kMaxBands]; };
  w.band_extras_.fill(BandExtra{});
  PredictedBand* band_out[2] = {p.bands_to_and_fro, p.bands_racetrack};
  const metrics::WorkingWidth* overlap_widths[2] = {&to_and_fro, &racetrack};
  const metrics::Overlap overlaps[2] = {metrics::Overlap::kToAndFro, metrics::Overlap::kRacetrack};
  // One standard error to compute: of the CV at `trays` trays, or (width_band set) of that band's
  // interpolated upper end W* = (n + (t − c_n)/(c_{n+1} − c_n))·w, whose gradient combines the gradients
  // of the two CVs around the crossing.
  using SeTask = PredictorWorkspace::SeTask;
  SeTask* const tasks = w.se_tasks_.data();
  std::size_t task_count = 0;
  const int request_bout_trays =
      request.bout_width_m > 0.0 ? metrics::bout_tray_count(trays, request.bout_width_m) : 0;
  double request_cv[2] = {nan, nan}, request_cv_se[2] = {nan, nan};
  if (request_bout_trays > 0) {
    for (int o = 0; o < 2; ++o) {
      request_cv[o] = metrics::cv_at_trays(tray_mass, trays, request_bout_trays, overlaps[o], metrics_scratch);
      if (std::isfinite(request_cv[o])) tasks[task_count++] = {&request_cv_se[o], overlaps[o], request_bout_trays, nullptr};
    }
  }
  for (int o = 0; o < 2; ++o) {
    const metrics::WorkingWidth& ww = *overlap_widths[o];
    for (int b = 0; b < ww.stored_bands(); ++b) {
      const metrics::WidthBand& in = ww.bands[b];
      BandExtra& extra = extras(o)[b];
      PredictedBand& band = band_out[o][b];
      extra.band = &in;
      band.lower_m = in.lower_m;
      band.upper_m = in.upper_m;
      band.upper_se_m = nan;
      band.bout_width_m = in.trays_below * trays.tray_width_m;
      band.cv = in.cv_below;
      band.cv_se = nan;
      band.lowest_cv = in.lowest_cv;
      band.lowest_cv_se = nan;
      band.lowest_cv_bout_width_m = in.lowest_cv_trays * trays.tray_width_m;
      band.limited_by_layout = in.limited_by_layout;
      tasks[task_count++] = {&band.cv_se, overlaps[o], in.trays_below, nullptr};
      if (in.lowest_cv_trays != in.trays_below) {
        tasks[task_count++] = {&band.lowest_cv_se, overlaps[o], in.lowest_cv_trays, nullptr};
      }
      if (!in.limited_by_layout && std::isfinite(in.cv_above) && in.cv_above > in.cv_below) {
        tasks[task_count++] = {&band.upper_se_m, overlaps[o], in.trays_below, &in};
      }
      // The gap before this band (when the band before is its neighbour: the last stored band follows the
      // one before it only when every band is stored): its highest CV over the whole-tray bouts between.
      band.gap_peak_cv = nan;
      band.gap_peak_cv_se = nan;
      // Only with standard errors: without them no gap can join two bands (a search's predictions skip it).
      if (request.standard_errors && b > 0 && (b < kMaxBands - 1 || ww.band_count == ww.stored_bands())) {
        const int first = ww.bands[b - 1].trays_below + 1;
        const int last = static_cast<int>(std::ceil(in.lower_m / trays.tray_width_m - 1e-9)) - 1;
        int peak_trays = first;
        double peak = -std::numeric_limits<double>::infinity();
        for (int gap_trays = first; gap_trays <= last; ++gap_trays) {
          const double cv = metrics::cv_at_trays(tray_mass, trays, gap_trays, overlaps[o], metrics_scratch);
          if (!(cv <= peak)) {
            peak = cv;
            peak_trays = gap_trays;
          }
        }
        if (last >= first) {
          band.gap_peak_cv = peak;
          if (std::isfinite(peak)) tasks[task_count++] = {&band.gap_peak_cv_se, overlaps[o], peak_trays, nullptr};
        }
      }
      if (o == 0 && request_bout_trays == 0) {
        extra.racetrack_cv =
            metrics::cv_at_trays(tray_mass, trays, in.trays_below, metrics::Overlap::kRacetrack, metrics_scratch);
        if (std::isfinite(extra.racetrack_cv)) {
          tasks[task_count++] = {&extra.racetrack_cv_se, metrics::Overlap::kRacetrack, in.trays_below, nullptr};
        }
      }
    }
  }
  p.throw_width_se_m = nan;
  if (p.throw_width_m > 0.0) tasks[task_count++] = {&p.throw_width_se_m, metrics::Overlap::kToAndFro, 0, nullptr, true};
  // With the right disc mirrored a sample's two landings x and −x contribute Σ_k g_k K_k(x) + Σ_k g_k
  // K_k(−x) = Σ_k (g_k + g_{T−1−k}) K_k(x): the folded gradient at the left landing alone, half the pass.
  // Each gradient is made in the workspace's one gradient buffer and handed to the pass, which keeps what
  // it needs of it (its prefix sums) in the metrics' scratch — all but the tail that cv_gradient uses,
  // which is free at those moments (the binning and the working widths are done).
  const std::span<double> cv_scratch = metrics_scratch.last(w.cv_scratch_size_);
  const std::span<double> pass_scratch = metrics_scratch.first(metrics_scratch.size() - w.cv_scratch_size_);
  const SampleInfluence influence{xs,     weights, sample_total, two_discs ? 2u : 1u, trays, kernel_m,
                                  std::span<const SampleBlock>(w.sample_blocks_.data(), w.sample_block_count_),
                                  pass_scratch};
  const SampleInfluence left_influence{xs.first(n), weights.first(n), n, 1u, trays, kernel_m, {}, pass_scratch};
  const SampleInfluence& pass_influence = mirrored ? left_influence : influence;
  const std::span<double> grad = std::span(w.gradients_).first(tray_count);
  const std::span<double> scratch = std::span(w.gradient_scratch_).first(tray_count);
  // Without standard errors (a search comparing settings) the passes are skipped: about half the cost.
  if (!request.standard_errors) task_count = 0;
  const std::size_t per_pass = InfluencePass::capacity(pass_influence);
  if (task_count > 0 && per_pass == 0) {
    throw std::logic_error("Predictor: the workspace's scratch holds no gradient of " + std::to_string(tray_count) +
                           " trays");
  }
  for (std::size_t first = 0; first < task_count; first += per_pass) {
    const std::size_t count = std::min(task_count - first, per_pass);
    InfluencePass pass(pass_influence, count);
    for (std::size_t g = 0; g < count; ++g) {
      const SeTask& task = tasks[first + g];
      if (task.throw_width) {
        if (!throw_width_gradient(tray_mass, trays, extent, 0.99, grad)) {
          pass.set_gradient(g, {});  // no density at a quantile: NaN
          continue;
        }
      } else if (task.width_band == nullptr) {
        metrics::cv_gradient(tray_mass, trays, task.trays, task.overlap, grad, cv_scratch);
      } else {
        const metrics::WidthBand& in = *task.width_band;
        const double span = in.cv_above - in.cv_below;
        const double d_below = -trays.tray_width_m * (in.cv_above - request.cv_target) / (span * span);
        const double d_above = -trays.tray_width_m * (request.cv_target - in.cv_below) / (span * span);
        metrics::cv_gradient(tray_mass, trays, in.trays_below, task.overlap, grad, cv_scratch);
        metrics::cv_gradient(tray_mass, trays, in.trays_below + 1, task.overlap, scratch, cv_scratch);
        for (std::size_t k = 0; k < tray_count; ++k) grad[k] = d_below * grad[k] + d_above * scratch[k];
      }
      if (mirrored) fold_mirror(grad);
      pass.set_gradient(g, grad);
    }
    double pass_se[SampleInfluence::kMaxGradients];
    pass.standard_errors(std::span(pass_se, count));
    for (std::size_t g = 0; g < count; ++g) *tasks[first + g].out = pass_se[g];
  }

  // The headline: the widest band whose lowest CV meets the target at 95 % confidence over the launch
  // samples (CV + 1.96 SE <= target); a band that the samples do not establish is reported but not taken.
  // Bands whose gap the samples do not show above the target (its peak CV − 1.96 SE <= target) count as
  // one: a band that splits near the target in one draw of the granules and not in another must not take
  // the headline metres away. When none is established, the first band.
  int headline[2] = {-1, -1};
  for (int o = 0; o < 2; ++o) {
    const int stored = overlap_widths[o]->stored_bands();
    bool group_established = false;
    for (int b = 0; b < stored; ++b) {
      PredictedBand& band = band_out[o][b];
      if (extras(o)[b].band->lowest_cv_trays == extras(o)[b].band->trays_below) band.lowest_cv_se = band.cv_se;
      band.established = request.standard_errors
                             ? band.lowest_cv + kConfidence95 * band.lowest_cv_se <= request.cv_target
                             : band.lowest_cv <= request.cv_target;
      band.joins_previous = request.standard_errors && std::isfinite(band.gap_peak_cv) &&
                            band.gap_peak_cv - kConfidence95 * band.gap_peak_cv_se <= request.cv_target;
      group_established = band.established || (band.joins_previous && group_established);
      if (group_established) headline[o] = b;
    }
    if (headline[o] < 0 && stored > 0) headline[o] = 0;
  }
  double* widths_out[2] = {&p.working_width_to_and_fro_m, &p.working_width_racetrack_m};
  double* widths_se_out[2] = {&p.working_width_to_and_fro_se_m, &p.working_width_racetrack_se_m};
  for (int o = 0; o < 2; ++o) {
    const PredictedBand* h = headline[o] >= 0 ? &band_out[o][headline[o]] : nullptr;
    *widths_out[o] = h != nullptr ? h->upper_m : 0.0;
    *widths_se_out[o] = h != nullptr ? h->upper_se_m : nan;
  }
  p.headline_band_to_and_fro = headline[0];
  p.headline_band_racetrack = headline[1];
  p.cv_crossings_to_and_fro = to_and_fro.crossings;
  p.cv_crossings_racetrack = racetrack.crossings;
  p.band_count_to_and_fro = to_and_fro.band_count;
  p.band_count_racetrack = racetrack.band_count;
  p.first_band_width_to_and_fro_m = to_and_fro.first_band_upper_m();
  p.first_band_width_racetrack_m = racetrack.first_band_upper_m();
  // The CVs: at the requested bout, or without one at the to-and-fro headline band's widest whole-tray
  // bout (the working width itself lies between two whole-tray widths, where no CV is defined).
  if (request_bout_trays > 0) {
    p.bout_width_m = request_bout_trays * trays.tray_width_m;
    p.cv_to_and_fro = request_cv[0];
    p.cv_racetrack = request_cv[1];
    p.cv_to_and_fro_se = request_cv_se[0];
    p.cv_racetrack_se = request_cv_se[1];
  } else if (headline[0] >= 0) {
    const PredictedBand& h = band_out[0][headline[0]];
    p.bout_width_m = h.bout_width_m;
    p.cv_to_and_fro = h.cv;
    p.cv_to_and_fro_se = h.cv_se;
    p.cv_racetrack = extras(0)[headline[0]].racetrack_cv;
    p.cv_racetrack_se = extras(0)[headline[0]].racetrack_cv_se;
  } else {
    p.bout_width_m = 0.0;
    p.cv_to_and_fro = p.cv_racetrack = p.cv_to_and_fro_se = p.cv_racetrack_se = nan;
  }
  p.mean_radius_m = w.radial_mean_m_;
  p.radial_width_m = w.radial_width_m_;
  p.tray_mass_fraction = tray_mass;
  p.landing_x_m = xs;
  p.left_landing_count = n;
  p.landing_y_m = ys;
  p.landing_mass_fraction = weights;
}

void Predictor::add_interpolation_error(const PredictionRequest& request, const Landed& landed, bool mirrored,
                                        Prediction& p, PredictorWorkspace& w) const {
  InterpolationErrorInput in;
  in.x_m = std::span(w.landing_x_m_).first(landed.landings);
  in.weight = std::span(w.landing_weight_).first(landed.landings);
  in.discs[kLeftDisc] = landed.row_parts[kLeftDisc];
  in.discs[kRightDisc] = landed.row_parts[kRightDisc];
  in.disc_count = contents_.machine.disc_count == 2 ? 2 : 1;
  if (!interpolates_by_cells(in)) return;
  in.mirrored = mirrored;
  in.trays = p.trays;
  in.kernel_half_width_m = p.kernel_half_width_m;
  in.upper_weight = landed.upper_weight;
  in.cv_target = request.cv_target;
  in.bout_trays = p.bout_width_m > 0.0 ? static_cast<int>(std::lround(p.bout_width_m / p.trays.tray_width_m)) : 0;
  const int headline[2] = {p.headline_band_to_and_fro, p.headline_band_racetrack};
  const PredictedBand* bands[2] = {p.bands_to_and_fro, p.bands_racetrack};
  for (int o = 0; o < 2; ++o) {
    if (headline[o] < 0) continue;
    in.headline_lower_m[o] = bands[o][headline[o]].lower_m;
    in.headline_upper_m[o] = bands[o][headline[o]].upper_m;
  }
  InterpolatedFigures answer;
  answer.throw_width_m = p.throw_width_m;
  answer.working_width_m[0] = p.working_width_to_and_fro_m;
  answer.working_width_m[1] = p.working_width_racetrack_m;
  answer.cv[0] = p.cv_to_and_fro;
  answer.cv[1] = p.cv_racetrack;
  // The standard errors' buffers are free by now (their passes are done, the bands copied out).
  const std::size_t tray_count = static_cast<std::size_t>(p.trays.tray_count);
  const InterpolationErrorScratch scratch{std::span(w.gradients_).first(tray_count),
                                          std::span(w.gradient_scratch_).first(tray_count), w.metrics_scratch_,
                                          &w.widths_};
  const InterpolatedFigures e = interpolation_error(in, answer, scratch);
  p.interpolation_se = e;
  const auto combine = [](double& se, double error) {
    if (!std::isnan(error)) se = std::hypot(se, error);
  };
  combine(p.throw_width_se_m, e.throw_width_m);
  combine(p.working_width_to_and_fro_se_m, e.working_width_m[0]);
  combine(p.working_width_racetrack_se_m, e.working_width_m[1]);
  combine(p.cv_to_and_fro_se, e.cv[0]);
  combine(p.cv_racetrack_se, e.cv[1]);
}

}  // namespace spread::predict
