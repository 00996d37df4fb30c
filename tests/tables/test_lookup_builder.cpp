// lookup_builder's sweep on the bundled default scene: deterministic, resumable, explicit about DEM.
#include <gtest/gtest.h>

#include <cstring>
#include <sstream>

#include "libspread/scene/scene.hpp"
#include "libspread/tables/table_reader.hpp"
#include "lookup_builder/run_source.hpp"
#include "lookup_builder/table_build.hpp"
#include "tests/support/temp_path.hpp"

namespace spread::lookup {
namespace {

using spread::testing::TempPath;

// The bundled default scene with its sweep switched to the analytic source (the DEM source has its own
// tests in test_lookup_dem.cpp): the sweep logic is the same for both and the analytic runs are instant.
scene::Scene default_scene(std::vector<std::string> overrides = {}) {
  overrides.insert(overrides.begin(), {"sweep.source=\"analytic\"", "sweep.samples_per_run=512"});
  return scene::load_scene_file(std::string(SPREAD_SOURCE_DIR) + "/scenes/default.toml", overrides);
}

TEST(LookupBuilder, DefaultSceneTwiceGivesTheSameRuns) {
  const scene::Scene scene = default_scene();
  TempPath first("build1"), second("build2");
  BuildOptions options;
  options.output_path = first.path();
  const BuildSummary summary = build_tables(scene, options);
  EXPECT_EQ(summary.runs_written, static_cast<int>(scene.materials.size() * scene.sweep.rpm.size()));
  options.output_path = second.path();
  build_tables(scene, options);

  const tables::TableContents a = tables::read_table_file(first.path());
  const tables::TableContents b = tables::read_table_file(second.path());
  ASSERT_EQ(a.runs.size(), scene.materials.size() * scene.sweep.rpm.size());
  ASSERT_EQ(a.runs.size(), 9u);  // 3 materials x 3 rpm rows
  ASSERT_EQ(a.runs.size(), b.runs.size());
  EXPECT_EQ(a.machine.name, "case1-twin");
  EXPECT_EQ(a.materials.size(), 3u);
  for (std::size_t i = 0; i < a.runs.size(); ++i) {
    const tables::Run& ra = a.runs[i];
    const tables::Run& rb = b.runs[i];
    EXPECT_EQ(ra.material, rb.material);
    EXPECT_EQ(ra.rpm, rb.rpm);
    EXPECT_EQ(ra.source, "analytic");
    EXPECT_EQ(ra.scene_hash, scene.hash());
    EXPECT_EQ(ra.scene_hash, rb.scene_hash);
    EXPECT_EQ(ra.scene_text, scene.provenance_text());
    EXPECT_EQ(ra.stats_json, rb.stats_json);
    EXPECT_EQ(ra.software_version, SPREAD_VERSION_STRING);
    EXPECT_NE(ra.stats_json.find("speed_mean"), std::string::npos);
    ASSERT_EQ(ra.samples.size(), 512u);
    ASSERT_EQ(ra.samples.size(), rb.samples.size());
    EXPECT_EQ(std::memcmp(ra.samples.data(), rb.samples.data(), ra.samples.size() * sizeof(tables::LaunchSample)), 0)
        << ra.material << " @ " << ra.rpm;
  }
}

TEST(LookupBuilder, RerunSkipsFinishedRunsAndRebuildRedoesThem) {
  const scene::Scene scene = default_scene({"sweep.samples_per_run=32"});
  TempPath file("rerun");
  BuildOptions options;
  options.output_path = file.path();
  std::ostringstream progress;
  options.progress = &progress;
  const int runs = static_cast<int>(scene.materials.size() * scene.sweep.rpm.size());  // 3 x 3
  EXPECT_EQ(build_tables(scene, options).runs_written, runs);
  const BuildSummary again = build_tables(scene, options);
  EXPECT_EQ(again.runs_written, 0);
  EXPECT_EQ(again.runs_skipped, runs);
  EXPECT_NE(progress.str().find("skipped"), std::string::npos);
  // An extra rpm row is the only run made on the third pass.
  const scene::Scene more = default_scene({"sweep.samples_per_run=32", "sweep.rpm=[450.0, 500.0]"});
  const BuildSummary extended = build_tables(more, options);
  EXPECT_EQ(extended.runs_written, 3);
  EXPECT_EQ(extended.runs_skipped, 3);
  options.rebuild = true;
  EXPECT_EQ(build_tables(more, options).runs_written, 6);
  EXPECT_EQ(tables::read_table_file(file.path()).runs.size(), static_cast<std::size_t>(runs + 3));
}

TEST(LookupBuilder, DemSweepKeysAreValidatedByName) {
  // The DEM source itself is tested in test_lookup_dem.cpp; bad budgets are scene errors naming the key.
  for (const char* bad : {"sweep.batch_s=0", "sweep.convergence_tolerance=-1", "sweep.particle_budget=-5"}) {
    try {
      default_scene({"sweep.source=\"dem\"", bad});
      ADD_FAILURE() << bad << " accepted";
    } catch (const scene::SceneError& e) {
      const std::string key = std::string(bad).substr(0, std::string(bad).find('='));
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace spread::lookup
