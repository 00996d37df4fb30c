// Blends in a table (format version 3): `blend_components` written, read and checked (values, positions,
// checksums, the component rows present); a version-2 table still loads (no blends); lookup_builder builds
// a blend's rows from the mixed stream on the disc, each component's launches in its own row.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "libspread/io/scene/scene.hpp"
#include "libspread/io/tables/table_reader.hpp"
#include "libspread/io/tables/table_writer.hpp"
#include "lookup_builder/dem_run.hpp"
#include "lookup_builder/table_build.hpp"
#include "tests/support/temp_path.hpp"
#include "tests/tables/table_fixtures.hpp"

namespace spread::tables {
namespace {

using spread::testing::raw_exec;
using spread::testing::TempPath;

Blend two_component_blend() {
  return Blend{"B", {{"B / x", 0.6, 46.0, 0.0, 0.0}, {"B / y", 0.4, 18.0, 46.0, 0.0}}};
}

void write_blend_table(const std::string& path) {
  TableWriter writer(path);
  writer.write_machine(testing::sample_machine());
  writer.write_materials({testing::sample_material("B / x", 0.4), testing::sample_material("B / y", 0.6)});
  writer.write_run(testing::sample_run("B / x", 500.0, 16));
  writer.write_run(testing::sample_run("B / y", 500.0, 16));
  writer.write_blend(two_component_blend());
}

// The kind of the error reading the file gives; nullopt when it reads.
std::optional<ErrorKind> kind_of_reading(const std::string& path, std::string* message = nullptr) {
  try {
    read_table_file(path);
  } catch (const TableError& e) {
    if (message != nullptr) *message = e.what();
    return e.kind();
  }
  return std::nullopt;
}

TEST(BlendTable, WrittenReadAndChecked) {
  TempPath file("blend.sqlite");
  write_blend_table(file.path());
  const TableContents contents = read_table_file(file.path());
  ASSERT_EQ(contents.blends.size(), 1u);
  const Blend* blend = contents.find_blend("B");
  ASSERT_NE(blend, nullptr);
  ASSERT_EQ(blend->components.size(), 2u);
  EXPECT_EQ(blend->components[1].material, "B / y");
  EXPECT_EQ(blend->components[1].mass_fraction, 0.4);
  EXPECT_EQ(blend->components[1].p2o5_pct, 46.0);
  EXPECT_EQ(contents.find_blend("B / x"), nullptr);

  std::string message;
  raw_exec(file.path(), "UPDATE blend_components SET mass_fraction = 1.5 WHERE position = 1");
  EXPECT_EQ(kind_of_reading(file.path(), &message), ErrorKind::kCorrupt);
  EXPECT_NE(message.find("blend B component 1: impossible value: mass_fraction: must be in (0, 1], got 1.5"), std::string::npos)
      << message;
  raw_exec(file.path(), "UPDATE blend_components SET mass_fraction = 0.4 WHERE position = 1");
  EXPECT_EQ(kind_of_reading(file.path()), std::nullopt);
  raw_exec(file.path(), "UPDATE blend_components SET n_pct = 17 WHERE position = 1");
  EXPECT_EQ(kind_of_reading(file.path(), &message), ErrorKind::kCorrupt);
  EXPECT_NE(message.find("blend B component 1: checksum mismatch"), std::string::npos) << message;
  raw_exec(file.path(), "UPDATE blend_components SET n_pct = 18 WHERE position = 1; DELETE FROM blend_components WHERE position = 0");
  EXPECT_EQ(kind_of_reading(file.path(), &message), ErrorKind::kCorrupt);
  EXPECT_NE(message.find("positions must run 0, 1"), std::string::npos) << message;
}

TEST(BlendTable, TheWriterRefusesAnImpossibleBlend) {
  TempPath file("blend.sqlite");
  write_blend_table(file.path());
  TableWriter writer(file.path());
  Blend bad = two_component_blend();
  bad.components[0].mass_fraction = 0.5;
  EXPECT_THROW(writer.write_blend(bad), std::invalid_argument);
  bad = two_component_blend();
  bad.components[1].material = "B / z";  // no such material row
  EXPECT_THROW(writer.write_blend(bad), std::invalid_argument);
  bad = two_component_blend();
  bad.components[1].k2o_pct = 120.0;
  EXPECT_THROW(writer.write_blend(bad), std::invalid_argument);
  EXPECT_EQ(read_table_file(file.path()).blends.front().components[0].mass_fraction, 0.6);  // unchanged
}

// A version-2 table is a version-3 table without `blend_components`: it loads, with no blends. A
// version-3 table that lost the table is damaged. Writers write only the current version.
TEST(BlendTable, VersionTwoTablesStillLoad) {
  TempPath file("v2.sqlite");
  testing::write_sample_table(file.path());
  raw_exec(file.path(), "DROP TABLE blend_components");
  std::string message;
  EXPECT_EQ(kind_of_reading(file.path(), &message), ErrorKind::kCorrupt);
  EXPECT_NE(message.find("table `blend_components` is missing"), std::string::npos) << message;
  raw_exec(file.path(), "PRAGMA user_version = 2");
  const TableContents contents = read_table_file(file.path());
  EXPECT_TRUE(contents.blends.empty());
  EXPECT_EQ(contents.runs.size(), 3u);
  try {
    TableWriter writer(file.path());
    ADD_FAILURE() << "a version-2 file was opened for writing";
  } catch (const TableError& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kWrongVersion);
  }
  raw_exec(file.path(), "PRAGMA user_version = 1");
  EXPECT_EQ(kind_of_reading(file.path()), ErrorKind::kWrongVersion);
}

std::string text_of(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The tiny DEM machine with a blend of its urea and DAP (two densities, one size distribution).
scene::Scene tiny_blend_scene(double urea_fraction) {
  std::string text = text_of(std::string(SPREAD_SOURCE_DIR) + "/tests/tables/data/tiny_dem.toml");
  std::ostringstream blend;
  blend << "\n[[materials]]\nname = \"UD blend\"\n";
  const std::pair<const char*, double> components[] = {{"Urea", 1257}, {"DAP", 1606}};
  for (const auto& [name, density] : components) {
    blend << "[[materials.components]]\nname = \"" << name << "\"\ndensity_kg_m3 = " << density
          << "\nfriction_wall = 0.5\nfriction_particle = 0.5\nyoungs_modulus_pa = 5e6\nmass_fraction = "
          << (name == std::string("Urea") ? urea_fraction : 1.0 - urea_fraction) << "\n";
  }
  text.insert(text.find("[simulate]"), blend.str());
  return scene::parse_scene(text, "tiny_blend.toml", {"sweep.materials=[\"UD blend\"]", "sweep.rpm=[650.0]",
                                                      "inlet.mass_flow_kg_s=0.05"});
}

// Each launch's component is its granule's: a sample's mass over its volume is its component's density
// (to float32's rounding), so the split put every launch in its own component's row.
TEST(LookupBlend, BuildsEachComponentsRowFromTheMixedStream) {
  const scene::Scene scene = tiny_blend_scene(0.5);
  TempPath file("tiny_blend.sqlite");
  lookup::BuildOptions options;
  options.output_path = file.path();
  const lookup::BuildSummary first = lookup::build_tables(scene, options);
  EXPECT_EQ(first.runs_written, 2);
  const TableContents contents = read_table_file(file.path());
  const Blend* blend = contents.find_blend("UD blend");
  ASSERT_NE(blend, nullptr);
  ASSERT_EQ(blend->components.size(), 2u);
  ASSERT_EQ(contents.runs.size(), 2u);
  const double densities[] = {1606, 1257};  // runs by name: "UD blend / DAP", "UD blend / Urea"
  for (std::size_t r = 0; r < 2; ++r) {
    const tables::Run& run = contents.runs[r];
    EXPECT_EQ(run.inputs_hash, scene.run_inputs_hash(scene.materials.back(), 650.0));
    ASSERT_GT(run.samples.size(), 5u) << run.material;
    for (const LaunchSample& s : run.samples) {
      const double volume = std::numbers::pi / 6.0 * std::pow(double{s.diameter_m}, 3);
      EXPECT_NEAR(double{s.mass_kg} / volume, densities[r], 1e-3 * densities[r]) << run.material;
    }
  }
  EXPECT_EQ(contents.runs[1].material, "UD blend / Urea");
  // Rerun: nothing to do. Another recipe: other inputs, refused without --rebuild.
  EXPECT_EQ(lookup::build_tables(scene, options).runs_skipped, 1);
  EXPECT_THROW(lookup::build_tables(tiny_blend_scene(0.6), options), lookup::BuildConflictError);
}

TEST(LookupBlend, SplitNeedsAComponentPerLaunch) {
  const scene::Scene scene = tiny_blend_scene(0.5);
  tables::Run mixed = testing::sample_run("UD blend", 650.0, 3);
  const std::vector<int> short_list{0, 1};
  EXPECT_THROW(lookup::split_blend_run(mixed, short_list, scene.materials.back()), std::invalid_argument);
  const std::vector<int> unknown{0, 1, 2};
  EXPECT_THROW(lookup::split_blend_run(mixed, unknown, scene.materials.back()), std::invalid_argument);
  const std::vector<int> fine{1, 0, 1};
  const std::vector<tables::Run> runs = lookup::split_blend_run(mixed, fine, scene.materials.back());
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_EQ(runs[0].samples.size(), 1u);
  EXPECT_EQ(runs[1].samples.size(), 2u);
  EXPECT_EQ(runs[1].material, "UD blend / DAP");
  EXPECT_EQ(runs[1].samples[1].t_s, mixed.samples[2].t_s);
}

}  // namespace
}  // namespace spread::tables
