#pragma once
// Predictor: from a launch-table file's contents to the spread pattern of the machine, for any
// (material, rpm between table rows, disc height, wind, effects). The core of the C API (capi/).
//
// predict() runs named stages over one context (prediction_context.hpp), each in a file of its own —
// none allocates; all workspace (PredictorWorkspace, predictor_workspace.hpp) is sized from the largest
// pair of neighbouring rows and the widest tray layout:
//   1. request check (request_check.cpp): every field in its domain, the material's rows around each
//      disc's speed (launch_interpolation.hpp), the effects and air;
//   2. landings (landings.cpp): the normalised launch samples interpolated — pairwise for analytic rows of
//      equal count, otherwise by quantile cells found at construction (launch_quantile_cells.hpp,
//      launch_landing_keys.hpp) —, turned by the drop point, scaled by ωR and ω, placed at the disc
//      height (ground z = 0); for a drag-only table within the landing grid's domain (LandingDomain) each
//      landing read off its material's landing grid (landing_grid.hpp), otherwise flown (flight::fly_many,
//      default_flight_settings()); machine frame: the left disc centre at x = −s/2, the right disc its
//      mirror image (docs/design.md §3), flown itself in a lateral wind or at its own setting;
//   3. transverse pattern (transverse.cpp): kernel, trays fitted to the landings; in a wind that the return
//      pass of a to-and-fro field meets otherwise than as the outgoing one's mirror image, that pass first
//      (return_pass.cpp: stages 2–3 for the return pass's own wind and settings);
//   4. metrics (pattern_metrics.cpp): throw width, effective working widths (to-and-fro, racetrack) and
//      their bands, CV at the bout width;
//   5. uncertainty (uncertainty.cpp): standard errors over the launch samples;
//   6. headline (headline.cpp): the headline band, the CVs reported, R̄ and ξ of one disc (seed Eqs. 51–52);
//   7. between DEM rows, the interpolation's own error (uncertainty.cpp, interpolation_error.hpp).
// What the Predictor derives once per material — landing grids and quantile cells, or their copies from
// the table's landing data — is landing_data_cache.cpp.
//
// Sharing (as zstd's CDict and CCtx): the Predictor holds the read-only part (tables, quantile cells) and
// one workspace of its own for predict(request, out). Threads that predict at once each make a
// PredictorWorkspace from it and call predict(request, out, workspace), which only reads the Predictor.
#include <cstddef>
#include <cstdint>
#include <memory_resource>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "libspread/analysis/metrics/metrics.hpp"
#include "libspread/analysis/predict/interpolation_error.hpp"
#include "libspread/analysis/predict/landing_grid.hpp"
#include "libspread/analysis/predict/launch_interpolation.hpp"
#include "libspread/analysis/predict/launch_quantile_cells.hpp"
#include "libspread/analysis/predict/prediction.hpp"
#include "libspread/analysis/predict/prediction_request.hpp"
#include "libspread/analysis/predict/predictor_workspace.hpp"
#include "libspread/analysis/predict/sample_influence.hpp"
#include "libspread/io/tables/table_reader.hpp"
#include "libspread/physics/flight/flight.hpp"

namespace spread::predict {

struct LandingSlots;  // where fly_launches() writes each disc's landings (landings.cpp)

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
  // Where a disc's launch samples come from: the rows around its speed and the upper row's weight t.
  struct DiscRows {
    std::size_t lower_run = 0, upper_run = 0;
    double t = 0.0;
  };
  // What the landings stage landed into the workspace (and the sample blocks, w.sample_blocks_).
  struct Landed {
    std::size_t left_landings = 0;  // the left disc's landings come first, the right disc's from here
    std::size_t landings = 0;
    std::size_t samples = 0;        // independent launch samples behind the pattern
    int flights = 0;
    DiscRowParts row_parts[2];      // each disc's landings by source row (interpolation_error.hpp)
    double upper_weight = 0.0;      // the upper rows' share, the mean of the discs that interpolate by cells
  };
  // Which discs fly_launches() lands from the samples in the workspace: the left disc alone (one disc, or
  // the left of two at their own settings), the left and its mirror image (still air across), the left
  // and the right flown as its mirror (a lateral wind), or the right disc alone (at its own setting).
  enum class DiscFlights : std::uint8_t { kLeftOnly, kLeftAndMirror, kLeftAndRightFlown, kRightOnly };
  // One disc's flights: its rows, setting and conditions (fly_launches()).
  struct DiscFlightPlan {
    DiscRows rows;
    double drop_point_turn_rad = 0.0;
    double omega_rad_s = 0.0;
    double height_m = 0.0;
    double density_kg_m3 = 0.0;
    const flight::Air* air = nullptr;
    flight::EffectSet effects = 0;
    DiscFlights discs = DiscFlights::kLeftOnly;
    std::size_t right_offset = 0;       // where the right disc's landings start
    const LandingGrid* grid = nullptr;  // null: fly
  };

