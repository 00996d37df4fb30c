#pragma once
// Predictor: from a launch-table file's contents to the spread pattern of the machine, for any
// (material, rpm between table rows, disc height, wind, effects). The core of the C API (capi/).
//
// Steps of predict() — none allocates; all workspace (PredictorWorkspace) is sized from the largest pair
// of neighbouring rows and the widest tray layout:
//   1. find the material and the rows around the rpm (launch_interpolation.hpp),
//   2. interpolate the normalised launch samples — pairwise for analytic rows of equal count, otherwise
//      by quantile cells computed here at construction (launch_interpolation.hpp,
//      launch_quantile_cells.hpp, launch_landing_keys.hpp) —, scale velocities by ωR and spins by ω,
//      place them at the disc height (ground z = 0),
//   3. for a drag-only table within the landing grid's domain (LandingDomain: disc heights and winds a
//      machine meets), evaluate each granule's landing from its material's landing grid
//      (landing_grid.hpp); otherwise fly each granule (flight::fly_many — SIMD lanes for drag/wind-only
//      flights, the same landings as flight::fly_to_ground one by one —, default_flight_settings()),
//   4. machine frame: the left disc centre is at x = −s/2, the right disc is its mirror image
//      (docs/design.md §3). With a lateral wind the mirror trick is invalid (the wind breaks the symmetry),
//      so the right disc's launches are mirrored and flown themselves,
//   5. trays fitted to the landings, throw width, effective working widths (to-and-fro, racetrack),
//      CV at the bout width, R̄ and ξ of one disc (seed Eqs. 51–52).
//
// Sharing (as zstd's CDict and CCtx): the Predictor holds the read-only part (tables, quantile cells) and
// one workspace of its own for predict(request, out). Threads that predict at once each make a
// PredictorWorkspace from it and call predict(request, out, workspace), which only reads the Predictor.
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory_resource>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "libspread/physics/flight/flight.hpp"
#include "libspread/analysis/metrics/metrics.hpp"
#include "libspread/analysis/predict/interpolation_error.hpp"
#include "libspread/analysis/predict/landing_grid.hpp"
#include "libspread/analysis/predict/launch_interpolation.hpp"
#include "libspread/analysis/predict/launch_quantile_cells.hpp"
#include "libspread/analysis/predict/sample_influence.hpp"
#include "libspread/io/tables/table_reader.hpp"

