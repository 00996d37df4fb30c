#pragma once
// The one way a `spread` command reaches its launch table and prediction: the file named by --tables read
// once (tables::read_table_file), and from those contents, as the command needs them, the Predictor (plot,
// chart, border, guidance) and the C API's handle (`spread predict`, which goes through spread.h on
// purpose: what it prints is what an integrator gets). No command opens the table file a second time
// (tests/tools/test_table_opened_once.sh counts the opens of the file).
#include <memory>
#include <optional>
#include <string>

#include "libspread/analysis/predict/predictor.hpp"
#include "libspread/io/tables/table_reader.hpp"
#include "spread/spread.h"

namespace spread::cli {

class TableSession {
 public:
  // Reads the table file at `path`, given by the command's `option` (--tables; "" for a positional file):
  // a file that is not a readable launch table throws tables::TableError naming the option, the file and
  // what is wrong (its kind gives the exit code, once, in main).
  explicit TableSession(std::string path, const std::string& option = "--tables");
  TableSession(const TableSession&) = delete;
  TableSession& operator=(const TableSession&) = delete;
  ~TableSession();

  const std::string& path() const { return path_; }
  // The contents as read, samples per run (the bootstrap of --stability and the calibrations resample
  // them).
  const tables::TableContents& contents() const { return contents_; }
  const tables::Machine& machine() const { return contents_.machine; }
  // The Predictor over the table (the tools' limits), made on first use from a copy of the contents.
  predict::Predictor& predictor();
  // The C API's handle over the same contents (the controller's limits, as spread_open makes it), made on
  // first use; owned by the session. BadInput-like failures of the C API are thrown as spread_open's
  // would be reported: the status and its detail.
  spread_tables* capi();

 private:
  std::string path_;
  tables::TableContents contents_;
  std::optional<predict::Predictor> predictor_;
  spread_tables* capi_ = nullptr;
};

}  // namespace spread::cli
