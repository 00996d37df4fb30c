// The Predictor's derived data per material, made once at construction or restored from the table's
// landing data (tables::LandingData, landing_data_codec.hpp): the landing grid of a drag-only material
// (landing_grid.hpp) and the quantile cells of rows interpolated by cells (launch_quantile_cells.hpp).
// What a table stores is keyed by the model (landing_data_model) and by a digest of the rows it was
// derived from (landing_source_key): data of other rows or another model is derived afresh, never used.
#include <algorithm>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "libspread/analysis/predict/flight_defaults.hpp"
#include "libspread/analysis/predict/landing_data_codec.hpp"
#include "libspread/analysis/predict/launch_landing_keys.hpp"
#include "libspread/analysis/predict/launch_quantile_cells.hpp"
#include "libspread/analysis/predict/predictor.hpp"
#include "libspread/io/tables/row_checksum.hpp"
#include "libspread/io/tables/sample_codec.hpp"

namespace spread::predict {

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

}  // namespace spread::predict
