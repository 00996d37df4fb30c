#pragma once
// Writes a calibrated material into a NEW table file (docs/field-calibration.md, step 3): a byte copy of
// the original file, then — through TableWriter — the calibrated material (calibrated_material()) under
// a new name, with one run per rpm row the original material has: an analytic row rebuilt with the fitted
// parameters (calibrated_launch_samples(): same sample count and seed as the original row), a DEM row's
// own samples corrected by them (corrected_launch_samples()). The
// original file is only ever read, and the output must not exist yet: a calibration never overwrites.
// Provenance: each new run keeps the original run's scene text and hash (the machine is the same scene);
// its `effects` names the calibration, and the file's meta table gets a "calibration:<new name>" entry
// with the fitted values, their standard errors and the tray test.
#include <string>
#include <vector>

#include "libspread/analysis/calibration/pattern_model.hpp"
#include "libspread/io/tables/table_reader.hpp"

namespace spread::calibration {

struct CalibratedTableRequest {
  std::string original_path;      // read only
  std::string output_path;        // must not exist; not the original
  std::string material;           // the calibrated material's name in the original
  std::string new_material_name;  // e.g. calibrated_material_name("Urea", "2026-11-22")
  PatternParameters parameters;
  std::string calibration_json;   // stored verbatim in meta "calibration:<new name>"
  // Rows from the analytic model are rebuilt by it with the fitted parameters. Rows from the DEM (source
  // "dem") keep their own launch samples with the fitted correction (corrected_launch_samples()) — unless
  // this is set (`spread calibrate pattern --allow-analytic`): then they too are rebuilt analytically.
  bool allow_analytic_for_dem = false;
};

struct CalibratedTableSummary {
  std::string output_path;
  std::string material;
  std::vector<double> rpm_rows;   // the runs written
  int samples_per_run = 0;        // of the first row
  std::vector<double> replaced_dem_rpm;  // DEM rows of the original rebuilt analytically (allow_analytic_for_dem)
};

// The rpm of each row of `material` in the table that did not come from the analytic model (source
// other than "analytic", i.e. DEM rows), in table order.
std::vector<double> non_analytic_rows(const tables::TableContents& contents, const std::string& material);

// "<name> (calibrated <date>)"; the date is the caller's (spread calibrate pattern: SOURCE_DATE_EPOCH's when set,
// else today's, UTC), so the same inputs give the same name.
std::string calibrated_material_name(const std::string& material, const std::string& date_yyyy_mm_dd);

// A name the technician gives the calibrated material, kept as the product's name with that tag:
// "field" for Urea is "Urea (field)"; "Urea (field)" stays. A chart of "Urea" then finds its calibrated
// versions by their names (they keep the product's), and a reader sees what was calibrated.
std::string tagged_material_name(const std::string& material, const std::string& tag);

// Throws std::invalid_argument for an output that exists or is the original, an unknown material, a
// new name already in the table; tables::TableError for an unreadable original or an output that cannot
// be written. A failure after the copy removes the partial output.
CalibratedTableSummary write_calibrated_table(const CalibratedTableRequest& request);

}  // namespace spread::calibration
