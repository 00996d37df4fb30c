#pragma once
// The table's list of its runs (meta key `runs_manifest`, docs/table-format.md "Checksums"). Each run row
// carries its own checksum, which finds a changed value but not a run deleted or added whole: a table that
// lost its Urea 600 rpm row still reads, and predictions between the remaining rows silently move. The
// writer keeps, in the same transaction as every run it writes, one line per run — material, rpm, the
// row's checksum — and the reader compares it with the runs it finds.
#include <string>

#include "libspread/io/tables/sqlite_connection.hpp"

namespace spread::tables::detail {

inline constexpr const char* kRunsManifestKey = "runs_manifest";

// "material\trpm\tchecksum\n" per run, ordered by material and rpm (rpm as %.17g: exact).
std::string runs_manifest(Connection& db);

// "" when `stored` lists exactly the runs of `actual`; otherwise what differs, naming the first run that
// is missing, added or changed ("run Urea @ 600 rpm is in the manifest but not in `runs` (deleted?)").
std::string manifest_problem(const std::string& stored, const std::string& actual);

}  // namespace spread::tables::detail
