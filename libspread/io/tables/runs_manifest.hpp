#pragma once
// The table's list of its runs (meta key `runs_manifest`, docs/table-format.md "Checksums"). Each run row
// carries its own checksum, which finds a changed value but not a run deleted or added whole: a table that
// lost its Urea 600 rpm row still reads, and predictions between the remaining rows silently move. The
// writer keeps, in the same transaction as every run it writes, one line per run — material, rpm, the
// row's checksum — and the list's own checksum (meta key `runs_manifest_checksum`, CRC-64/XZ as the rows'),
// and the reader compares them with the runs it finds: a run deleted together with its line leaves the
// list's checksum stale. A table whose runs carry no checked list was written before the list was checked
// (or had it removed): the reader refuses it unless asked to read such legacy tables.
#include <string>

#include "libspread/io/tables/sqlite_connection.hpp"

namespace spread::tables::detail {

inline constexpr const char* kRunsManifestKey = "runs_manifest";
inline constexpr const char* kRunsManifestChecksumKey = "runs_manifest_checksum";

// "material\trpm\tchecksum\n" per run, ordered by material and rpm (rpm as %.17g: exact).
std::string runs_manifest(Connection& db);

// The list's checksum as stored under kRunsManifestChecksumKey: CRC-64/XZ of its text (row_checksum.hpp).
std::string manifest_checksum(const std::string& manifest);

// "" when `stored` lists exactly the runs of `actual`; otherwise what differs, naming the first run that
// is missing, added or changed ("run Urea @ 600 rpm is in the manifest but not in `runs` (deleted?)").
std::string manifest_problem(const std::string& stored, const std::string& actual);

}  // namespace spread::tables::detail
