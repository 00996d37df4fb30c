#pragma once
// The discs' own settings the ECU cannot work out inside its 50 ms loop step:
// - section control through the discs: when a task controller switches a side's outer sections off, that
//   side's disc must stop throwing beyond the last section left on — the border search of
//   docs/field-calibration.md "Border and edge spreading" with the edge line at that section's outer end
//   (the strip beyond it is spread already: a headland, a wedge, an earlier pass);
// - border and field-edge spreading: the same search with the edge line the border mode names;
// - wind compensation: each disc's speed and drop point in the measured wind (spread_compensate_wind).
// A border search costs hundreds of predictions (about half a second on the main job's table), wind
// compensation about fifty, so the planner answers from a cache and searches on a worker thread of its
// own, with its own predictor (a C API handle is not shared between threads): the loop never waits.
// Until a plan is known the ECU keeps that disc as it was and says so (ecu.hpp).
//
// When the field's setting changes, the ECU asks for every section narrowing of both sides at once
// (prepare), so that a section switched off later is usually answered from the cache.
#include <array>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string_view>
#include <thread>

#include "libspread/control/ecu_parameters.hpp"
#include "libspread/control/spread_predictor.hpp"

namespace spread::firmware {

inline constexpr std::size_t kMaxPlanMaterialLength = 63;  // bytes, as the ECU's material names
inline constexpr int kMaxSideSections = kMaxSections / 2;  // sections on one side of the centre line

enum class PlanKind : std::int32_t {
  kSections,   // a side narrowed to its last section on (border thresholds)
  kBorder,     // a side at a border: nothing beyond gap_m inside the bout's edge
  kFieldEdge,  // a side next to another field: full rate out to gap_m inside the bout's edge
  kWind,       // both discs compensating the wind
};

// One plan under one field setting. Plain values (no allocation), compared exactly.
struct SidePlanKey {
  std::array<char, kMaxPlanMaterialLength + 1> material{};  // NUL-terminated
  double rpm = 0.0;            // the field's disc speed [r/min]
  double bout_width_m = 0.0;   // [m]
  std::int32_t section_count = 0;
  PlanKind kind = PlanKind::kSections;
  std::int32_t side = kRightDisc;  // kLeftDisc, kRightDisc (kWind: unused)
  // kSections: of the side's own sections, those on, counted from the centre line outward: 1 up to the
  // side's count less one; with an odd count also 0 (only the section on the centre line on).
  std::int32_t sections_on = 0;
  double gap_m = 0.0;          // kBorder, kFieldEdge: the edge line this far inside the bout's edge [m]
  double wind_x_m_s = 0.0;     // the wind every plan is made in [m/s]
  double wind_y_m_s = 0.0;

  bool operator==(const SidePlanKey&) const = default;
};

// The side's own sections (a middle one excluded) and where the edge line of a key lies.
struct SideGeometry {
  int side_sections = 0;      // sections on one side
  double section_width_m = 0.0;
  double inner_m = 0.0;       // the side's first section starts this far from the centre line (half a
                              // section when one straddles it)
  double edge_line_m(int sections_on) const { return inner_m + sections_on * section_width_m; }
};
SideGeometry side_geometry(double bout_width_m, int section_count);

struct SidePlan {
  SideNarrowing narrowing;                  // the side's disc (kWind: unused)
  std::array<SideNarrowing, 2> wind_discs;  // kWind: each disc
  // Mean rate of each of the side's own sections on this pass (the pass before it included), percent of
  // the field's; index j = the side's j-th section from the centre line. Not for kWind.
  std::array<double, kMaxSideSections> section_rate_percent{};
  bool known = false;  // false: the search failed or the predictor cannot narrow (then the side stays)
};

class SectionPlanner {
 public:
  enum class Threading { kWorker, kInline };
  // `predictor` is used by the planner alone (on its worker thread with kWorker) and must outlive it.
  // kInline plans inside lookup(): deterministic, for tests and replays where the loop may wait.
  SectionPlanner(SpreadPredictor& predictor, double max_beyond_percent, Threading threading = Threading::kWorker);
  ~SectionPlanner();
  SectionPlanner(const SectionPlanner&) = delete;
  SectionPlanner& operator=(const SectionPlanner&) = delete;

  // The plan for `key` when known; otherwise nullopt, and the key is searched next. Allocation-free
  // (the queue keeps its capacity), never blocks on a search with kWorker.
  std::optional<SidePlan> lookup(const SidePlanKey& key);
  // Every section narrowing of both sides under this field setting (`key`'s kind, side and sections_on
  // ignored), queued behind the keys the loop asked for.
  void prepare(const SidePlanKey& field);
  // Searches done so far (cost indicator, tests).
  std::int64_t searches() const;

 private:
  static constexpr std::size_t kCacheSize = 64;
  static constexpr std::size_t kQueueCapacity = 4 * kMaxSections;
  struct Entry {
    SidePlanKey key;
    SidePlan plan;
    std::uint64_t used = 0;  // lookup counter at last use (least recently used is replaced)
  };

  SidePlan search(const SidePlanKey& key);  // never throws: a failure is an unknown plan
  SidePlan search_unguarded(const SidePlanKey& key);
  void store(const SidePlanKey& key, const SidePlan& plan);  // under mutex_
  const Entry* find(const SidePlanKey& key) const;            // under mutex_
  void enqueue(const SidePlanKey& key, bool first);           // under mutex_
  void work();

  SpreadPredictor& predictor_;
  double max_beyond_percent_;
  Threading threading_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::array<Entry, kCacheSize> cache_{};
  std::size_t cache_count_ = 0;
  std::uint64_t clock_ = 0;
  std::array<SidePlanKey, kQueueCapacity> queue_{};  // [0, queue_count_): next first
  std::size_t queue_count_ = 0;
  std::optional<SidePlanKey> searching_;  // the key the worker is searching now (not queued again)
  std::int64_t searches_ = 0;
  bool stop_ = false;
  std::thread worker_;
};

}  // namespace spread::firmware
