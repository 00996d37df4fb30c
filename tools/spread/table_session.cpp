#include "tools/spread/table_session.hpp"

#include <stdexcept>
#include <string>
#include <utility>

#include "capi/src/in_tree_open.hpp"
#include "libspread/core/error.hpp"

namespace spread::cli {

namespace {

tables::TableContents read_naming(const std::string& path, const std::string& option) {
  try {
    return tables::read_table_file(path);
  } catch (const tables::TableError& e) {
    if (option.empty()) throw;
    throw tables::TableError(e.kind(), option + " '" + path + "': " + e.what());
  }
}

}  // namespace

TableSession::TableSession(std::string path, const std::string& option)
    : path_(std::move(path)), contents_(read_naming(path_, option)) {}

TableSession::~TableSession() {
  if (capi_ != nullptr) spread_close(capi_);
}

predict::Predictor& TableSession::predictor() {
  if (!predictor_) predictor_.emplace(contents_);
  return *predictor_;
}

spread_tables* TableSession::capi() {
  if (capi_ != nullptr) return capi_;
  const spread_status status = capi::open_contents(contents_, &capi_);
  if (status == SPREAD_OK) return capi_;
  const std::string message =
      "--tables '" + path_ + "': " + spread_status_str(status) + ": " + spread_last_error_detail();
  if (status == SPREAD_ERROR_OUT_OF_MEMORY || status == SPREAD_ERROR_INTERNAL) throw std::runtime_error(message);
  throw Error(ErrorKind::kCorrupt, {}, message);
}

}  // namespace spread::cli
