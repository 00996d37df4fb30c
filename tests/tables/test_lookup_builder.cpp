// lookup_builder's sweep on the bundled default scene: deterministic, resumable, explicit about DEM.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <random>
#include <sstream>
#include <thread>

#include "libspread/io/scene/scene.hpp"
#include "libspread/io/tables/table_reader.hpp"
#include "libspread/io/tables/table_writer.hpp"
#include "lookup_builder/run_source.hpp"
#include "lookup_builder/table_build.hpp"
#include "tests/support/temp_path.hpp"
#include "tests/tables/table_fixtures.hpp"

extern char** environ;

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
    EXPECT_EQ(ra.software_version, rb.software_version);
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
  const std::vector<char> built = spread::testing::file_bytes(file.path());
  const BuildSummary again = build_tables(scene, options);
  EXPECT_EQ(again.runs_written, 0);
  EXPECT_EQ(spread::testing::file_bytes(file.path()), built) << "a rerun with nothing to do changed the file";
  EXPECT_FALSE(std::filesystem::exists(file.path() + ".building"));
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

// Every build stores each material's landing data (the predictor's grid and cells) beside the rows; a
// table without it (written before it existed) gets it on the next run, and is then left as it is.
TEST(LookupBuilder, LandingDataIsStoredAndAddedToATableWithout) {
  const scene::Scene scene = default_scene({"sweep.samples_per_run=32"});
  TempPath file("landing");
  BuildOptions options;
  options.output_path = file.path();
  build_tables(scene, options);
  ASSERT_EQ(tables::read_table_file(file.path()).landing_data.size(), 3u);
  spread::testing::raw_exec(file.path(), "DROP TABLE landing_data; VACUUM");
  ASSERT_TRUE(tables::read_table_file(file.path()).landing_data.empty());
  EXPECT_EQ(build_tables(scene, options).runs_written, 0);
  const tables::TableContents added = tables::read_table_file(file.path());
  ASSERT_EQ(added.landing_data.size(), 3u);
  for (const tables::LandingData& landing : added.landing_data) EXPECT_FALSE(landing.data.empty()) << landing.material;
  const std::vector<char> built = spread::testing::file_bytes(file.path());
  build_tables(scene, options);
  EXPECT_EQ(spread::testing::file_bytes(file.path()), built) << "a rerun with nothing to do changed the file";
}

