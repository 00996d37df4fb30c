#pragma once
// The `blend_components` rows of a table file (internal header, as table_rows.hpp): one row per component
// of a blend, its position in the blend, its material row, its mass fraction and nutrient contents, and
// the row's checksum (CRC-64/XZ of blend, position, material, mass_fraction, n_pct, p2o5_pct, k2o_pct in
// the canonical form of row_checksum.hpp). docs/table-format.md "blend_components".
#include <cstdint>
#include <string>
#include <vector>

#include "libspread/io/tables/sqlite_connection.hpp"
#include "libspread/io/tables/table_format.hpp"

namespace spread::tables::detail {

inline constexpr const char* kBlendComponentsTable = "blend_components";

std::string blend_component_checksum(const std::string& blend, std::int64_t position, const BlendRowComponent& c);

// Every blend of the file, by name, its components by position; kCorrupt naming the row for an impossible
// value (blend_problem's rules), a position missing, a checksum mismatch, or a component whose material
// row is not in `materials`. A version-2 file has no such table: no blends.
std::vector<Blend> read_blend_rows(Connection& db, const std::vector<Material>& materials);

// Replaces the blend's rows (inside the caller's transaction).
void write_blend_rows(Connection& db, const Blend& blend);

}  // namespace spread::tables::detail