namespace spread::predict {

// Why a request was refused. kOk = success. (Not exceptions: the C API maps these without unwinding,
// and a refused request must not allocate either.)
enum class PredictStatus : std::uint8_t {
  kOk,
  kNotFinite,          // a NaN/Inf in rpm, height, wind, CV target, bout or tray width
  kOutOfRange,         // height < 0 (or disc below the ground) or > max_disc_height_m, |drop point turn| > π
                       // (either disc's), |wind| component > max_wind_m_s, CV target <= 0 or > max_cv_target,
                       // bout width < 0 or > max_bout_width_m, tray width outside [min_tray_width_m,
                       // max_half_extent_m], a right-disc setting on a one-disc machine, rpm or
                       // drop_point_turn_rad not 0 while both discs' own are given
  kUnknownEffect,      // bits outside flight::kAllEffects | kTableEffects
  kUnknownMaterial,
  kRpmOutsideTable,    // rpm (or a disc's own rpm) outside the material's rows
  kOutsideDomain,      // PredictorLimits::refuse_outside_domain and a request the landing grid does not
                       // cover (landing_domain_miss) without fly_outside_domain
};
const char* to_string(PredictStatus status);

// The request field a refusal is about (Predictor::request_problem), as PredictionRequest names them.
enum class RequestField : std::uint8_t {
  kNone, kRpm, kDiscHeight, kWindX, kWindY, kCvTarget, kBoutWidth, kTrayWidth, kKernelHalfWidth, kDropPointTurn,
  kLeftDiscRpm, kRightDiscRpm, kLeftDiscDropPointTurn, kRightDiscDropPointTurn, kEffects
};
// The first field of a request that validation refuses: its value and the range it must lie in (the
// field's own units; cv_target a fraction), or, with lower == upper, the rule it breaks as a phrase that
// follows the value ("given while every disc has its own speed (set it to 0)"); rule "above" marks a
// range open below.
struct RequestProblem {
  PredictStatus status = PredictStatus::kOk;
  RequestField field = RequestField::kNone;
  double value = 0.0, lower = 0.0, upper = 0.0;
  const char* rule = "";
};

inline constexpr flight::EffectSet kTableEffects = 1u << 31;

struct PredictionRequest {
  std::string_view material;
  double rpm = 0.0;                                              // r/min
  double disc_height_m = std::numeric_limits<double>::quiet_NaN();  // NaN: the machine's stored height
  double wind_x_m_s = 0.0;                                       // lateral wind (used with kWind)
  double wind_y_m_s = 0.0;                                       // wind along the driving direction
  double cv_target = 0.15;                                       // fraction (0.15 = 15 %)
  // flight::Effect bits, or kTableEffects: the flight effects the table was built with (each run records
  // them), plus any bits given beside it. With kTableEffects a non-zero wind adds flight::kWind: the wind
  // is a condition of the day, not of the machine.
  flight::EffectSet effects = kTableEffects;
  double bout_width_m = 0.0;                                     // 0: at the to-and-fro working width
  double tray_width_m = 0.5;
  // Half-width h (m) of the Epanechnikov kernel each landing's mass is spread over
  // (metrics::accumulate_transverse_kernel). NaN: the automatic rule (kernel_half_width_for); 0: each
  // landing falls into one tray as a point mass.
  double kernel_half_width_m = std::numeric_limits<double>::quiet_NaN();
  // The drop point (feed position on the disc) turned from the table's by this angle (rad) about the disc
  // axis, counter-clockwise seen from above for the left disc, mirrored for the right (both discs set
  // alike, as a twin-disc spreader's mirrored scales are); within [−π, π].
  double drop_point_turn_rad = 0.0;
  // Each disc's own setting (kLeftDisc, kRightDisc as the driver sees them), NaN: the both-discs value above.
  // A disc turned by its own drop point turns as drop_point_turn_rad does for it (mirrored on the right).
  // When both discs' rpm are given `rpm` is unused and must be 0, and likewise drop_point_turn_rad
  // (a value that would be dropped is refused). A one-disc machine has only kLeftDisc.
  std::array<double, 2> disc_rpm = {std::numeric_limits<double>::quiet_NaN(),
                                    std::numeric_limits<double>::quiet_NaN()};
  std::array<double, 2> disc_drop_point_turn_rad = {std::numeric_limits<double>::quiet_NaN(),
                                                    std::numeric_limits<double>::quiet_NaN()};
  // Opt-in for a Predictor that refuses requests outside its landing grid's domain
  // (PredictorLimits::refuse_outside_domain): fly every launch sample instead, at the cost of one flight
  // per sample and disc (tens of milliseconds; docs/c-api.md "Landing grid").
  bool fly_outside_domain = false;
  // False: no standard errors (all NaN) — for a search that compares many settings, at about half the
  // cost. The headline rule then takes a band as established when its lowest CV meets the target, with
  // no confidence test.
  bool standard_errors = true;
  // With standard errors, between DEM rows: include the interpolation's own error (interpolation_error.hpp:
  // the answer's trays binned again from each row's granules alone). False: the launch samples' error
  // alone.
  bool interpolation_error = true;
};
inline constexpr int kLeftDisc = 0, kRightDisc = 1;

// Drop-point turns (rad), [low_rad, high_rad] with low_rad <= 0 <= high_rad.
struct TurnRange {
  double low_rad = 0.0, high_rad = 0.0;
  bool contains(double turn_rad) const { return turn_rad >= low_rad - 1e-12 && turn_rad <= high_rad + 1e-12; }
};

// The speed (r/min) and drop-point turn (rad) disc `disc` runs at under this request.
struct DiscSetting {
  double rpm = 0.0;
  double drop_point_turn_rad = 0.0;
  bool operator==(const DiscSetting&) const = default;
};
DiscSetting disc_setting(const PredictionRequest& request, int disc);

// The automatic kernel half-width (m) for N launch samples whose landings (one disc) have lateral
// standard deviation sd_x_m: h = kKernelScale · sd_x · N^(−1/5) (the rate of Silverman's rule; the
// constant is the accuracy–cost study's, docs/metrics.md "Predicted patterns").
inline constexpr double kKernelScale = 0.5;
double kernel_half_width_for(double sd_x_m, std::size_t sample_count);

// One band of bout widths whose CV meets the target (metrics::WidthBand), as predicted, with the
// standard errors over the launch samples.
struct PredictedBand {
  double lower_m = 0.0;             // narrowest bout width of the band
  double upper_m = 0.0;             // widest, interpolated between whole trays (the layout's edge if limited)
  double upper_se_m = 0.0;          // NaN when limited by the layout
  double bout_width_m = 0.0;        // the widest whole-tray bout inside the band
  double cv = 0.0;                  // CV there (fraction)
  double cv_se = 0.0;               // its standard error (fraction)
  double lowest_cv = 0.0;           // the band's lowest CV (fraction) and its bout width
  double lowest_cv_se = 0.0;
  double lowest_cv_bout_width_m = 0.0;
  bool limited_by_layout = false;   // CV stays within the target up to the widest layout
  // lowest_cv + kConfidence95 · lowest_cv_se <= target: the launch samples establish the band (the
  // headline rule takes the widest established band).
  bool established = false;
  // The gap before this band, between the previous band's upper end and this band's lower end: its
  // highest CV at a whole-tray bout and that CV's standard error (NaN for the first band, when the band
  // before is not stored, or without standard errors).
  double gap_peak_cv = std::numeric_limits<double>::quiet_NaN();
  double gap_peak_cv_se = std::numeric_limits<double>::quiet_NaN();
  // gap_peak_cv − kConfidence95 · gap_peak_cv_se <= target: the launch samples do not show the gap above
  // the target, so the headline rule takes this band and the one before as one (an established band
  // makes the bands joined to it established).
  bool joins_previous = false;
};
inline constexpr int kMaxBands = metrics::kMaxWidthBands;
// Two-sided 95 % normal quantile: the intervals the tools print and the headline rule's confidence.
inline constexpr double kConfidence95 = 1.96;

struct Prediction {
  double throw_width_m = 0.0;               // 99 % of the mass
  // The headline working width (docs/metrics.md "Effective working width"): the upper end of the widest
  // band of bout widths with CV <= target whose lowest CV meets the target at 95 % confidence, or that is
  // joined to such a band by gaps the samples do not show above the target (the first band when none
  // is), PredictedBand::established and joins_previous; 0 = no width meets the target.
  double working_width_to_and_fro_m = 0.0;
  double working_width_racetrack_m = 0.0;
  double bout_width_m = 0.0;                // where the CVs below were evaluated
  double cv_to_and_fro = 0.0;               // fraction; NaN when bout_width_m == 0
  double cv_racetrack = 0.0;                // fraction; NaN when bout_width_m == 0
  double mean_radius_m = 0.0;               // R̄ of the left disc about its centre, Eq. 51
  double radial_width_m = 0.0;              // ξ, Eq. 52
  double disc_height_m = 0.0;               // as used
  DiscSetting discs[2];                     // each disc's setting as used (kLeftDisc, kRightDisc)
  double lost_mass_fraction = 0.0;          // outside the trays or not landed
  metrics::TrayLayout trays;
  int flights = 0;                          // trajectories integrated (0: landings from the landing grid)
  // Monte Carlo uncertainty (docs/metrics.md "Uncertainty"): the standard errors of the estimates above
  // over the table's launch samples, by the delta method (the influence of each sample, linear in the
  // samples: no resampling). NaN where the estimate has no derivative (no width meets the target, or
  // the CV is infinite).
  double throw_width_se_m = 0.0;
  double working_width_to_and_fro_se_m = 0.0;
  double working_width_racetrack_se_m = 0.0;
  double cv_to_and_fro_se = 0.0;            // fraction
  double cv_racetrack_se = 0.0;             // fraction
  // Between DEM rows the standard errors above include the interpolation's own error
  // (interpolation_error.hpp), in quadrature; here that part alone (0 on a row, between rows that
  // interpolate sample by sample, and without standard errors).
  InterpolatedFigures interpolation_se;
  // Times CV(W) crosses the target between two trays and the layout width: more than 1 means more than
  // one band (a bout width between two bands does not meet the target; say so to the user).
  int cv_crossings_to_and_fro = 0;
  int cv_crossings_racetrack = 0;
  // Every band of bout widths within the target (the first kMaxBands − 1 and the widest are kept), each
  // with its CV and standard error at its widest whole-tray bout; headline_band_*: the index of the band
  // whose upper end is the working width above (−1: none). first_band_width_*_m: the narrowest band's
  // upper end (the first rise of CV(W) above the target).
  int band_count_to_and_fro = 0;
  int band_count_racetrack = 0;
  int headline_band_to_and_fro = -1;
  int headline_band_racetrack = -1;
  PredictedBand bands_to_and_fro[kMaxBands];
  PredictedBand bands_racetrack[kMaxBands];
  double first_band_width_to_and_fro_m = 0.0;
  double first_band_width_racetrack_m = 0.0;
  int stored_bands_to_and_fro() const { return band_count_to_and_fro < kMaxBands ? band_count_to_and_fro : kMaxBands; }
  int stored_bands_racetrack() const { return band_count_racetrack < kMaxBands ? band_count_racetrack : kMaxBands; }
  std::size_t sample_count = 0;             // independent launch samples behind the estimate
  flight::EffectSet effects = 0;            // the flight effects that ran
  double kernel_half_width_m = 0.0;         // as used
  // Views into the predictor's workspace, valid until the next predict():
  std::span<const double> tray_mass_fraction;  // per tray, of the machine's total discharged mass
  // Landings of the whole machine in the machine frame (both discs; the left disc's first), with the
  // fraction of the total mass each stands for. Not-landed granules have x = y = NaN.
  std::span<const double> landing_x_m, landing_y_m, landing_mass_fraction;
  std::size_t left_landing_count = 0;  // the left disc's landings come first, the right disc's after them
};

struct PredictorLimits {
  double max_half_extent_m = 100.0;  // trays cover at most [-100 m, 100 m]; landings beyond are "lost"
  double min_tray_width_m = 0.05;
  // Upper bounds of the request fields (kOutOfRange above them). Far beyond any spreader, but they keep
  // a finite yet absurd value (a bout width of 3.6e59 m) out of the metrics and flight code.
  double max_bout_width_m = 1000.0;   // m
  double max_disc_height_m = 100.0;   // m above the ground
  double max_wind_m_s = 100.0;        // each wind component, absolute value
  double max_cv_target = 10.0;        // fraction (1000 %)
  double max_kernel_half_width_m = 10.0;  // m
  // Requests outside the landing grid's domain (another height or wind than it covers, effects beyond the
  // table's drag) are refused with kOutsideDomain unless they opt in (fly_outside_domain): a controller's
  // time is then bounded by the grid's cost. False: they fly every launch sample (tools, studies).
  // Tables without a landing grid (runs that fly more than drag) fly every request.
  bool refuse_outside_domain = false;
};

class Predictor;

// Flights per flight::fly_many call in predict(): the workspace holds launch samples, launches and
// landings for this many, not for every flight (the samples of the default table's largest pair of rows
// alone would be 0.5 MB per workspace).
inline constexpr std::size_t kFlightChunk = 128;

// Everything one predict() call writes: launch samples at the requested rpm, flights, landings, trays,
// gradients and the metrics' scratch. Sized for one Predictor; one per thread that predicts.
class PredictorWorkspace {
 public:
  // Allocates from `memory` (which must outlive the workspace); the Predictor is only read.
  explicit PredictorWorkspace(const Predictor& predictor,
                              std::pmr::memory_resource* memory = std::pmr::get_default_resource());
  // Bytes of the buffers it holds.
  std::size_t bytes() const;
  // Room for a search that combines each disc's trays between predictions (wind_compensation.hpp): four
  // arrays of the widest layout's trays and a bout of the widest bout width. predict() never touches it.
  std::span<double> search_buffer() { return search_buffer_; }