// Every table a build leaves lists its runs with the list's checksum; a legacy table (its runs without a
// checked list), which readers refuse unless they accept legacy files, is listed by the next run of the
// builder even when no run is left to compute, and is then left as it is.
TEST(LookupBuilder, ALegacyTableIsListedByTheNextBuild) {
  const scene::Scene scene = default_scene({"sweep.samples_per_run=32"});
  TempPath file("legacy");
  BuildOptions options;
  options.output_path = file.path();
  build_tables(scene, options);
  ASSERT_TRUE(tables::read_table_file(file.path()).runs_listed);
  spread::testing::raw_exec(file.path(), "DELETE FROM meta WHERE key IN ('runs_manifest', 'runs_manifest_checksum')");
  try {
    tables::read_table_file(file.path());
    ADD_FAILURE() << "a table without a list of its runs was read";
  } catch (const tables::TableError& e) {
    EXPECT_EQ(e.kind(), tables::TableErrorKind::kWrongVersion) << e.what();
    EXPECT_NE(std::string(e.what()).find("rebuild it with lookup_builder"), std::string::npos) << e.what();
  }
  tables::ReadOptions legacy;
  legacy.legacy_files = true;
  EXPECT_FALSE(tables::read_table_file(file.path(), nullptr, legacy).runs_listed);
  EXPECT_EQ(build_tables(scene, options).runs_written, 0);
  EXPECT_TRUE(tables::read_table_file(file.path()).runs_listed);
  const std::vector<char> listed = spread::testing::file_bytes(file.path());
  build_tables(scene, options);
  EXPECT_EQ(spread::testing::file_bytes(file.path()), listed) << "a rerun with nothing to do changed the file";
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


scene::Scene scene_file(const std::string& name, std::vector<std::string> overrides = {}) {
  overrides.insert(overrides.begin(), "sweep.samples_per_run=32");
  return scene::load_scene_file(std::string(SPREAD_SOURCE_DIR) + "/scenes/" + name, overrides);
}

// The message of the BuildConflictError a build throws ("" when it does not throw one).
std::string conflict_of(const scene::Scene& scene, const std::string& path) {
  BuildOptions options;
  options.output_path = path;
  try {
    build_tables(scene, options);
  } catch (const BuildConflictError& e) {
    return e.what();
  }
  return {};
}

TEST(LookupBuilderConflicts, AnotherMachineIsRefusedAndTheFileIsUntouched) {
  TempPath file("case1.sqlite");
  BuildOptions options;
  options.output_path = file.path();
  build_tables(scene_file("case1.toml"), options);
  const std::vector<char> before = spread::testing::file_bytes(file.path());
  const std::string problem = conflict_of(scene_file("case2.toml"), file.path());
  EXPECT_NE(problem.find("machine.disc_radius_m: file 0.29, scene 0.1524"), std::string::npos) << problem;
  EXPECT_NE(problem.find("--rebuild"), std::string::npos) << problem;
  EXPECT_EQ(spread::testing::file_bytes(file.path()), before);
}

TEST(LookupBuilderConflicts, AChangedMaterialOrSourceIsRefused) {
  TempPath file("changed.sqlite");
  BuildOptions options;
  options.output_path = file.path();
  build_tables(default_scene({"sweep.samples_per_run=32"}), options);
  const std::vector<char> before = spread::testing::file_bytes(file.path());
  const std::string friction = conflict_of(default_scene({"sweep.samples_per_run=32", "materials.0.friction_wall=0.55"}),
                                           file.path());
  EXPECT_NE(friction.find(".friction_wall: file"), std::string::npos) << friction;
  const std::string budget = conflict_of(default_scene({"sweep.samples_per_run=33"}), file.path());
  EXPECT_NE(budget.find("built from other inputs"), std::string::npos) << budget;
  const std::string source = conflict_of(default_scene({"sweep.samples_per_run=32", "sweep.source=\"dem\""}), file.path());
  EXPECT_NE(source.find("source analytic in the file, dem in the scene"), std::string::npos) << source;
  EXPECT_EQ(spread::testing::file_bytes(file.path()), before);
  // The same inputs with other comments, another rpm list or thread count are not a conflict.
  EXPECT_EQ(conflict_of(default_scene({"sweep.samples_per_run=32", "numerics.threads=1", "sweep.rpm=[450.0]"}),
                        file.path()),
            "");
}

TEST(LookupBuilderConflicts, RebuildReplacesTheTableOnlyWhenTheNewOneIsComplete) {
  TempPath file("rebuilt.sqlite");
  BuildOptions options;
  options.output_path = file.path();
  build_tables(scene_file("case1.toml"), options);
  options.rebuild = true;
  const scene::Scene case2 = scene_file("case2.toml");
  const BuildSummary summary = build_tables(case2, options);
  EXPECT_EQ(summary.runs_written, static_cast<int>(case2.sweep_materials().size() * case2.sweep_rpms().size()));
  const tables::TableContents table = tables::read_table_file(file.path());
  EXPECT_DOUBLE_EQ(table.machine.disc_radius_m, case2.machine.disc_radius_m);
  EXPECT_EQ(table.runs.size(), case2.sweep_materials().size() * case2.sweep_rpms().size());  // no case1 rows left
  for (const tables::Run& run : table.runs) EXPECT_EQ(run.inputs_hash, case2.run_inputs_hash(*case2.find_material(run.material), run.rpm));
  EXPECT_FALSE(std::filesystem::exists(file.path() + ".building"));
}

TEST(LookupBuilderConflicts, ASecondBuilderIsRefusedBeforeItComputes) {
  TempPath file("busy.sqlite");
  const scene::Scene scene = default_scene({"sweep.samples_per_run=32"});
  tables::TableWriter holder(file.path());  // another writer holds the file
  BuildOptions options;
  options.output_path = file.path();
  try {
    build_tables(scene, options);
    FAIL() << "the build ran beside another writer";
  } catch (const tables::TableBusyError& e) {
    EXPECT_NE(std::string(e.what()).find("another writer (pid "), std::string::npos) << e.what();
  }
}

TEST(LookupBuilderConflicts, ARunAlreadyWrittenIsSkippedNotFatal) {
  // The same run handed to the writer twice (a run another process finished meanwhile looks the same
  // to it): the second is counted as skipped and the build completes.
  TempPath file("twice.sqlite");
  const scene::Scene scene = default_scene({"sweep.samples_per_run=32", "sweep.rpm=[600.0]",
                                            "sweep.materials=[\"Urea\"]"});
  BuildOptions options;
  options.output_path = file.path();
  SweepWriter writer(scene, options);
  ASSERT_EQ(writer.pending().size(), 1u);
  const SweepJob& job = writer.pending().front();
  const std::vector<tables::Run> runs{analytic_run(scene, *job.material, job.rpm)};
  writer.finished(job, runs, RunCost{});
  EXPECT_NO_THROW(writer.finished(job, runs, RunCost{}));
  const BuildSummary summary = writer.finish();
  EXPECT_EQ(summary.runs_written, 1);
  EXPECT_EQ(summary.runs_skipped, 1);
}

TEST(LookupBuilderProvenance, RunsRecordTheSourceRevision) {
  TempPath file("revision.sqlite");
  const scene::Scene scene = default_scene({"sweep.samples_per_run=32", "sweep.rpm=[600.0]"});
  BuildOptions options;
  options.output_path = file.path();
  build_tables(scene, options);
  for (const tables::Run& run : tables::read_table_file(file.path()).runs) {
    const std::string prefix = std::string(SPREAD_VERSION_STRING) + "+";
    ASSERT_EQ(run.software_version.rfind(prefix, 0), 0u) << run.software_version;
    EXPECT_GT(run.software_version.size(), prefix.size()) << run.software_version;  // a revision or "unknown"
    EXPECT_EQ(run.inputs_hash, scene.run_inputs_hash(*scene.find_material(run.material), run.rpm));
  }
}

TEST(SceneBounds, AbsurdValuesAndAMissingDiscFileAreRefusedAtLoad) {
  const std::pair<const char*, const char*> cases[] = {
      {"sweep.rpm=[1e300]", "sweep.rpm[0]: must be <= 10000"},
      {"machine.rpm=20000", "machine.rpm: must be <= 10000"},
      {"materials.0.density_kg_m3=1e300", "materials[0].density_kg_m3: must be <= 25000"},
      {"materials.0.diameter_mean_m=2.0", "materials[0].diameter_mean_m: must be <= 0.1"},
      {"machine.disc_height_m=150", "machine.disc_height_m: must be <= 100"}};
  for (const auto& [bad, message] : cases) {
    try {
      default_scene({bad});
      ADD_FAILURE() << bad << " accepted";
    } catch (const scene::SceneError& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    }
  }
  // A disc STL that does not exist is found when the scene is read, whatever the launch source.
  try {
    default_scene({"machine.disc_model=\"stl\"", "machine.stl_path=\"no-such-disc.stl\""});
    ADD_FAILURE() << "a missing stl_path was accepted";
  } catch (const scene::SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("machine.stl_path"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("no such file"), std::string::npos) << e.what();
  }
}

// lookup_builder killed (SIGKILL) at a random moment of a --rebuild, again and again: the table it
// replaces always opens at once, whole (every run), without a journal to roll back — the build writes a
// staging file and renames it into place — and a build after the kills completes and leaves no staging
// file. The kill times are fractions of the first, complete build as timed here (about 0.3 s in the
// release build, 0.9 s under the sanitizers, its staging file after 12 and 50 ms; slower still on a
// loaded machine), so that the kills land in the same phases everywhere: every other kill anywhere from
// the spawn to past the end, the others once the staging file exists (one left by an interrupted build
// exists from the start), short of the end. The fractions are seeded; the assertions do not depend on
// where the kills land.
void kill_builds_at_random(int kills) {
  using Clock = std::chrono::steady_clock;
  TempPath table("killed_again.sqlite");
  const std::string staging = table.path() + ".building";
  const std::string scene_path = std::string(SPREAD_SOURCE_DIR) + "/scenes/default.toml";
  std::vector<std::string> args = {LOOKUP_BUILDER_EXE, scene_path, "--output", table.path(), "--rebuild",
                                   "--set", "sweep.source=\"analytic\"", "--set", "sweep.samples_per_run=2000",
                                   "--set", "sweep.rpm=[450, 500, 550, 600, 650, 700, 750]"};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t quiet;  // the builder's progress lines to /dev/null
  posix_spawn_file_actions_init(&quiet);
  posix_spawn_file_actions_addopen(&quiet, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&quiet, 2, "/dev/null", O_WRONLY, 0);
  const auto spawn = [&] {
    pid_t pid = 0;
    EXPECT_EQ(posix_spawn(&pid, LOOKUP_BUILDER_EXE, &quiet, nullptr, argv.data(), environ), 0);
    return pid;
  };
  // Polls until the staging file exists or the builder has exited; returns whether it exited.
  const auto wait_for_staging = [&](pid_t pid) {
    int status = 0;
    while (!std::filesystem::exists(staging)) {
      if (waitpid(pid, &status, WNOHANG) == pid) return true;
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
    return false;
  };
  // The first table, complete, timed: when the staging file appeared and when the builder exited.
  const Clock::time_point start = Clock::now();
  pid_t pid = spawn();
  ASSERT_GT(pid, 0);
  ASSERT_FALSE(wait_for_staging(pid)) << "the builder exited before writing its staging file";
  const double staging_s = std::chrono::duration<double>(Clock::now() - start).count();
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "the first build failed";
  const double build_s = std::chrono::duration<double>(Clock::now() - start).count();
  const std::size_t runs = tables::read_table_file(table.path()).runs.size();
  ASSERT_EQ(runs, 21u);
  std::mt19937 random(1);
  std::uniform_real_distribution<double> fraction(0.0, 1.0);
  int interrupted = 0;  // kills that landed inside a build (its staging file left behind)
  for (int k = 0; k < kills; ++k) {
    pid = spawn();
    ASSERT_GT(pid, 0);
    bool exited = false;
    if (k % 2 == 0) {  // anywhere: during start-up, the writing, or after the builder has finished
      std::this_thread::sleep_for(std::chrono::duration<double>(1.2 * build_s * fraction(random)));
    } else {  // inside the writing, short of its end
      exited = wait_for_staging(pid);
      std::this_thread::sleep_for(std::chrono::duration<double>(0.8 * (build_s - staging_s) * fraction(random)));
    }
    if (!exited) {
      kill(pid, SIGKILL);
      ASSERT_EQ(waitpid(pid, &status, 0), pid);
    }
    if (std::filesystem::exists(staging)) ++interrupted;
    EXPECT_FALSE(std::filesystem::exists(table.path() + "-journal")) << "kill " << k;
    try {
      EXPECT_EQ(tables::read_table_file(table.path()).runs.size(), runs) << "kill " << k;
    } catch (const tables::TableError& e) {
      ADD_FAILURE() << "kill " << k << ": the table does not open: " << e.what();
    }
  }
  EXPECT_GT(interrupted, 0) << "no kill landed inside a build (the first build: staging file after "
                            << staging_s << " s, done after " << build_s << " s)";
  pid = spawn();
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  posix_spawn_file_actions_destroy(&quiet);
  EXPECT_EQ(tables::read_table_file(table.path()).runs.size(), runs);
  EXPECT_FALSE(std::filesystem::exists(staging));
}

TEST(LookupBuilderKills, TenRandomKillsLeaveTheTableWhole) { kill_builds_at_random(10); }

// A fresh build (no table at its path yet) killed (SIGKILL) at a random moment, again and again: the path
// holds nothing until the build's first complete table takes it by rename — never an empty or partial
// file, which readers would refuse ("empty file") and a later build would have to judge. Each kill lands
// anywhere from the spawn to past the end of a build as timed here; the assertions do not depend on where.
TEST(LookupBuilderKills, KilledFreshBuildsLeaveNoFileAtTheTablesPath) {
  using Clock = std::chrono::steady_clock;
  TempPath table("killed_fresh.sqlite");
  const std::string staging = table.path() + ".building";
  const std::string scene_path = std::string(SPREAD_SOURCE_DIR) + "/scenes/default.toml";
  std::vector<std::string> args = {LOOKUP_BUILDER_EXE, scene_path, "--output", table.path(),
                                   "--set", "sweep.source=\"analytic\"", "--set", "sweep.samples_per_run=2000"};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t quiet;
  posix_spawn_file_actions_init(&quiet);
  posix_spawn_file_actions_addopen(&quiet, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&quiet, 2, "/dev/null", O_WRONLY, 0);
  const auto fresh_build = [&] {
    std::filesystem::remove(table.path());
    std::filesystem::remove(staging);
    pid_t pid = 0;
    EXPECT_EQ(posix_spawn(&pid, LOOKUP_BUILDER_EXE, &quiet, nullptr, argv.data(), environ), 0);
    return pid;
  };
  const Clock::time_point start = Clock::now();
  pid_t pid = fresh_build();
  ASSERT_GT(pid, 0);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "the first build failed";
  const double build_s = std::chrono::duration<double>(Clock::now() - start).count();
  const std::size_t runs = tables::read_table_file(table.path()).runs.size();
  ASSERT_GT(runs, 0u);
  std::mt19937 random(2);
  std::uniform_real_distribution<double> fraction(0.0, 1.0);
  int absent = 0, whole = 0;
  for (int k = 0; k < 30; ++k) {
    pid = fresh_build();
    ASSERT_GT(pid, 0);
    std::this_thread::sleep_for(std::chrono::duration<double>(1.1 * build_s * fraction(random)));
    kill(pid, SIGKILL);
    ASSERT_EQ(waitpid(pid, &status, 0), pid);
    if (!std::filesystem::exists(table.path())) {
      ++absent;
      continue;
    }
    EXPECT_GT(std::filesystem::file_size(table.path()), 0u) << "kill " << k << ": an empty file at the table's path";
    try {
      EXPECT_EQ(tables::read_table_file(table.path()).runs.size(), runs) << "kill " << k;
      ++whole;
    } catch (const tables::TableError& e) {
      ADD_FAILURE() << "kill " << k << ": a file at the table's path that does not open: " << e.what();
    }
  }
  posix_spawn_file_actions_destroy(&quiet);
  std::filesystem::remove(staging);
  EXPECT_GT(absent, 0) << "no kill landed before the table was complete (a build takes " << build_s << " s)";
  RecordProperty("kills_before_the_table", absent);
  RecordProperty("kills_after_it", whole);
}
TEST(LookupBuilderKills, HundredRandomKillsLeaveTheTableWhole) { kill_builds_at_random(100); }

}  // namespace
}  // namespace spread::lookup
