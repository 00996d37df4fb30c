// The landing grid against flying every launch sample on the main job's DEM table (the fixture of
// capi.fixture.default_scene), over the grid's domain: every material, rows and between rows, disc
// heights and winds across it. No working width, throw width or CV may differ by more than its own 95 %
// interval (1.96 standard errors over the launch samples): the grid's error is below what the table's
// sampling leaves uncertain.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <string>

#include "libspread/analysis/predict/predictor.hpp"
#include "libspread/io/tables/table_reader.hpp"

namespace spread::predict {
namespace {

TEST(DefaultGrid, NoWidthOrCvMovesByMoreThanItsInterval) {
  if (!std::filesystem::exists(SPREAD_DEFAULT_TABLE)) {
    GTEST_SKIP() << SPREAD_DEFAULT_TABLE << " missing: run through ctest (fixture capi.fixture.default_scene)";
  }
  Predictor gridded(tables::read_table_file(SPREAD_DEFAULT_TABLE));
  Predictor flown(tables::read_table_file(SPREAD_DEFAULT_TABLE));
  flown.set_landing_grid_enabled(false);
  const LandingDomain& domain = gridded.landing_domain();
  struct Condition {
    double height_m, wind_x_m_s, wind_y_m_s;
  };
  const double stored = std::numeric_limits<double>::quiet_NaN();
  const Condition conditions[] = {{stored, 0.0, 0.0},
                                  {domain.min_disc_height_m, 3.0, 0.0},
                                  {1.2, 0.0, -5.0},
                                  {domain.max_disc_height_m, 0.7 * domain.max_wind_m_s, 0.7 * domain.max_wind_m_s}};
  double worst_ratio = 0.0;
  std::string worst;
  int requests = 0;
  for (std::size_t m = 0; m < gridded.material_count(); ++m) {
    const std::string name = gridded.material(m).name;
    for (double rpm : {450.0, 525.0, 600.0, 675.0, 750.0}) {
      for (const Condition& c : conditions) {
        PredictionRequest r;
        r.material = name;
        r.rpm = rpm;
        r.disc_height_m = c.height_m;
        r.wind_x_m_s = c.wind_x_m_s;
        r.wind_y_m_s = c.wind_y_m_s;
        r.bout_width_m = 10.0;  // the CV at a fixed bout, beside the working width
        Prediction a, b;
        ASSERT_EQ(gridded.predict(r, a), PredictStatus::kOk);
        ASSERT_EQ(flown.predict(r, b), PredictStatus::kOk);
        ASSERT_EQ(a.flights, 0);
        ASSERT_GT(b.flights, 0);
        ++requests;
        const std::string where = name + " " + std::to_string(rpm) + " rpm, height " + std::to_string(c.height_m) +
                                  " m, wind " + std::to_string(c.wind_x_m_s) + "," + std::to_string(c.wind_y_m_s);
        const auto check = [&](const char* what, double grid, double fly, double se) {
          ASSERT_TRUE(std::isfinite(se) && se > 0.0) << what << " " << where;
          const double ratio = std::abs(grid - fly) / (kConfidence95 * se);
          EXPECT_LE(ratio, 1.0) << what << ": grid " << grid << ", flown " << fly << " ± " << kConfidence95 * se
                                << " at " << where;
          if (ratio > worst_ratio) {
            worst_ratio = ratio;
            worst = std::string(what) + " at " + where;
          }
        };
        check("throw width", a.throw_width_m, b.throw_width_m, b.throw_width_se_m);
        check("CV at 10 m", a.cv_to_and_fro, b.cv_to_and_fro, b.cv_to_and_fro_se);
        if (a.headline_band_to_and_fro >= 0 && b.headline_band_to_and_fro >= 0 &&
            std::isfinite(b.working_width_to_and_fro_se_m)) {
          check("working width", a.working_width_to_and_fro_m, b.working_width_to_and_fro_m,
                b.working_width_to_and_fro_se_m);
        }
      }
    }
  }
  std::printf("%d requests; the largest difference is %.3f of its 95 %% interval: %s\n", requests, worst_ratio,
              worst.c_str());
}

}  // namespace
// lookup_builder stores each material's landing grid and quantile cells in the table (landing_data), and
// a Predictor reads them instead of flying them: what it reads is byte for byte what a Predictor derives
// from the same rows, and it predicts bit for bit the same. Data that no longer fits its rows is derived
// afresh.
TEST(DefaultGrid, StoredLandingDataIsWhatAReaderDerives) {
  if (!std::filesystem::exists(SPREAD_DEFAULT_TABLE)) {
    GTEST_SKIP() << SPREAD_DEFAULT_TABLE << " missing: run through ctest (fixture capi.fixture.default_scene)";
  }
  tables::TableContents contents = tables::read_table_file(SPREAD_DEFAULT_TABLE);
  const std::vector<tables::LandingData> stored = contents.landing_data;
  ASSERT_EQ(stored.size(), 3u) << "one row of landing data per material";
  tables::TableContents bare = contents;
  bare.landing_data.clear();
  Predictor read(std::move(contents));
  Predictor derived(std::move(bare));
  for (std::size_t m = 0; m < read.material_count(); ++m) {
    EXPECT_TRUE(read.landing_data_from_table(m)) << read.material(m).name;
    EXPECT_FALSE(derived.landing_data_from_table(m));
  }
  EXPECT_TRUE(read.derived_landing_data().empty());
  const std::vector<tables::LandingData> again = derived.derived_landing_data();
  ASSERT_EQ(again.size(), stored.size());
  for (std::size_t m = 0; m < stored.size(); ++m) {
    EXPECT_EQ(again[m].material, stored[m].material);
    EXPECT_EQ(again[m].model, stored[m].model);
    EXPECT_TRUE(again[m].data == stored[m].data) << stored[m].material;
  }
  // Contents changed after reading (a row left out): that material's stored data no longer fits its rows
  // and is derived afresh; the others' still is read.
  tables::TableContents edited = tables::read_table_file(SPREAD_DEFAULT_TABLE);
  std::erase_if(edited.runs, [](const tables::Run& run) { return run.material == "Urea" && run.rpm == 600.0; });
  const Predictor after_edit(std::move(edited));
  for (std::size_t m = 0; m < after_edit.material_count(); ++m) {
    EXPECT_EQ(after_edit.landing_data_from_table(m), after_edit.material(m).name != "Urea") << after_edit.material(m).name;
  }
  // Data of another model (another build's grid or flight settings) is derived afresh too.
  tables::TableContents other_model = tables::read_table_file(SPREAD_DEFAULT_TABLE);
  for (tables::LandingData& landing : other_model.landing_data) {
    if (landing.material == "DAP") landing.model += " (another build)";
  }
  const Predictor after_model(std::move(other_model));
  for (std::size_t m = 0; m < after_model.material_count(); ++m) {
    EXPECT_EQ(after_model.landing_data_from_table(m), after_model.material(m).name != "DAP") << after_model.material(m).name;
  }
  // Data of this model and these rows that does not fit them (here: cut short) is a damaged table, named.
  tables::TableContents cut = tables::read_table_file(SPREAD_DEFAULT_TABLE);
  cut.landing_data[0].data.resize(cut.landing_data[0].data.size() - 4);
  try {
    const Predictor refused(std::move(cut));
    ADD_FAILURE() << "landing data cut short was accepted";
  } catch (const tables::TableError& e) {
    EXPECT_EQ(e.kind(), tables::TableErrorKind::kCorrupt);
    EXPECT_NE(std::string(e.what()).find("landing data of " + stored[0].material), std::string::npos) << e.what();
  }
  for (const char* material : {"Urea", "DAP"}) {
    PredictionRequest r;
    r.material = material;
    r.rpm = 560.0;  // between the 450 and 600 rpm rows: quantile cells
    r.wind_x_m_s = 3.0;
    Prediction a, b;
    ASSERT_EQ(read.predict(r, a), PredictStatus::kOk);
    ASSERT_EQ(derived.predict(r, b), PredictStatus::kOk);
    EXPECT_EQ(a.working_width_to_and_fro_m, b.working_width_to_and_fro_m) << material;
    EXPECT_EQ(a.throw_width_m, b.throw_width_m) << material;
    ASSERT_EQ(a.tray_mass_fraction.size(), b.tray_mass_fraction.size());
    for (std::size_t t = 0; t < a.tray_mass_fraction.size(); ++t) {
      ASSERT_EQ(a.tray_mass_fraction[t], b.tray_mass_fraction[t]) << material << " tray " << t;
    }
  }
}

}  // namespace spread::predict
