#pragma once
// The one error type for configuration and file problems: what kind, where (the scene key, the file
// path or the argument), and a message that names both. Scenes (scene::SceneError) and table files
// (tables::TableError) throw it through their own names; each boundary maps the kind once — the CLI to
// its exit code (tools/spread/command_registry.hpp), the C API to its status (capi/src/tables_handle.cpp).
#include <stdexcept>
#include <string>

namespace spread {

enum class ErrorKind {
  kScene,         // a scene value is missing, unknown, of the wrong type or impossible
  kArgument,      // a caller's argument (a CLI option, a library call) is impossible
  kMissing,       // no such file
  kNotOurs,       // not SQLite, or not a libspread table (application_id)
  kCorrupt,       // a file's content is damaged or impossible
  kWrongVersion,  // a table file of another format version
  kEmpty,         // a table file without runs
  kIo,            // any other read/write failure (locked, read-only, disk full)
};

constexpr const char* to_string(ErrorKind kind) {
  switch (kind) {
    case ErrorKind::kScene: return "bad scene";
    case ErrorKind::kArgument: return "bad argument";
    case ErrorKind::kMissing: return "missing";
    case ErrorKind::kNotOurs: return "not a libspread table";
    case ErrorKind::kCorrupt: return "corrupt";
    case ErrorKind::kWrongVersion: return "wrong format version";
    case ErrorKind::kEmpty: return "empty";
    case ErrorKind::kIo: return "i/o error";
  }
  return "unknown";
}

class Error : public std::runtime_error {
 public:
  // `message` is the whole text shown to the user; it names `where` already.
  Error(ErrorKind kind, std::string where, const std::string& message)
      : std::runtime_error(message), kind_(kind), where_(std::move(where)) {}
  ErrorKind kind() const { return kind_; }
  const std::string& where() const { return where_; }

 private:
  ErrorKind kind_;
  std::string where_;
};

}  // namespace spread
