#include "libspread/tables/table_format.hpp"

namespace spread::tables {

const char* to_string(TableErrorKind kind) {
  switch (kind) {
    case TableErrorKind::kMissing: return "missing";
    case TableErrorKind::kNotOurs: return "not a libspread table";
    case TableErrorKind::kCorrupt: return "corrupt";
    case TableErrorKind::kWrongVersion: return "wrong format version";
    case TableErrorKind::kEmpty: return "empty";
    case TableErrorKind::kIo: return "i/o error";
  }
  return "unknown";
}

}  // namespace spread::tables