 private:
  friend class Predictor;
  std::size_t sample_capacity_ = 0;  // launch samples of the largest pair of rows it was sized for
  std::size_t tray_capacity_ = 0;
  // One chunk of launch samples at the request's setting and their weights (kg), and of flights
  // (kFlightChunk): the left disc's, then the right disc's when flown.
  std::pmr::vector<tables::LaunchSample> samples_;
  std::pmr::vector<double> sample_weight_kg_;
  std::pmr::vector<flight::Granule> granules_;
  std::pmr::vector<flight::State> launches_;
  std::pmr::vector<flight::Landing> landings_;
  std::pmr::vector<double> landing_x_m_, landing_y_m_, landing_weight_;  // machine frame, both discs
  std::pmr::vector<double> tray_mass_;
  // Per tray, for the standard errors: the gradient being made for a pass (InfluencePass keeps its prefix
  // sums), and one more for the width gradients' second CV.
  std::pmr::vector<double> gradients_, gradient_scratch_;
  // metrics::working_widths' scratch, also the bout buffer of cv_at_trays / cv_gradient (up to the widest
  // requested bout at the narrowest trays, its last cv_scratch_size_ values), so that no bout is built on
  // the stack, and during the standard errors' passes the gradients' prefix sums (before that tail).
  std::pmr::vector<double> metrics_scratch_;
  std::size_t cv_scratch_size_ = 0;  // the metrics scratch's tail that cv_gradient uses during the passes
  // The landing grid's landings of one chunk (kFlightChunk: both discs land half a chunk of samples each)
  // and its stencils' set-up.
  std::pmr::vector<double> chunk_landing_x_m_, chunk_landing_y_m_;
  std::pmr::vector<LandingGrid::StencilBlock> stencil_block_;
  std::pmr::vector<tables::LaunchSample> cell_target_;  // Predictor::cell_targets
  std::pmr::vector<double> search_buffer_;
  // predict()'s bookkeeping of the bands and their standard errors (kept here, not on the caller's stack):
  // one standard error to compute — of the CV at `trays` trays, or (width_band set) of that band's upper
  // end, or (throw_width) of the throw width —, and per band the racetrack CV at a to-and-fro band's bout.
  struct SeTask {
    double* out;
    metrics::Overlap overlap;
    int trays;
    const metrics::WidthBand* width_band;
    bool throw_width = false;
  };
  struct BandExtra {
    const metrics::WidthBand* band = nullptr;
    double racetrack_cv = std::numeric_limits<double>::quiet_NaN();
    double racetrack_cv_se = std::numeric_limits<double>::quiet_NaN();
  };
  std::array<SeTask, 3 + 2 * kMaxBands * 5> se_tasks_{};
  // The discs' launch samples by source (SampleInfluence), when each disc has its own setting.
  std::array<SampleBlock, kMaxSampleBlocks> sample_blocks_{};
  std::size_t sample_block_count_ = 0;
  std::array<BandExtra, 2 * kMaxBands> band_extras_{};
  metrics::WorkingWidths widths_;
  double radial_mean_m_ = 0.0;  // R̄, ξ of the last fly_launches()
  double radial_width_m_ = 0.0;
};

class Predictor {
 public:
  // Throws tables::TableError(kCorrupt) when a run names a material the file does not describe, and
  // std::invalid_argument for bad limits. Materials without runs are not offered. Rows interpolated by
  // quantile cells are flown once here to find their cells (one flight per sample, default settings), and
  // a drag-only table's materials into their landing grids (landing_grid.hpp) over the domain of the
  // machine's stored height (landing_domain_for).
  // The launch samples, the cells and the own workspace are allocated from `memory` (which must outlive
  // the Predictor); the samples are moved out of `contents` into one block.
  explicit Predictor(tables::TableContents contents, PredictorLimits limits = {},
                     std::pmr::memory_resource* memory = std::pmr::get_default_resource());
  Predictor(const Predictor&) = delete;
  Predictor& operator=(const Predictor&) = delete;

