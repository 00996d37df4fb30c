#pragma once
// Writes a calibrated material into a NEW table file (docs/field-calibration.md, step 3): a byte copy of
// the original file, then — through TableWriter — the calibrated material (calibrated_material()) under
// a new name, with one analytic run per rpm row the original material has, rebuilt with the fitted
// parameters (calibrated_launch_samples(): same sample count and seed as the original row). The
// original file is only ever read, and the output must not exist yet: a calibration never overwrites.
// Provenance: each new run keeps the original run's scene text and hash (the machine is the same scene);
// its `effects` names the calibration, and the file's meta table gets a "calibration:<new name>" entry
// with the fitted values, their standard errors and the tray test.
#include <string>
#include <vector>

#include "libspread/calibration/pattern_model.hpp"

namespace spread::calibration {

struct CalibratedTableRequest {
  std::string original_path;      // read only
  std::string output_path;        // must not exist; not the original
  std::string material;           // the calibrated material's name in the original
  std::string new_material_name;  // e.g. calibrated_material_name("Urea", "2026-11-22")
  PatternParameters parameters;
  std::string calibration_json;   // stored verbatim in meta "calibration:<new name>"
};

struct CalibratedTableSummary {
  std::string output_path;
  std::string material;
  std::vector<double> rpm_rows;   // the runs written
  int samples_per_run = 0;        // of the first row
};

// "<name> (calibrated <date>)".
std::string calibrated_material_name(const std::string& material, const std::string& date_yyyy_mm_dd);
// Today's UTC date, YYYY-MM-DD.
std::string utc_date_today();

// Throws std::invalid_argument for an output that exists or is the original, an unknown material or a
// new name already in the table; tables::TableError for an unreadable original or an output that cannot
// be written. A failure after the copy removes the partial output.
CalibratedTableSummary write_calibrated_table(const CalibratedTableRequest& request);

}  // namespace spread::calibration