  // predict() runs named stages over one context (prediction_context.hpp), in this order; each reads what
  // the stages before it left in the context and the workspace:
  //   check_request (request_check.cpp): validation, the material's rows around each disc's speed, the
  //     effects and air, whether the right disc is flown or mirrored;
  //   land_discs (landings.cpp): launch samples at each disc's setting, flights or landing-grid reads,
  //     the machine frame, which landings each launch sample owns;
  //   bin_transverse (transverse.cpp): the kernel, the tray layout and the transverse pattern;
  //   return_pass_of, fly_return_pass, align_return_pass (return_pass.cpp): how the to-and-fro figures are
  //     read in wind, and where the return pass is flown, its pattern (landed and binned before the
  //     outgoing pass, whose landings the standard errors need) on the outgoing pass's trays;
  //   measure_pattern (pattern_metrics.cpp): the throw width, the working widths and their bands, and the
  //     standard errors they need;
  //   sample_standard_errors (uncertainty.cpp): those standard errors over the launch samples;
  //   choose_headline (headline.cpp): the headline band and the CVs reported;
  //   add_interpolation_error (uncertainty.cpp): between DEM rows, the interpolation's own error.
  // Each is a function of its own in a file of its own, called one after another: no two stages' frames
  // are on the stack together (the C API's stack budget holds in an unoptimised build too).
  struct Context;
  PredictStatus check_request(Context& c) const;
  void land_discs(Context& c) const;
  void bin_transverse(Context& c) const;
  ReturnPass return_pass_of(const Context& c) const;
  PredictStatus fly_return_pass(Context& c) const;
  void align_return_pass(Context& c) const;
  void measure_pattern(Context& c) const;
  void sample_standard_errors(Context& c) const;
  void choose_headline(Context& c) const;
  void add_interpolation_error(Context& c) const;

  // The request check's parts (request_check.cpp).
  PredictStatus validate(const PredictionRequest& request, double& height_m, RequestProblem* problem = nullptr) const;
  // The effects and air a request flies with (the table's effects resolved, a zero wind no wind).
  void flight_conditions(const PredictionRequest& request, const DiscRows (&disc_rows)[2], flight::EffectSet& effects,
                         flight::Air& air) const;

  // The landings' parts (landings.cpp).
  // Both discs alike: the left disc's samples, landed for it and (mirrored or flown) for the right disc.
  void land_alike_discs(Context& c) const;
  // Discs at their own settings: each disc's own samples, one disc after the other, and which landings each
  // launch sample of the table owns (the standard errors' sample blocks).
  void land_each_disc(Context& c) const;
  void own_sample_blocks(Context& c) const;
  // Each disc's landings by source row (the interpolation's own error).
  void record_row_parts(Context& c) const;
  // Lands one disc's launch samples (plan.rows, interpolated_count of them): left-disc landing i at i,
  // right-disc landing i at plan.right_offset + i (machine frame, with each landing's weight); R̄ and ξ
  // when the left disc is landed. Returns the flights integrated.
  std::size_t fly_launches(PredictorWorkspace& w, const DiscFlightPlan& plan) const;
  // The plan of one disc's flights under the context's conditions.
  DiscFlightPlan flight_plan(const Context& c, const DiscRows& rows, const DiscSetting& setting, DiscFlights discs,
                             std::size_t right_offset) const;
  // One chunk of fly_launches(): samples [first, first + count) in the workspace's sample buffer, landed
  // from the landing grid, or flown (returns the flights), into `slots`.
  void land_chunk_from_grid(PredictorWorkspace& w, const DiscFlightPlan& plan, const LandingSlots& slots,
                            std::size_t first, std::size_t count) const;
  std::size_t fly_chunk(PredictorWorkspace& w, const DiscFlightPlan& plan, const LandingSlots& slots,
                        std::size_t first, std::size_t count) const;
  // Steps 1–2 of the landings for one disc: its samples [first, first + count) into the front of the
  // workspace's sample buffer (count <= kFlightChunk), turned by drop_point_turn_rad.
  void disc_samples(PredictorWorkspace& w, const DiscRows& rows, double drop_point_turn_rad, std::size_t first,
                    std::size_t count, std::span<const tables::LaunchSample> cell_target) const;
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

  // The metrics' parts (pattern_metrics.cpp): each stored band of both overlaps into the Prediction, with
  // the standard errors it needs queued; the CVs at the requested bout.
  void copy_bands(Context& c) const;
  void queue_gap_peak(Context& c, int overlap, int band) const;
  void request_bout_cvs(Context& c) const;
  // The CV at `bout_trays` trays of one overlap, to-and-fro with the return pass (return_pass.cpp).
  double bout_cv(const Context& c, metrics::Overlap overlap, int bout_trays) const;
  // The headline's part (headline.cpp): the CVs reported, R̄ and ξ, and the views into the workspace.
  void report_cvs(Context& c) const;

  // The landing grids and quantile cells, derived at construction or restored from the table's landing
  // data (landing_data_cache.cpp).
  // True when runs a and b (neighbours) interpolate sample by sample: both from the analytic builder
  // (sample k is the same granule in every row) and of equal count.
  bool pairwise(std::size_t run_a, std::size_t run_b) const;
  // Whether run `run` of these rows is interpolated by quantile cells with a neighbour.
  bool needs_cells(const MaterialRows& rows, std::size_t run) const;
  QuantileCellCounts cell_counts(const MaterialRows& rows) const;
  // Flies the runs that need cells once (landing keys) and fills their cells and cell means.
  void assign_cells(const MaterialRows& rows);
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
  // Construction's parts (predictor.cpp): the contents checked, the runs grouped by material, the samples
  // moved into one block, each material's grid and cells read or derived.
  void check_contents();
  // Run k's launch samples wherever the contents keep them (pooled or per run), before gather_samples().
  std::span<const tables::LaunchSample> contents_samples(std::size_t run) const;
  void group_runs();
  void gather_samples();
  void prepare_landing_data(std::pmr::memory_resource* memory);

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
