#pragma once
// Reads a whole launch-table file into memory. Opens read-only (SQLITE_OPEN_READONLY), checks
// application_id, user_version and PRAGMA quick_check, and validates every record; every failure is a
// TableError whose kind() names the class of problem (missing, not ours, corrupt, wrong version, empty).
#include <array>
#include <cstddef>
#include <memory_resource>
#include <optional>
#include <string>
#include <vector>

#include "libspread/io/tables/landing_data.hpp"
#include "libspread/io/tables/table_format.hpp"

namespace spread::tables {

struct TableContents {
  std::int32_t format_version = kFormatVersion;  // the file's user_version (kOldestReadableVersion..kFormatVersion)
  Machine machine;
  std::vector<Material> materials;   // sorted by name
  std::vector<Run> runs;             // sorted by (material, rpm)
  // Landing data stored with the rows (landing_data.hpp), by material: the reader of it judges whether it
  // is current for them.
  std::vector<LandingData> landing_data;
  // The blends (`blend_components`), by name: each component a material row of its own above.
  std::vector<Blend> blends;
  // Read with a sample memory: every run's samples one after the other in one block from that memory,
  // run k's at [pooled_offset[k], pooled_offset[k + 1]), and each Run::samples left empty. A predictor
  // keeps the block as it is; the samples are written once, straight from SQLite's bytes.
  std::pmr::vector<LaunchSample> pooled_samples;
  std::vector<std::size_t> pooled_offset;
  // The drop-point turns (rad, [low, high] with low <= 0 <= high) over which turning the rows' launches
  // about the disc axis was checked against DEM rows built at the turned drop point (meta key
  // kDropPointTurnValidatedKey, in degrees; docs/table-format.md). Empty: the table states none.
  std::optional<std::array<double, 2>> drop_point_turn_validated_rad;
  // Whether the runs were checked against the table's list of them (runs_manifest.hpp); false only for a
  // legacy table read with ReadOptions::legacy_files.
  bool runs_listed = true;
  const Blend* find_blend(const std::string& name) const {
    for (const Blend& b : blends)
      if (b.name == name) return &b;
    return nullptr;
  }
};

// How read_table_file treats a table with runs but no checked list of them (no `runs_manifest`, or none
// with its checksum): written before the list was checked — or with runs deleted together with the list,
// which a reader cannot tell apart.
struct ReadOptions {
  // false: refused (TableError kWrongVersion, naming this option); true: read with the runs unchecked
  // against a list (TableContents::runs_listed false; a list present without its checksum still has to
  // match the runs).
  bool legacy_files = false;
};

inline constexpr const char* kDropPointTurnValidatedKey = "drop_point_turn_validated_deg";
// The meta value of a validated range, "low,high" in degrees, and its parse (nullopt: not two finite numbers
// with -180 <= low <= 0 <= high <= 180).
std::string drop_point_turn_validated_text(const std::array<double, 2>& range_deg);
std::optional<std::array<double, 2>> parse_drop_point_turn_validated(const std::string& text);

// sample_memory: nullptr, every Run::samples its own vector; otherwise the samples pooled in one block
// from it (TableContents::pooled_samples).
TableContents read_table_file(const std::string& path, std::pmr::memory_resource* sample_memory = nullptr,
                              const ReadOptions& options = {});

}  // namespace spread::tables
