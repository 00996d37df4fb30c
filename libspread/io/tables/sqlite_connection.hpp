#pragma once
// Thin RAII wrappers over the sqlite3 C API used by the table reader and writer (internal header).
// Every failure becomes a TableError whose message names the file and the SQLite message; the kind
// follows the SQLite result code (SQLITE_NOTADB → kNotOurs, SQLITE_CORRUPT → kCorrupt, else kIo).
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "libspread/io/tables/table_format.hpp"

struct sqlite3;
struct sqlite3_stmt;

namespace spread::tables::detail {

TableErrorKind kind_from_sqlite_code(int code);

class Connection {
 public:
  // kReadOnlyImmutable: read-only without locks or side files (SQLite's immutable=1), for a file in WAL
  // mode whose log is empty: a plain read-only open would create -wal and -shm files beside it.
  enum class Mode { kReadOnly, kReadOnlyImmutable, kReadWrite, kReadWriteCreate };
  Connection(const std::string& path, Mode mode);
  ~Connection();
  Connection(const Connection&) = delete;
  Connection& operator=(const Connection&) = delete;

  const std::string& path() const { return path_; }
  sqlite3* handle() const { return db_; }
  void exec(const std::string& sql);                 // statements without results
  std::int64_t pragma_int(const std::string& name);  // e.g. "application_id"
  [[noreturn]] void fail(int code, const std::string& doing) const;

 private:
  std::string path_;
  sqlite3* db_ = nullptr;
};

class Statement {
 public:
  Statement(Connection& connection, const std::string& sql);
  ~Statement();
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;

  // Bind by 1-based index.
  void bind(int index, double value);
  void bind(int index, std::int64_t value);
  void bind(int index, const std::string& value);
  void bind_blob(int index, std::span<const std::uint8_t> bytes);
  bool step();  // true: a row is available; false: done
  void reset();

  double column_double(int column) const;
  std::int64_t column_int(int column) const;
  std::string column_text(int column) const;
  std::vector<std::uint8_t> column_blob(int column) const;
  // The BLOB where SQLite holds it: valid until the next step() or the statement's end.
  std::span<const std::uint8_t> column_blob_view(int column) const;
  bool column_is_null(int column) const;

 private:
  Connection& connection_;
  sqlite3_stmt* stmt_ = nullptr;
  std::string sql_;
};

}  // namespace spread::tables::detail