  const tables::Machine& machine() const { return contents_.machine; }
  std::size_t material_count() const { return materials_.size(); }
  const tables::Material& material(std::size_t index) const;  // sorted by name
  double min_rpm(std::size_t index) const;
  double max_rpm(std::size_t index) const;
  // The rpm of each of the material's rows, ascending (a view into the Predictor).
  std::span<const double> row_rpm(std::size_t index) const;
  std::optional<std::size_t> find_material(std::string_view name) const;
  const PredictorLimits& limits() const { return limits_; }
  // The drop-point turns a search over settings may use (the setting chart, border and edge spreading,
  // wind compensation): all of [−π, π] when every row is analytic (the analytic launch model is the same
  // all round the disc: its fan turns with the feed exactly); otherwise the table's validated range
  // (TableContents::drop_point_turn_validated_rad), and none when it states none (a DEM row's turned
  // launches are an approximation that only a comparison with DEM rows at the turned drop point validates).
  TurnRange drop_point_turn_range() const { return turn_range_; }

  // Tray count of the widest layout for this tray width: an upper bound of Prediction::trays.tray_count.
  // 0 when the tray width is outside the limits.
  int tray_capacity(double tray_width_m) const;

  // Integrator used by predict(); default_flight_settings() unless changed (benchmarks, tests). The landing
  // grids were flown with their own settings at construction: changing these turns them off.
  void set_flight_settings(const flight::Settings& settings) {
    settings_ = settings;
    landing_grid_enabled_ = false;
  }
  const flight::Settings& flight_settings() const { return settings_; }
  // Whether predict() may take landings from the landing grids where they cover the request; off: every
  // granule is flown (benchmarks and tests compare the two).
  void set_landing_grid_enabled(bool enabled) { landing_grid_enabled_ = enabled; }
  // Bytes the landing grids hold (0: the table's flight effects are not drag alone, or the grids are off).
  std::size_t landing_grid_bytes() const;
  // The disc heights and winds the landing grids cover.
  const LandingDomain& landing_domain() const { return domain_; }
  // Whether material `index` (as material()) has a landing grid: its runs fly drag alone or nothing.
  bool has_landing_grid(std::size_t index) const;
  // Whether material `index`'s landing grid and quantile cells were read from the table's landing data
  // (TableContents::landing_data of this build's model, derived from these very rows: contents changed
  // after reading derive afresh) instead of derived here.
  bool landing_data_from_table(std::size_t index) const { return landing_data_from_table_.at(index); }
  // The landing data of every material derived here (not read from the table), as a table stores it
  // (landing_data_codec.hpp): what a table writer adds so that the next Predictor of the file reads it.
  std::vector<tables::LandingData> derived_landing_data() const;
  // What validation refuses in a request (status kOk: nothing; the material, rpm rows and landing domain
  // are checked by predict() after it): the first field at fault, for the refusal's message.
  RequestProblem request_problem(const PredictionRequest& request) const;
  // Why the landing grid does not serve a valid request (kNone: it does, or the material has no grid and
  // every request flies): what the refusal's message names.
  enum class DomainMiss : std::uint8_t { kNone, kHeight, kWind, kEffects };
  DomainMiss landing_domain_miss(const PredictionRequest& request) const;

