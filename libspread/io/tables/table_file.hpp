#pragma once
// What a path holds, found with plain POSIX calls before SQLite opens it (internal header). SQLite's own
// open would block forever on a FIFO, report a permission problem as a missing file, and create -wal and
// -shm files beside a WAL-mode database even when opened read-only.
#include <cstdint>
#include <string>

namespace spread::tables::detail {

struct TableFileInfo {
  bool exists = false;          // false: no such file (only when allow_missing)
  bool empty = false;           // a zero-byte regular file
  std::int64_t bytes = 0;       // its size when inspected
  bool sqlite = false;          // starts with "SQLite format 3\0"
  bool wal = false;             // the header says WAL mode (bytes 18 and 19 are 2; sqlite.org/fileformat2.html)
  bool wal_has_content = false; // a non-empty PATH-wal beside it
  bool hot_journal = false;     // a non-empty PATH-journal beside it (a writer stopped mid-transaction)
  std::int32_t application_id = 0;  // header bytes 68..71, big-endian
  std::int32_t user_version = 0;    // header bytes 60..63, big-endian (the format version)
};

// Throws TableError: kMissing (no such file, unless allow_missing), kNotOurs (a directory, a FIFO,
// socket or device), kIo (exists but cannot be read, e.g. permission denied). Never blocks, never writes.
TableFileInfo inspect_table_file(const std::string& path, bool allow_missing);

}  // namespace spread::tables::detail
