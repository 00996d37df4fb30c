// lookup_builder with the DEM source: runs are deterministic and normalised as the table
// format says; a build killed mid-run (SIGKILL) leaves the table as it was and resumes to the same content
// as an uninterrupted build; threads give the same file as one process; damaged, truncated and foreign files are refused and left
// byte-identical; finished runs survive the MPI message round trip.
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <nlohmann/json.hpp>
#include <numbers>
#include <thread>
#include <utility>
#include <vector>

#include "libspread/io/scene/scene.hpp"
#include "libspread/io/tables/scene_hash.hpp"
#include "libspread/io/tables/table_reader.hpp"
#include "libspread/io/tables/table_writer.hpp"
#include "lookup_builder/dem_run.hpp"
#include "lookup_builder/run_message.hpp"
#include "lookup_builder/table_build.hpp"
#include "tests/support/temp_path.hpp"

extern char** environ;

namespace spread::lookup {
namespace {

using spread::testing::file_bytes;
using spread::testing::TempPath;
using spread::testing::write_bytes;

const std::string kTinyScene = std::string(SPREAD_SOURCE_DIR) + "/tests/tables/data/tiny_dem.toml";

scene::Scene tiny_scene(std::vector<std::string> overrides = {}) {
  overrides.insert(overrides.begin(), "sweep.materials=[\"Urea\", \"Kmag\"]");
  return scene::load_scene_file(kTinyScene, overrides);
}

// Same runs: (material, rpm), samples bit for bit, statistics, convergence and provenance — all but
// created_utc (the build date).
void expect_same_runs(const tables::TableContents& a, const tables::TableContents& b) {
  ASSERT_EQ(a.runs.size(), b.runs.size());
  for (std::size_t i = 0; i < a.runs.size(); ++i) {
    const tables::Run& ra = a.runs[i];
    const tables::Run& rb = b.runs[i];
    SCOPED_TRACE(ra.material + " @ " + std::to_string(ra.rpm));
    EXPECT_EQ(ra.material, rb.material);
    EXPECT_EQ(ra.rpm, rb.rpm);
    EXPECT_EQ(ra.source, rb.source);
    EXPECT_EQ(ra.scene_hash, rb.scene_hash);
    EXPECT_EQ(ra.scene_text, rb.scene_text);
    EXPECT_EQ(ra.effects, rb.effects);
    EXPECT_EQ(ra.dt_contact_s, rb.dt_contact_s);
    EXPECT_EQ(ra.particle_count, rb.particle_count);
    EXPECT_EQ(ra.stats_json, rb.stats_json);
    EXPECT_EQ(ra.convergence_json, rb.convergence_json);
    ASSERT_EQ(ra.samples.size(), rb.samples.size());
    EXPECT_EQ(std::memcmp(ra.samples.data(), rb.samples.data(), ra.samples.size() * sizeof(tables::LaunchSample)), 0);
  }
}

TEST(LookupDem, RunIsDeterministicNormalisedAndRecordsConvergence) {
  const scene::Scene scene = tiny_scene();
  const scene::Material& urea = *scene.find_material("Urea");
  const tables::Run a = dem_run(scene, urea, 650.0);
  const tables::Run b = dem_run(scene, urea, 650.0, DemRunOptions{2});  // thread count must not matter
  ASSERT_GT(a.samples.size(), 10u);
  ASSERT_EQ(a.samples.size(), b.samples.size());
  EXPECT_EQ(std::memcmp(a.samples.data(), b.samples.data(), a.samples.size() * sizeof(tables::LaunchSample)), 0);
  EXPECT_EQ(a.stats_json, b.stats_json);
  EXPECT_EQ(a.source, "dem");
  EXPECT_GT(a.dt_contact_s, 0.0);
  EXPECT_GE(a.particle_count, static_cast<std::int64_t>(a.samples.size()));
  EXPECT_EQ(a.effects, "particle_contact,wall_contact,rotation,drag,magnus,spin_decay");

  // Table frame: disc centre at the origin, rim at z = 0; launches at the collector (R = 0.29 m).
  // Velocities / ωR: most granules leave a radial vane with at least the rim speed tangentially; a few,
  // knocked up by other granules, leave over the vane top, slower and higher.
  const double radius_m = scene.machine.disc_radius_m;
  std::size_t vane_launches = 0;
  for (const tables::LaunchSample& s : a.samples) {
    const double r = std::hypot(s.x_m, s.y_m);
    EXPECT_GE(r, radius_m - 1e-6);
    EXPECT_LT(r, radius_m + 0.02);
    EXPECT_LT(std::abs(s.z_m), 0.2);
    const double speed = std::sqrt(s.vx_norm * s.vx_norm + s.vy_norm * s.vy_norm + s.vz_norm * s.vz_norm);
    EXPECT_LT(speed, 2.0);
    if (speed > 0.8 && std::abs(s.z_m) < 0.05) ++vane_launches;
    EXPECT_GT(s.t_s, 0.0f);
    EXPECT_GT(s.mass_kg, 0.0f);
  }
  EXPECT_GT(vane_launches, a.samples.size() * 8 / 10);
  const nlohmann::json history = nlohmann::json::parse(a.convergence_json);
  ASSERT_TRUE(history.is_array());
  ASSERT_EQ(history.size(), 3u);  // 0.15 s in batches of 0.05 s
  EXPECT_NEAR(history.back()["simulated_s"].get<double>(), 0.15, 1e-4);
  const nlohmann::json stats = nlohmann::json::parse(a.stats_json);
  EXPECT_EQ(stats["launched"].get<std::size_t>(), a.samples.size());
  EXPECT_DOUBLE_EQ(stats["mean_radius_m"].get<double>(), history.back()["mean_radius_m"].get<double>());
  EXPECT_GT(stats["mean_radius_m"].get<double>(), 1.0);
}

// Circular mean (rad) and its standard error of the angles atan2(y, x) of the launch samples, after
// turning them by `turn_rad` about the disc axis (Mardia & Jupp, Directional Statistics, §3.4: the standard
// error of the mean direction is sqrt((1 − mean cos 2(θ − μ)) / (2 n R̄²)), R̄ the mean resultant length).
struct Direction {
  double mean_rad = 0.0, se_rad = 0.0;
};
template <typename AngleOf>
Direction circular_mean(const std::vector<tables::LaunchSample>& samples, AngleOf angle_of) {
  double c = 0.0, s = 0.0;
  for (const auto& sample : samples) {
    c += std::cos(angle_of(sample));
    s += std::sin(angle_of(sample));
  }
  const double n = static_cast<double>(samples.size());
  Direction d;
  d.mean_rad = std::atan2(s, c);
  const double r_bar = std::hypot(c, s) / n;
  double c2 = 0.0;
  for (const auto& sample : samples) c2 += std::cos(2.0 * (angle_of(sample) - d.mean_rad));
  d.se_rad = std::sqrt(std::max(0.0, 1.0 - c2 / n) / (2.0 * n * r_bar * r_bar));
  return d;
}

// A disc that is the same all round, fed continuously, has no phase of its own in the time average: turning
// the feed (the drop point) by Δ about the disc axis turns the whole fan of launches by Δ. The claim the
// predictor's drop-point setting rests on, checked against a DEM run with the inlet turned: the launch
// positions' and velocities' mean directions of the turned run equal the first run's plus Δ within
// 4 combined standard errors, and differ from the first run's unturned (the check has power).
TEST(LookupDem, TurningTheFeedTurnsTheLaunchFan) {
  constexpr double kTurn_rad = 0.6;
  const std::vector<std::string> more{"sweep.samples_per_run=400", "numerics.duration_s=0.6",
                                      "sweep.convergence_tolerance=1e-6"};
  const scene::Scene base = tiny_scene(more);
  std::vector<std::string> turned_overrides = more;
  turned_overrides.push_back("inlet.angle_rad=" + std::to_string(base.inlet.angle_rad + kTurn_rad));
  const scene::Scene turned = tiny_scene(turned_overrides);
  const tables::Run a = dem_run(base, *base.find_material("Urea"), 650.0);
  const tables::Run b = dem_run(turned, *turned.find_material("Urea"), 650.0);
  ASSERT_GE(a.samples.size(), 300u);
  ASSERT_GE(b.samples.size(), 300u);
  const auto position = [](const tables::LaunchSample& s) { return std::atan2(double{s.y_m}, double{s.x_m}); };
  const auto velocity = [](const tables::LaunchSample& s) { return std::atan2(double{s.vy_norm}, double{s.vx_norm}); };
  for (const auto& [what, angle] : {std::pair{"position", +position}, std::pair{"velocity", +velocity}}) {
    const Direction da = circular_mean(a.samples, angle), db = circular_mean(b.samples, angle);
    const double combined_se = std::hypot(da.se_rad, db.se_rad);
    const double shift = std::remainder(db.mean_rad - da.mean_rad, 2.0 * std::numbers::pi);
    std::printf("launch %s direction: %.4f rad, turned feed %.4f rad: shift %.4f rad (feed turned %.4f), SE %.4f\n",
                what, da.mean_rad, db.mean_rad, shift, kTurn_rad, combined_se);
    EXPECT_NEAR(shift, kTurn_rad, 4.0 * combined_se) << what;
    EXPECT_GT(std::abs(shift), 10.0 * combined_se) << what << ": the turn must be detectable";
  }
  // What the turn leaves alone: the launch speed and the radius (mean within 4 combined SE).
  const auto speed_stats = [](const std::vector<tables::LaunchSample>& samples) {
    double sum = 0.0, sum2 = 0.0;
    for (const auto& s : samples) {
      const double v = std::hypot(double{s.vx_norm}, double{s.vy_norm}, double{s.vz_norm});
      sum += v;
      sum2 += v * v;
    }
    const double n = static_cast<double>(samples.size()), mean = sum / n;
    return std::pair{mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n)};
  };
  const auto [va, va_se] = speed_stats(a.samples);
  const auto [vb, vb_se] = speed_stats(b.samples);
  EXPECT_NEAR(vb, va, 4.0 * std::hypot(va_se, vb_se));
}

TEST(LookupDem, StopsAtTheParticleBudgetAndOnConvergence) {
  const scene::Scene budget = tiny_scene({"sweep.particle_budget=15"});
  const tables::Run a = dem_run(budget, *budget.find_material("Urea"), 650.0);
  EXPECT_EQ(a.samples.size(), 15u);
  EXPECT_EQ(nlohmann::json::parse(a.stats_json)["stop"], "particle_budget");

  // A huge tolerance: converged at the first batch with a previous one to compare with and enough launches.
  const scene::Scene loose = tiny_scene({"sweep.convergence_tolerance=10", "numerics.duration_s=1"});
  const tables::Run b = dem_run(loose, *loose.find_material("Urea"), 650.0);
  const nlohmann::json stats = nlohmann::json::parse(b.stats_json);
  EXPECT_EQ(stats["stop"], "converged");
  EXPECT_LT(stats["simulated_s"].get<double>(), 0.5);
}

// sweep.working_width_ci_m: once R̄ and ξ have converged the run still waits until the working width
// predicted from its launches is known that well. Unreachable: the run goes to its time budget, and every
// check is in the convergence history. Loose: it stops where it stops without the rule, bit for bit.
TEST(LookupDem, WaitsForTheWorkingWidthPrecisionAsked) {
  const std::vector<std::string> loose = {"sweep.convergence_tolerance=10", "numerics.duration_s=0.6"};
  auto with = [&](const char* ci) {
    std::vector<std::string> overrides = loose;
    overrides.push_back(ci);
    const scene::Scene scene = tiny_scene(overrides);
    return dem_run(scene, *scene.find_material("Urea"), 650.0);
  };
  const tables::Run strict = with("sweep.working_width_ci_m=0.001");
  const nlohmann::json strict_stats = nlohmann::json::parse(strict.stats_json);
  EXPECT_EQ(strict_stats["stop"], "time_budget");
  EXPECT_EQ(strict_stats["working_width_ci_target_m"], 0.001);
  int checks = 0;
  for (const auto& point : nlohmann::json::parse(strict.convergence_json)) {
    if (!point.contains("working_width_ci_m")) continue;
    ++checks;
    EXPECT_GT(point["working_width_ci_m"].get<double>(), 0.001);
  }
  EXPECT_GE(checks, 2);

  const tables::Run lax = with("sweep.working_width_ci_m=100");
  const tables::Run off = with("sweep.working_width_ci_m=0");
  EXPECT_EQ(nlohmann::json::parse(lax.stats_json)["stop"], "converged");
  ASSERT_EQ(lax.samples.size(), off.samples.size());
  EXPECT_LT(lax.samples.size(), strict.samples.size());
  EXPECT_EQ(std::memcmp(lax.samples.data(), off.samples.data(), lax.samples.size() * sizeof(tables::LaunchSample)), 0);
}

TEST(LookupDem, JobsOnThreadsGiveTheSameFileAsOneProcess) {
  const scene::Scene scene = tiny_scene();
  TempPath one("dem_jobs1"), two("dem_jobs2");
  BuildOptions options;
  options.output_path = one.path();
  EXPECT_EQ(build_tables(scene, options).runs_written, 4);
  options.output_path = two.path();
  options.jobs = 2;
  EXPECT_EQ(build_tables(scene, options).runs_written, 4);
  expect_same_runs(tables::read_table_file(one.path()), tables::read_table_file(two.path()));
}

int runs_in(const std::string& path) {
  try {
    return static_cast<int>(tables::read_table_file(path).runs.size());
  } catch (const tables::TableError&) {
    return 0;  // not created yet, empty, or locked by the writer at this instant
  }
}

// A build writes into TABLE.building and renames it over the table when done: killed at any moment, the
// table is the previous complete one, which readers open at once (no journal to roll back), and the next
// build resumes from the staging file's finished runs.
TEST(LookupDem, BuildKilledMidRunLeavesTheTableWholeAndResumesToTheSameContent) {
  // Slower runs than the other tests so the kill lands inside a run: rows of ~1 s.
  const std::vector<std::string> first = {"sweep.materials=[\"Urea\"]", "sweep.rpm=[500]", "numerics.duration_s=0.3"};
  const std::vector<std::string> overrides = {"sweep.materials=[\"Urea\"]", "sweep.rpm=[500, 550, 600, 650]",
                                              "numerics.duration_s=0.3"};
  TempPath killed("dem_killed"), reference("dem_reference");
  const std::string staging = killed.path() + ".building";
  BuildOptions options;
  options.output_path = killed.path();
  ASSERT_EQ(build_tables(scene::load_scene_file(kTinyScene, first), options).runs_written, 1);
  const std::vector<char> complete = file_bytes(killed.path());
  EXPECT_FALSE(std::filesystem::exists(staging));

  std::vector<std::string> args = {LOOKUP_BUILDER_EXE, kTinyScene, "--output", killed.path()};
  for (const std::string& o : overrides) {
    args.push_back("--set");
    args.push_back(o);
  }
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  ASSERT_EQ(posix_spawn(&pid, LOOKUP_BUILDER_EXE, nullptr, nullptr, argv.data(), environ), 0);
  // Kill as soon as a new run is committed in the staging file: the next is then in progress.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  int status = 0;
  bool exited = false;
  while (runs_in(staging) < 2 && std::chrono::steady_clock::now() < deadline) {
    if (waitpid(pid, &status, WNOHANG) == pid) {
      exited = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_FALSE(exited) << "the build finished before it could be killed";
  ASSERT_EQ(kill(pid, SIGKILL), 0);
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFSIGNALED(status));
  // The table is the last complete one, byte for byte, and opens at once.
  EXPECT_EQ(file_bytes(killed.path()), complete);
  EXPECT_FALSE(std::filesystem::exists(killed.path() + "-journal"));
  EXPECT_EQ(tables::read_table_file(killed.path()).runs.size(), 1u);
  const int survived = runs_in(staging);
  EXPECT_GE(survived, 2);
  EXPECT_LT(survived, 4) << "kill came too late to interrupt a run";

  // Resume: only the missing runs are made.
  const scene::Scene scene = scene::load_scene_file(kTinyScene, overrides);
  const BuildSummary resumed = build_tables(scene, options);
  EXPECT_EQ(resumed.runs_skipped, survived);
  EXPECT_EQ(resumed.runs_written, 4 - survived);
  EXPECT_FALSE(std::filesystem::exists(staging));
  // A rerun skips everything and leaves the file byte-identical; --rebuild is needed to redo.
  const std::vector<char> built = file_bytes(killed.path());
  EXPECT_EQ(build_tables(scene, options).runs_written, 0);
  EXPECT_EQ(file_bytes(killed.path()), built);
  EXPECT_FALSE(std::filesystem::exists(staging));

  // The same two builds without a kill.
  options.output_path = reference.path();
  build_tables(scene::load_scene_file(kTinyScene, first), options);
  build_tables(scene, options);
  expect_same_runs(tables::read_table_file(killed.path()), tables::read_table_file(reference.path()));
}

TEST(LookupDem, DamagedTruncatedAndForeignFilesAreRefusedAndLeftAlone) {
  const scene::Scene scene = tiny_scene({"sweep.materials=[\"Kmag\"]", "sweep.rpm=[650]", "numerics.duration_s=0.1"});
  TempPath good("dem_good");
  BuildOptions options;
  options.output_path = good.path();
  build_tables(scene, options);
  const std::vector<char> valid = file_bytes(good.path());
  ASSERT_GT(valid.size(), 4096u * 3);

  struct Case {
    const char* name;
    std::vector<char> bytes;
    tables::TableErrorKind kind;
  };
  std::vector<char> truncated(valid.begin(), valid.begin() + static_cast<std::ptrdiff_t>(valid.size() / 2));
  std::vector<char> damaged = valid;
  for (std::size_t i = 4096 + 8; i < 4096 + 1000; ++i) damaged[i] = static_cast<char>(0xA5);  // page 2 garbled
  const std::string text = "[machine]\nname = \"not a table\"\n";
  std::vector<char> foreign(text.begin(), text.end());
  std::vector<Case> cases = {{"truncated", truncated, tables::TableErrorKind::kCorrupt},
                             {"damaged", damaged, tables::TableErrorKind::kCorrupt},
                             {"foreign", foreign, tables::TableErrorKind::kNotOurs}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    TempPath file(std::string("dem_") + c.name);
    write_bytes(file.path(), c.bytes);
    options.output_path = file.path();
    try {
      build_tables(scene, options);
      ADD_FAILURE() << "accepted a " << c.name << " file";
    } catch (const tables::TableError& e) {
      EXPECT_EQ(e.kind(), c.kind) << e.what();
      EXPECT_NE(std::string(e.what()).find(file.path()), std::string::npos) << e.what();
    }
    EXPECT_EQ(file_bytes(file.path()), c.bytes) << "the refused file was modified";
  }
}

TEST(LookupDem, ExtendsATableWhoseInputsSpellTheHertzLawHertzMindlin) {
  // Tables built before the law's rename hashed "numerics.contact_model = \"hertz_mindlin\"": the same law,
  // so --extend keeps their runs; any other difference in the inputs is still refused.
  const scene::Scene scene = tiny_scene({"sweep.materials=[\"Kmag\"]", "sweep.rpm=[650]", "numerics.duration_s=0.1"});
  const scene::Material& kmag = *scene.find_material("Kmag");
  std::string old_text = scene.run_inputs_text(kmag, 650.0);
  const std::string line = "numerics.contact_model = \"hertz_thornton\"\n";
  ASSERT_NE(old_text.find(line), std::string::npos) << old_text;
  old_text.replace(old_text.find(line), line.size(), "numerics.contact_model = \"hertz_mindlin\"\n");
  TempPath file("dem_old_spelling");
  BuildOptions options;
  options.output_path = file.path();
  build_tables(scene, options);
  auto rewrite_inputs_hash = [&](const std::string& hash) {
    tables::Run run = tables::read_table_file(file.path()).runs.at(0);
    run.inputs_hash = hash;
    tables::TableWriter(file.path()).write_run(run, true);
  };
  rewrite_inputs_hash(tables::fnv1a64_hex(old_text));
  const BuildSummary extended = build_tables(scene, options);
  EXPECT_EQ(extended.runs_skipped, 1);
  EXPECT_EQ(extended.runs_written, 0);
  EXPECT_EQ(tables::read_table_file(file.path()).runs.at(0).inputs_hash, tables::fnv1a64_hex(old_text));

  rewrite_inputs_hash(tables::fnv1a64_hex(old_text + "numerics.seed = 2\n"));
  try {
    build_tables(scene, options);
    ADD_FAILURE() << "a run from other inputs was kept";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("built from other inputs"), std::string::npos) << e.what();
  }
}

TEST(LookupDem, RunSurvivesTheMpiMessageRoundTrip) {
  const scene::Scene scene = tiny_scene({"numerics.duration_s=0.1"});
  const tables::Run run = dem_run(scene, *scene.find_material("Kmag"), 650.0);
  const std::vector<std::uint8_t> bytes = serialise_run(run);
  const tables::Run back = deserialise_run(bytes);
  EXPECT_EQ(back.material, run.material);
  EXPECT_EQ(back.rpm, run.rpm);
  EXPECT_EQ(back.source, run.source);
  EXPECT_EQ(back.scene_text, run.scene_text);
  EXPECT_EQ(back.scene_hash, run.scene_hash);
  EXPECT_EQ(back.effects, run.effects);
  EXPECT_EQ(back.dt_contact_s, run.dt_contact_s);
  EXPECT_EQ(back.dt_flight_s, run.dt_flight_s);
  EXPECT_EQ(back.particle_count, run.particle_count);
  EXPECT_EQ(back.software_version, run.software_version);
  EXPECT_EQ(back.created_utc, run.created_utc);
  EXPECT_EQ(back.stats_json, run.stats_json);
  EXPECT_EQ(back.convergence_json, run.convergence_json);
  ASSERT_EQ(back.samples.size(), run.samples.size());
  EXPECT_EQ(std::memcmp(back.samples.data(), run.samples.data(), run.samples.size() * sizeof(tables::LaunchSample)), 0);
  const std::vector<std::uint8_t> cut(bytes.begin(), bytes.end() - 3);
  EXPECT_THROW(deserialise_run(cut), std::invalid_argument);
}

}  // namespace
}  // namespace spread::lookup