  // Does not allocate. Refused requests are statuses, not exceptions (so a refusal does not allocate
  // either); on a refusal `out` is unchanged. An exception from here means a malformed table record that
  // the reader let through (e.g. a zero diameter) or a bug. Uses the Predictor's own workspace: one
  // thread at a time.
  PredictStatus predict(const PredictionRequest& request, Prediction& out);
  // The same with a caller's workspace (made from this Predictor): only reads the Predictor, so threads
  // with a workspace each may call it at once. The views in `out` point into `workspace`.
  PredictStatus predict(const PredictionRequest& request, Prediction& out, PredictorWorkspace& workspace) const;

  // The Predictor's own workspace, the one predict(request, out) uses (for searches that predict many
  // times through the Predictor's workspace: one thread at a time).
  PredictorWorkspace& own_workspace() { return *own_workspace_; }

  // Launch samples of the largest pair of neighbouring rows (what a workspace is sized for).
  std::size_t largest_pair() const { return largest_pair_; }
  // The most quantile cells of any run (a workspace holds where they move their granules).
  std::size_t most_cells() const;
  // Launch samples of run k (runs sorted by material and rpm, as TableContents::runs).
  std::span<const tables::LaunchSample> run_samples(std::size_t run) const {
    return std::span(samples_).subspan(run_offset_[run], run_offset_[run + 1] - run_offset_[run]);
  }

