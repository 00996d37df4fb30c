// The JSON contracts of `spread simulate` and `spread verify cone|vane|impact`: the real CLI is run, its
// stdout parsed as JSON, and every key listed below checked for presence and type. One ctest per command
// (tests/dem/CMakeLists.txt); the commands use short settings.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <sys/wait.h>

using nlohmann::json;

namespace {

// Runs `spread <args>`, returns stdout parsed as JSON; fails the test on a non-zero exit or bad JSON.
json run_cli(const std::string& args) {
  const std::string command = std::string("'") + SPREAD_CLI + "' " + args;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) {
    ADD_FAILURE() << "cannot run " << command;
    return json();
  }
  std::string out;
  std::array<char, 4096> buffer{};
  std::size_t n = 0;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) out.append(buffer.data(), n);
  const int status = ::pclose(pipe);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << command << " exited with status " << status;
  try {
    return json::parse(out);
  } catch (const json::exception& e) {
    ADD_FAILURE() << command << ": stdout is not JSON (" << e.what() << "):\n" << out;
    return json();
  }
}

void expect_number(const json& j, const std::string& key, const std::string& where) {
  ASSERT_TRUE(j.contains(key)) << where << ": missing key '" << key << "'";
  EXPECT_TRUE(j.at(key).is_number()) << where << ": '" << key << "' is not a number: " << j.at(key).dump();
}

}  // namespace

TEST(DemCli, SimulateJsonKeys) {
  // Case 1 for 0.035 s with the inlet near the rim and a 5 mm drop, so a vane sweeps granules off
  // within the short run (~55 launched); ξ 5 mm keeps it short; no files written.
  const json out = run_cli(std::string("simulate '") + SPREAD_SOURCE_DIR +
                           "/scenes/case1.toml' --set numerics.duration_s=0.035 --set inlet.offset_m=0.25 "
                           "--set inlet.drop_height_m=0.005 --set machine.mesh_size_m=0.005 --set numerics.threads=1 "
                           "--set outputs.launch_csv=false --set outputs.pattern_png=false --json");
  ASSERT_TRUE(out.is_object());
  expect_number(out, "launched", "simulate");
  EXPECT_GT(out.value("launched", 0), 0) << "nothing launched: the launch statistics would be empty";
  ASSERT_TRUE(out.contains("launch") && out["launch"].is_object());
  for (const char* k : {"speed_mean", "speed_sd", "angle_from_tangent_deg_mean", "elevation_deg_mean"})
    expect_number(out["launch"], k, "simulate.launch");
  ASSERT_TRUE(out.contains("sector_mass_fraction") && out["sector_mass_fraction"].is_array());
  ASSERT_EQ(out["sector_mass_fraction"].size(), 12u);
  double total = 0.0;
  for (const auto& f : out["sector_mass_fraction"]) {
    ASSERT_TRUE(f.is_number());
    total += f.get<double>();
  }
  EXPECT_NEAR(total, 1.0, 1e-9);
  for (const char* k : {"mean_radius_m", "radial_width_m", "particle_steps", "wall_time_s"}) expect_number(out, k, "simulate");
  ASSERT_TRUE(out.contains("effects"));
  EXPECT_TRUE(out["effects"].is_string() || out["effects"].is_array()) << out["effects"].dump();
  ASSERT_TRUE(out.contains("module_time_s") && out["module_time_s"].is_object());
  EXPECT_FALSE(out["module_time_s"].empty());
  for (const auto& [name, seconds] : out["module_time_s"].items()) EXPECT_TRUE(seconds.is_number()) << name;
}

TEST(DemCli, VerifyConeJsonKeys) {
  // The analytic cone and one coarse mesh: the full sweep (ξ down to 0.01) is the long test's job.
  const json out = run_cli("verify cone --mesh-sizes 0 0.1 --json");
  ASSERT_TRUE(out.contains("results") && out["results"].is_array());
  ASSERT_EQ(out["results"].size(), 10u);  // five μ × two surfaces
  for (const auto& row : out["results"])
    for (const char* k : {"mu", "speed", "elevation_deg", "angle_from_tangent_deg", "t_exit", "speed_ref",
                          "elevation_deg_ref", "angle_from_tangent_deg_ref", "t_exit_ref", "speed_rel_error"})
      expect_number(row, k, "verify cone");
}

TEST(DemCli, VerifyVaneJsonKeys) {
  const json out = run_cli("verify vane --json");
  ASSERT_TRUE(out.contains("results") && out["results"].is_array());
  ASSERT_EQ(out["results"].size(), 6u);  // 500 and 900 rpm × μ 0, 0.3, 0.4
  for (const auto& row : out["results"])
    for (const char* k : {"rpm", "mu", "v_radial", "v_tangential", "v_radial_ref", "v_tangential_ref",
                          "v_radial_rel_error", "v_tangential_rel_error"})
      expect_number(row, k, "verify vane");
}

TEST(DemCli, VerifyImpactJsonKeys) {
  const json out = run_cli("verify impact --json");
  ASSERT_TRUE(out.contains("results") && out["results"].is_array());
  ASSERT_EQ(out["results"].size(), 12u);  // two geometries × e 0.1 … 0.9 and 1
  for (const auto& row : out["results"]) {
    for (const char* k : {"e_requested", "e_measured", "t_contact", "t_contact_hertz", "t_contact_ref",
                          "t_contact_ref_rel_error", "energy_ratio"})
      expect_number(row, k, "verify impact");
    const bool sphere_sphere = row.value("geometry", "") == "sphere_sphere";
    // The momentum balance means something only between two spheres (a plane takes any momentum).
    EXPECT_EQ(row.contains("momentum_rel_error"), sphere_sphere) << row.dump();
    if (row.value("e_requested", 0.0) < 1.0) {
      EXPECT_LT(std::abs(row.value("t_contact_ref_rel_error", 1.0)), 0.02) << row.dump();
    }
  }
}
