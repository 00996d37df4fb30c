#include "libspread/io/tables/sqlite_connection.hpp"

#include <sqlite3.h>

namespace spread::tables::detail {

TableErrorKind kind_from_sqlite_code(int code) {
  switch (code & 0xff) {  // primary result code
    case SQLITE_NOTADB: return TableErrorKind::kNotOurs;
    case SQLITE_CORRUPT: return TableErrorKind::kCorrupt;
    case SQLITE_CANTOPEN: return TableErrorKind::kMissing;
    default: return TableErrorKind::kIo;
  }
}

namespace {

// An RFC 3986 file: URI for sqlite3_open_v2 with SQLITE_OPEN_URI: only '%', '?' and '#' need escaping.
std::string file_uri(const std::string& path, const char* query) {
  std::string uri = "file:";
  for (char c : path) {
    if (c == '%' || c == '?' || c == '#') {
      static constexpr char kHex[] = "0123456789ABCDEF";
      uri += '%';
      uri += kHex[(static_cast<unsigned char>(c) >> 4) & 0xF];
      uri += kHex[static_cast<unsigned char>(c) & 0xF];
    } else {
      uri += c;
    }
  }
  return uri + "?" + query;
}

}  // namespace

Connection::Connection(const std::string& path, Mode mode) : path_(path) {
  int flags = 0;
  std::string name = path;
  switch (mode) {
    case Mode::kReadOnly: flags = SQLITE_OPEN_READONLY; break;
    case Mode::kReadOnlyImmutable:
      flags = SQLITE_OPEN_READONLY | SQLITE_OPEN_URI;
      name = file_uri(path, "immutable=1");
      break;
    case Mode::kReadWrite: flags = SQLITE_OPEN_READWRITE; break;
    case Mode::kReadWriteCreate: flags = SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE; break;
  }
  const int rc = sqlite3_open_v2(name.c_str(), &db_, flags | SQLITE_OPEN_NOMUTEX, nullptr);
  if (rc != SQLITE_OK) fail(rc, "cannot open");
  sqlite3_extended_result_codes(db_, 1);
  // A writer waits a little for another process instead of failing at once.
  sqlite3_busy_timeout(db_, 5000);
}

Connection::~Connection() { sqlite3_close_v2(db_); }

void Connection::fail(int code, const std::string& doing) const {
  if (code == SQLITE_READONLY_ROLLBACK) {
    // A writer stopped inside a transaction (killed, power lost) and left a hot rollback journal; only a
    // read-write connection may roll it back, which lookup_builder's writer does when it opens the file.
    throw TableError(TableErrorKind::kIo, path_ + ": interrupted write: a rollback journal (" + path_ +
                                              "-journal) was left by a writer that stopped mid-transaction; "
                                              "rerun lookup_builder on this file to recover it");
  }
  std::string message = path_ + ": " + doing + ": ";
  message += (db_ != nullptr && sqlite3_errcode(db_) == code) ? sqlite3_errmsg(db_) : sqlite3_errstr(code);
  throw TableError(kind_from_sqlite_code(code), message);
}

void Connection::exec(const std::string& sql) {
  char* error = nullptr;
  const int rc = sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &error);
  if (rc != SQLITE_OK) {
    std::string text = error != nullptr ? error : sqlite3_errstr(rc);
    sqlite3_free(error);
    throw TableError(kind_from_sqlite_code(rc), path_ + ": " + text + " (in: " + sql.substr(0, 60) + ")");
  }
}

std::int64_t Connection::pragma_int(const std::string& name) {
  Statement statement(*this, "PRAGMA " + name);
  if (!statement.step()) throw TableError(TableErrorKind::kIo, path_ + ": PRAGMA " + name + " returned nothing");
  return statement.column_int(0);
}

Statement::Statement(Connection& connection, const std::string& sql) : connection_(connection), sql_(sql) {
  const int rc = sqlite3_prepare_v2(connection_.handle(), sql.c_str(), -1, &stmt_, nullptr);
  if (rc != SQLITE_OK) connection_.fail(rc, "cannot prepare \"" + sql.substr(0, 60) + "\"");
}

Statement::~Statement() { sqlite3_finalize(stmt_); }

void Statement::bind(int index, double value) {
  const int rc = sqlite3_bind_double(stmt_, index, value);
  if (rc != SQLITE_OK) connection_.fail(rc, "bind");
}
void Statement::bind(int index, std::int64_t value) {
  const int rc = sqlite3_bind_int64(stmt_, index, value);
  if (rc != SQLITE_OK) connection_.fail(rc, "bind");
}
void Statement::bind(int index, const std::string& value) {
  const int rc = sqlite3_bind_text(stmt_, index, value.c_str(), static_cast<int>(value.size()), SQLITE_TRANSIENT);
  if (rc != SQLITE_OK) connection_.fail(rc, "bind");
}
void Statement::bind_blob(int index, std::span<const std::uint8_t> bytes) {
  const int rc = sqlite3_bind_blob64(stmt_, index, bytes.data(), bytes.size(), SQLITE_TRANSIENT);
  if (rc != SQLITE_OK) connection_.fail(rc, "bind");
}

bool Statement::step() {
  const int rc = sqlite3_step(stmt_);
  if (rc == SQLITE_ROW) return true;
  if (rc == SQLITE_DONE) return false;
  connection_.fail(rc, "cannot run \"" + sql_.substr(0, 60) + "\"");
}

void Statement::reset() {
  sqlite3_reset(stmt_);
  sqlite3_clear_bindings(stmt_);
}

double Statement::column_double(int column) const { return sqlite3_column_double(stmt_, column); }
std::int64_t Statement::column_int(int column) const { return sqlite3_column_int64(stmt_, column); }
std::string Statement::column_text(int column) const {
  const unsigned char* text = sqlite3_column_text(stmt_, column);
  const int size = sqlite3_column_bytes(stmt_, column);
  return text != nullptr ? std::string(reinterpret_cast<const char*>(text), static_cast<std::size_t>(size))
                         : std::string();
}
std::vector<std::uint8_t> Statement::column_blob(int column) const {
  const auto* data = static_cast<const std::uint8_t*>(sqlite3_column_blob(stmt_, column));
  const int size = sqlite3_column_bytes(stmt_, column);
  if (data == nullptr || size <= 0) return {};
  return std::vector<std::uint8_t>(data, data + size);
}
std::span<const std::uint8_t> Statement::column_blob_view(int column) const {
  const auto* data = static_cast<const std::uint8_t*>(sqlite3_column_blob(stmt_, column));
  const int size = sqlite3_column_bytes(stmt_, column);  // after the pointer: sqlite3_column_bytes' own advice
  if (data == nullptr || size <= 0) return {};
  return {data, static_cast<std::size_t>(size)};
}
bool Statement::column_is_null(int column) const { return sqlite3_column_type(stmt_, column) == SQLITE_NULL; }

}  // namespace spread::tables::detail