 private:
  struct MaterialRows {
    std::size_t material = 0;   // index into contents_.materials
    std::size_t first_run = 0;  // runs are sorted by (material, rpm)
    std::size_t run_count = 0;
  };

  PredictStatus validate(const PredictionRequest& request, double& height_m, RequestProblem* problem = nullptr) const;
  // Where a disc's launch samples come from: the rows around its speed and the upper row's weight t.
  struct DiscRows {
    std::size_t lower_run = 0, upper_run = 0;
    double t = 0.0;
  };
  // What steps 1–4 of predict() landed into the workspace (and the sample blocks, w.sample_blocks_).
  struct Landed {
    std::size_t left_landings = 0;  // the left disc's landings come first, the right disc's from here
    std::size_t landings = 0;
    std::size_t samples = 0;        // independent launch samples behind the pattern
    int flights = 0;
    DiscRowParts row_parts[2];      // each disc's landings by source row (interpolation_error.hpp)
    double upper_weight = 0.0;      // the upper rows' share, the mean of the discs that interpolate by cells
  };
  Landed land_discs(PredictorWorkspace& w, const MaterialRows& rows, const DiscRows (&disc_rows)[2],
                    const DiscSetting (&settings)[2], bool per_disc, double height_m, const flight::Air& air,
                    flight::EffectSet effects, bool fly_right_disc) const;
  // Step 5 of predict(): trays, widths, bands and standard errors from the landings, into `out` (a function
  // of its own: its frame and land_discs()'s are never on the stack together).
  void measure(const PredictionRequest& request, const Landed& landed, bool per_disc, bool fly_right_disc,
               flight::EffectSet effects, double height_m, const DiscSetting (&settings)[2], Prediction& out,
               PredictorWorkspace& w) const;
  // Between DEM rows: the interpolation's own error (interpolation_error.hpp) into p.interpolation_se and,
  // in quadrature, into p's standard errors. After measure(), from its trays, kernel and bands.
  void add_interpolation_error(const PredictionRequest& request, const Landed& landed, bool mirrored, Prediction& p,
                               PredictorWorkspace& w) const;
  // True when runs a and b (neighbours) interpolate sample by sample: both from the analytic builder
  // (sample k is the same granule in every row) and of equal count.
  bool pairwise(std::size_t run_a, std::size_t run_b) const;
  // Whether run `run` of these rows is interpolated by quantile cells with a neighbour.
  bool needs_cells(const MaterialRows& rows, std::size_t run) const;
  QuantileCellCounts cell_counts(const MaterialRows& rows) const;
  // Flies the runs that need cells once (landing keys) and fills their cells and cell means.
  void assign_cells(const MaterialRows& rows);
  // Launch samples of the rows lower..upper at weight t (lower == upper: that row), as predict() uses
  // them: pairwise for analytic rows of equal count, otherwise by quantile cells (the lower row's, then the
  // upper row's). interpolated_count: how many; interpolate: those at [first, first + samples.size()).
  std::size_t interpolated_count(std::size_t lower_run, std::size_t upper_run) const;
  // cell_target: cell_targets() of these rows at t (empty for rows without cells).
  void interpolate(std::size_t lower_run, std::size_t upper_run, double t, std::size_t first,
                   std::span<tables::LaunchSample> samples, std::span<double> weight_kg,
                   std::span<const tables::LaunchSample> cell_target) const;
  // Where the cells of rows lower..upper move their granules at t (quantile_cell_targets), into the
  // workspace; empty when the rows are not interpolated by cells.
  std::span<const tables::LaunchSample> cell_targets(PredictorWorkspace& w, std::size_t lower_run,
                                                     std::size_t upper_run, double t) const;
  CelledRow celled(std::size_t run) const;
  // The still-air effects of the material's landing grid and the fastest rim speed of its rows: false
  // when its rows do not all fly drag alone (or nothing), and it has no grid.
  bool grid_effects(const MaterialRows& rows, flight::EffectSet& effects, double& max_rim_speed_m_s) const;
  LandingGrid::Axes grid_axes(const MaterialRows& rows, double max_rim_speed_m_s) const;
  flight::Settings grid_flight_settings() const;
  // Flies a drag-only material's landing grid over the domain (landing_grid_axes()).
  void build_landing_grid(const MaterialRows& rows);
  // The material's grid and cells from its stored landing data; TableError kCorrupt when the data does
  // not fit the rows (a writer of the same model tag wrote something else).
  void restore_landing_data(const MaterialRows& rows, std::span<const std::uint8_t> data);
  tables::LandingData encode_landing_data(const MaterialRows& rows) const;
  // Digest of what the material's landing data is derived from (tables::LandingData::source_key).
  std::string landing_source_key(const MaterialRows& rows) const;
  // The grid that serves a request of this material, or null (fly).
  const LandingGrid* landing_grid_for(const MaterialRows& rows, double height_m, flight::EffectSet effects,
                                      const flight::Air& air) const;
  // Which discs fly_launches() lands from the samples in the workspace: the left disc alone (one disc, or
  // the left of two at their own settings), the left and its mirror image (still air across), the left
  // and the right flown as its mirror (a lateral wind), or the right disc alone (at its own setting).
  enum class DiscFlights : std::uint8_t { kLeftOnly, kLeftAndMirror, kLeftAndRightFlown, kRightOnly };
  // Lands one disc's launch samples (the rows and weight of `rows`, turned by drop_point_turn_rad;
  // interpolated_count of them): left-disc landing i at i, right-disc landing i at right_offset + i (machine
  // frame, with each landing's weight); R̄ and ξ when the left disc is landed. Returns the flights integrated.
  std::size_t fly_launches(PredictorWorkspace& w, const DiscRows& rows, double drop_point_turn_rad, double omega_rad_s,
                           double height_m, const flight::Air& air, flight::EffectSet effects, DiscFlights discs,
                           std::size_t right_offset, double density_kg_m3, const LandingGrid* grid) const;
  // Steps 1–2 of predict() for one disc: its samples [first, first + count) into the front of the
  // workspace's sample buffer (count <= kFlightChunk), turned by drop_point_turn_rad.
  void disc_samples(PredictorWorkspace& w, const DiscRows& rows, double drop_point_turn_rad, std::size_t first,
                    std::size_t count, std::span<const tables::LaunchSample> cell_target) const;
  // The effects and air a request flies with (the table's effects resolved, a zero wind no wind).
  void flight_conditions(const PredictionRequest& request, const DiscRows (&disc_rows)[2], flight::EffectSet& effects,
                         flight::Air& air) const;

