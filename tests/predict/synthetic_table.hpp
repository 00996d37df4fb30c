#pragma once
// Launch-table files for the predictor and C API tests, written with the real tables::TableWriter
// (never a hand-made format). The launch states follow the Patterson & Reece picture (docs/design.md §2):
// granules leave the rim of a flat disc with the rim speed ωR tangentially plus a radial component, over
// an arc of launch angles, with a spread of diameters. Sample k of every row of a material describes the
// same granule (same angle and diameter), as the analytic builder does, so rows interpolate pairwise.
#include <string>
#include <vector>

#include "libspread/io/tables/table_format.hpp"
#include "libspread/io/tables/table_reader.hpp"

namespace spread::testing {

struct SyntheticMaterial {
  std::string name;
  double density_kg_m3;
  std::vector<double> rpms;
  int samples_per_row;           // same count in every row → pairwise interpolation
  int samples_first_row = -1;    // >= 0: the first row has this count instead → mixture interpolation
};

// The machine of every synthetic table: twin disc, R = 0.3 m, height 0.8 m, spacing 1.0 m.
tables::Machine synthetic_machine(int disc_count = 2);

// The normalised samples of one row (deterministic in material, rpm and count).
std::vector<tables::LaunchSample> synthetic_samples(double rpm, int count, double density_kg_m3);

// Default materials: "can" (CAN 27, 256 samples at 500/600/700/800 rpm) and "urea" (mixture rows:
// 200 samples at 500 rpm, 256 at 700 rpm).
std::vector<SyntheticMaterial> default_synthetic_materials();

// The same contents in memory, as read_table_file() would return them (materials and runs sorted).
tables::TableContents synthetic_contents(
    const std::vector<SyntheticMaterial>& materials = default_synthetic_materials(), int disc_count = 2);

// Writes a table file at `path` (replacing any existing file).
void write_synthetic_table(const std::string& path,
                           const std::vector<SyntheticMaterial>& materials = default_synthetic_materials(),
                           int disc_count = 2);

// A table file with machine and materials but no runs (for the "empty" error).
void write_table_without_runs(const std::string& path);

}  // namespace spread::testing
