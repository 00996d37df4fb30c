// The landings stage of predict() (predictor.hpp): each disc's launch samples at its setting (rows
// interpolated pairwise or by quantile cells, turned by the drop point), flown or read off the landing
// grid, in the machine frame — the left disc centre at x = −s/2, the right disc its mirror image
// (docs/design.md §3); with a lateral wind the mirror trick is invalid (the wind breaks the symmetry), so
// the right disc's launches are mirrored and flown themselves — and which landings each launch sample of
// the table owns (the standard errors' samples, SampleInfluence; the interpolation's own error,
// DiscRowParts).
#include <algorithm>
#include <cmath>
#include <limits>
#include <span>

#include "libspread/analysis/metrics/metrics.hpp"
#include "libspread/analysis/predict/launch_interpolation.hpp"
#include "libspread/analysis/predict/launch_quantile_cells.hpp"
#include "libspread/analysis/predict/prediction_context.hpp"
#include "libspread/analysis/predict/predictor.hpp"

namespace spread::predict {

std::size_t Predictor::interpolated_count(std::size_t lower_run, std::size_t upper_run) const {
  if (lower_run == upper_run || pairwise(lower_run, upper_run)) return run_samples(lower_run).size();
  return run_samples(lower_run).size() + run_samples(upper_run).size();
}

CelledRow Predictor::celled(std::size_t run) const {
  return CelledRow{run_samples(run), std::span(cell_of_sample_).subspan(run_offset_[run], run_samples(run).size()),
                   std::span(cell_mean_).subspan(cell_offset_[run], cell_offset_[run + 1] - cell_offset_[run])};
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

// Where a disc's landings go in the workspace's landing arrays (machine frame, both discs): left-disc
// landing i at i, right-disc landing i at right_offset + i, each with the mass it stands for.
struct LandingSlots {
  std::span<double> x_m, y_m, weight;
  std::size_t right_offset = 0;
  double half_spacing_m = 0.0;  // the disc centres at ∓ this (0 on a one-disc machine)
  bool left_only = false;       // the left disc alone lands on this pass
  bool right_mirrored = false;  // the right disc is the left one's mirror image, not flown
  bool left_flown = true;       // false: the right disc alone

  // The left disc's landing i at (x, y) about its centre (not landed: NaN), and the mirrored right
  // disc's when it is not flown.
  void record_left(std::size_t i, double mass, bool landed, double x, double y) const {
    if (!landed) x = y = std::numeric_limits<double>::quiet_NaN();
    x_m[i] = x - half_spacing_m;
    y_m[i] = y;
    weight[i] = mass;
    if (left_only) return;
    if (right_mirrored) {
      x_m[right_offset + i] = half_spacing_m - x;
      y_m[right_offset + i] = y;
    }
    weight[right_offset + i] = mass;
  }
  void record_right(std::size_t i, double mass, bool landed, double x, double y) const {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    x_m[right_offset + i] = landed ? x + half_spacing_m : nan;
    y_m[right_offset + i] = landed ? y : nan;
    if (!left_flown) weight[right_offset + i] = mass;
  }
};

void Predictor::land_discs(Context& c) const {
  // Launch samples at each disc's setting (normalised, scaled during the flight loop), flights, machine
  // frame. The sample blocks say which landings each launch sample of the table owns (the standard
  // errors' samples, SampleInfluence); empty when the discs are alike (sample s owns s and n + s).
  c.w.sample_block_count_ = 0;
  if (c.per_disc) {
    land_each_disc(c);
    own_sample_blocks(c);
  } else {
    land_alike_discs(c);
  }
  record_row_parts(c);
}

Predictor::DiscFlightPlan Predictor::flight_plan(const Context& c, const DiscRows& rows, const DiscSetting& setting,
                                                 DiscFlights discs, std::size_t right_offset) const {
  DiscFlightPlan plan;
  plan.rows = rows;
  plan.drop_point_turn_rad = setting.drop_point_turn_rad;
  plan.omega_rad_s = setting.rpm * 2.0 * kPi / 60.0;
  plan.height_m = c.height_m;
  plan.density_kg_m3 = contents_.materials[c.rows->material].density_kg_m3;
  plan.air = &c.air;
  plan.effects = c.effects;
  plan.discs = discs;
  plan.right_offset = right_offset;
  plan.grid = landing_grid_for(*c.rows, c.height_m, c.effects, c.air);
  return plan;
}

void Predictor::land_alike_discs(Context& c) const {
  const DiscRows& r = c.disc_rows[0];
  const std::size_t n = interpolated_count(r.lower_run, r.upper_run);
  const DiscFlights discs = !c.two_discs        ? DiscFlights::kLeftOnly
                            : c.fly_right_disc ? DiscFlights::kLeftAndRightFlown
                                               : DiscFlights::kLeftAndMirror;
  c.landed.flights = static_cast<int>(fly_launches(c.w, flight_plan(c, r, c.settings[kLeftDisc], discs, n)));
  c.landed.left_landings = n;
  c.landed.landings = c.two_discs ? 2 * n : n;
  c.landed.samples = n;
}

void Predictor::land_each_disc(Context& c) const {
  // One disc after the other through the same sample buffers; each disc's landings carry half of the
  // machine's mass (both discs are fed alike), whatever the count of its samples.
  std::size_t disc_count[2] = {0, 0};
  std::size_t n = 0;  // left-disc landings; the right disc's start at n
  int flights = 0;
  for (int d = 0; d < 2; ++d) {
    const DiscRows& r = c.disc_rows[d];
    const std::size_t count = interpolated_count(r.lower_run, r.upper_run);
    disc_count[d] = count;
    if (d == kLeftDisc) n = count;
    const DiscFlights discs = d == kLeftDisc ? DiscFlights::kLeftOnly : DiscFlights::kRightOnly;
    flights += static_cast<int>(fly_launches(c.w, flight_plan(c, r, c.settings[d], discs, n)));
    double disc_kg = 0.0;
    const std::span<double> disc_weights = std::span(c.w.landing_weight_).subspan(d == kLeftDisc ? 0 : n, count);
    for (double weight : disc_weights) disc_kg += weight;
    for (double& weight : disc_weights) weight = disc_kg > 0.0 ? 0.5 * weight / disc_kg : 0.0;
  }
  c.landed.flights = flights;
  c.landed.left_landings = n;
  c.landed.landings = disc_count[0] + disc_count[1];
}

void Predictor::own_sample_blocks(Context& c) const {
  // A launch sample of the table is one sample however many discs it feeds: the discs' blocks by source
  // row (interpolate(): a row alone or rows pairwise is one block of the lower row's samples, quantile
  // cells the lower row's then the upper row's), a source both discs draw on shared.
  struct RowBlock {
    std::size_t run, count, first_landing;
  };
  // Rows that interpolate pairwise draw the same granules (the analytic builder's sample k is one
  // granule in every row): such a chain of rows is one source, named by its first row.
  const auto source_of = [&](std::size_t run) {
    while (run > c.rows->first_run && pairwise(run - 1, run)) --run;
    return run;
  };
  RowBlock row_blocks[2][2];
  std::size_t row_block_count[2] = {0, 0};
  for (int d = 0; d < 2; ++d) {
    const DiscRows& r = c.disc_rows[d];
    const std::size_t first = d == kLeftDisc ? 0 : c.landed.left_landings;
    const std::size_t lower_count = run_samples(r.lower_run).size();
    row_blocks[d][row_block_count[d]++] = {source_of(r.lower_run), lower_count, first};
    if (r.lower_run != r.upper_run && !pairwise(r.lower_run, r.upper_run)) {
      row_blocks[d][row_block_count[d]++] = {source_of(r.upper_run), run_samples(r.upper_run).size(),
                                             first + lower_count};
    }
  }
  SampleBlock* const blocks = c.w.sample_blocks_.data();
  std::size_t& block_count = c.w.sample_block_count_;
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
  std::size_t sample_total = 0;
  for (std::size_t b = 0; b < block_count; ++b) sample_total += blocks[b].count;
  c.landed.samples = sample_total;
}

void Predictor::record_row_parts(Context& c) const {
  // Each disc's landings by source row: quantile cells write the lower row's granules, then the upper
  // row's (interpolate()); a row alone or rows interpolated pairwise are one part.
  Landed& landed = c.landed;
  int interpolating = 0;
  for (int d = 0; d < (c.two_discs ? 2 : 1); ++d) {
    const DiscRows& r = c.disc_rows[c.per_disc ? d : 0];
    const std::size_t first = d == kLeftDisc ? 0 : landed.left_landings;
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
}

std::size_t Predictor::fly_launches(PredictorWorkspace& w, const DiscFlightPlan& plan) const {
  const auto& machine = contents_.machine;
  const bool left_flown = plan.discs != DiscFlights::kRightOnly;
  const bool right_flown = plan.discs == DiscFlights::kLeftAndRightFlown || plan.discs == DiscFlights::kRightOnly;
  const double half_spacing_m = machine.disc_count == 2 ? 0.5 * machine.disc_spacing_m : 0.0;
  const LandingSlots slots{w.landing_x_m_, w.landing_y_m_, w.landing_weight_, plan.right_offset, half_spacing_m,
                           plan.discs == DiscFlights::kLeftOnly, plan.discs == DiscFlights::kLeftAndMirror, left_flown};
  const std::size_t n = interpolated_count(plan.rows.lower_run, plan.rows.upper_run);
  // The samples are interpolated a chunk at a time into the workspace (kFlightChunk flights: half as many
  // samples when both discs are flown), so no buffer holds them all. flight::fly_many flies several at once
  // in SIMD lanes where the effects allow and gives fly_to_ground's landings bit for bit, so the chunking
  // changes no result (a workspace per thread stays small: docs/c-api.md).
  const std::size_t chunk = left_flown && right_flown ? kFlightChunk / 2 : kFlightChunk;
  std::size_t flights = 0;
  const std::span<const tables::LaunchSample> cell_target =
      cell_targets(w, plan.rows.lower_run, plan.rows.upper_run, plan.rows.t);
  for (std::size_t first = 0; first < n; first += chunk) {
    const std::size_t count = std::min(chunk, n - first);
    disc_samples(w, plan.rows, plan.drop_point_turn_rad, first, count, cell_target);
    if (plan.grid != nullptr) {
      land_chunk_from_grid(w, plan, slots, first, count);
    } else {
      flights += fly_chunk(w, plan, slots, first, count);
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

void Predictor::land_chunk_from_grid(PredictorWorkspace& w, const DiscFlightPlan& plan, const LandingSlots& slots,
                                     std::size_t first, std::size_t count) const {
  // A block of samples at a time, both discs at once where both are landed (a sample's two landings
  // share the stencil's diameter, vertical speed and height). Only the launch's horizontal motion,
  // height, vertical speed and diameter are needed (no spin, no full state).
  const bool left_flown = plan.discs != DiscFlights::kRightOnly;
  const bool right_flown = plan.discs == DiscFlights::kLeftAndRightFlown || plan.discs == DiscFlights::kRightOnly;
  const double rim_speed_m_s = plan.omega_rad_s * contents_.machine.disc_radius_m;
  const bool windy = (plan.effects & flight::kWind) != 0;
  const double wind_x_m_s = windy ? plan.air->wind_m_s.x() : 0.0;
  const double wind_y_m_s = windy ? plan.air->wind_m_s.y() : 0.0;
  const std::span<const tables::LaunchSample> chunk_samples = std::span(w.samples_).first(count);
  const std::span<double> xs = std::span(w.chunk_landing_x_m_), ys = std::span(w.chunk_landing_y_m_);
  if (left_flown && right_flown) {
    plan.grid->sample_landings(chunk_samples, rim_speed_m_s, plan.height_m, wind_x_m_s, wind_y_m_s,
                               LandingGrid::Sides::kBoth, w.stencil_block_[0], xs, ys);
    for (std::size_t c = 0; c < count; ++c) {
      slots.record_left(first + c, w.sample_weight_kg_[c], true, xs[c], ys[c]);
      slots.record_right(first + c, w.sample_weight_kg_[c], true, xs[count + c], ys[count + c]);
    }
    return;
  }
  plan.grid->sample_landings(chunk_samples, rim_speed_m_s, plan.height_m, wind_x_m_s, wind_y_m_s,
                             left_flown ? LandingGrid::Sides::kAsStored : LandingGrid::Sides::kMirrored,
                             w.stencil_block_[0], xs, ys);
  for (std::size_t c = 0; c < count; ++c) {
    if (left_flown) {
      slots.record_left(first + c, w.sample_weight_kg_[c], true, xs[c], ys[c]);
    } else {
      slots.record_right(first + c, w.sample_weight_kg_[c], true, xs[c], ys[c]);
    }
  }
}

std::size_t Predictor::fly_chunk(PredictorWorkspace& w, const DiscFlightPlan& plan, const LandingSlots& slots,
                                 std::size_t first, std::size_t count) const {
  const bool left_flown = plan.discs != DiscFlights::kRightOnly;
  const bool right_flown = plan.discs == DiscFlights::kLeftAndRightFlown || plan.discs == DiscFlights::kRightOnly;
  const double rim_speed_m_s = plan.omega_rad_s * contents_.machine.disc_radius_m;
  // mirror = +1: the left disc as stored; −1: its mirror image x → −x, the right disc. Spin is an axial
  // vector: under the reflection its x component keeps its sign and y, z change sign.
  const auto launch_of = [&](const tables::LaunchSample& s, double mirror, std::size_t slot) {
    flight::Granule& granule = w.granules_[slot];
    granule.diameter_m = s.diameter_m;
    granule.density_kg_m3 = plan.density_kg_m3;
    flight::State& launch = w.launches_[slot];
    launch.position_m = Vec3(mirror * s.x_m, s.y_m, s.z_m + plan.height_m);
    launch.velocity_m_s = rim_speed_m_s * Vec3(mirror * s.vx_norm, s.vy_norm, s.vz_norm);
    launch.spin_rad_s = plan.omega_rad_s * Vec3(s.wx_norm, mirror * s.wy_norm, mirror * s.wz_norm);
  };
  // Slots [0, count): the left disc's flights; then the right disc's mirror of each sample, when flown.
  const std::size_t right_slot = left_flown ? count : 0;
  for (std::size_t c = 0; c < count; ++c) {
    if (left_flown) launch_of(w.samples_[c], 1.0, c);
    if (right_flown) launch_of(w.samples_[c], -1.0, right_slot + c);
  }
  const std::size_t flown = right_flown ? right_slot + count : count;
  flight::fly_many(std::span(w.granules_).first(flown), std::span(w.launches_).first(flown), 0.0, *plan.air,
                   plan.effects, settings_, std::span(w.landings_).first(flown));
  for (std::size_t c = 0; c < count; ++c) {
    const double weight = w.sample_weight_kg_[c];
    if (left_flown) {
      const flight::Landing& landing = w.landings_[c];
      slots.record_left(first + c, weight, landing.landed, landing.state.position_m.x(), landing.state.position_m.y());
    }
    if (right_flown) {
      const flight::Landing& landing = w.landings_[right_slot + c];
      slots.record_right(first + c, weight, landing.landed, landing.state.position_m.x(), landing.state.position_m.y());
    }
  }
  return flown;
}

}  // namespace spread::predict