  tables::TableContents contents_;  // without the samples (in samples_)
  PredictorLimits limits_;
  TurnRange turn_range_;
  flight::Settings settings_;
  std::vector<MaterialRows> materials_;
  std::vector<double> run_rpm_;       // contents_.runs[i].rpm, flat for bracket_rpm
  std::vector<flight::EffectSet> run_effects_;  // the flight effects each run was built with
  std::size_t largest_pair_ = 0;
  // Launch samples of all runs, flat: run i's occupy [run_offset_[i], run_offset_[i + 1]). Quantile cells
  // (launch_quantile_cells.hpp) of the runs interpolated by cells: cell_of_sample_ at the same offsets,
  // run i's cell means [cell_offset_[i], cell_offset_[i + 1]) of cell_mean_ (empty for runs only
  // interpolated pairwise).
  std::vector<std::size_t> run_offset_, cell_offset_;
  std::pmr::vector<tables::LaunchSample> samples_;
  std::pmr::vector<CellIndex> cell_of_sample_;
  std::pmr::vector<tables::LaunchSample> cell_mean_;
  double lowest_sample_z_m_ = 0.0;    // over all runs: the disc must sit at least -this above ground
  // Landing grids by material (contents_.materials' index; empty where the material's runs fly more than
  // drag) and the domain they cover.
  LandingDomain domain_;
  std::vector<LandingGrid> grids_;
  std::vector<bool> landing_data_from_table_;  // by materials_ index
  bool landing_grid_enabled_ = true;
  std::optional<PredictorWorkspace> own_workspace_;  // for predict(request, out)
};

}  // namespace spread::predict
