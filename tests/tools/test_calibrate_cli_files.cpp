// `spread calibrate tray` on the files a technician really has: one short stderr line in the tool's own
// format for every refusal (argument errors too), and the right numbers from old Mac line endings and
// units in parentheses. The reader's own cases are in tests/calibration (TrayFileSafety, TrayColumns,
// TrayPlausibility); these check that the tool passes them on.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace fs = std::filesystem;

namespace {

const std::string kSpread = SPREAD_CLI;
const std::string kExample = std::string(SPREAD_SOURCE_DIR) + "/scenes/field/tray_test_3passes.csv";

fs::path work_dir() {
  const fs::path dir = fs::path(SPREAD_TEST_WORK_DIR) / std::to_string(getpid());
  fs::create_directories(dir);
  return dir;
}

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

struct CommandRun {
  int exit_code = -1;
  std::string out, err;
};

CommandRun spread(const std::string& arguments) {
  const fs::path out = work_dir() / "run.out", err = work_dir() / "run.err";
  const int status =
      std::system(("'" + kSpread + "' " + arguments + " > '" + out.string() + "' 2> '" + err.string() + "'").c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(out), slurp(err)};
}

// The example's header and tray rows (comments dropped).
std::vector<std::string> example_lines() {
  std::istringstream in(slurp(kExample));
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line[0] != '#') lines.push_back(line);
  }
  return lines;
}

fs::path write_file(const std::string& name, const std::string& text) {
  const fs::path path = work_dir() / name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

std::string joined(const std::vector<std::string>& lines, const std::string& end, std::size_t from = 0) {
  std::string text;
  for (std::size_t i = from; i < lines.size(); ++i) text += lines[i] + end;
  return text;
}

// One line "spread calibrate ...: error: ..." and exit code 2.
void expect_one_error_line(const CommandRun& r, const std::string& command, const std::string& part) {
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_EQ(r.err.rfind(command + ": error: ", 0), 0u) << r.err.substr(0, 300);
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "more than one line: " << r.err.substr(0, 300);
  EXPECT_NE(r.err.find(part), std::string::npos) << r.err.substr(0, 300);
  EXPECT_LT(r.err.size(), 400u);
}

}  // namespace

TEST(CalibrateCliFiles, ArgumentErrorIsOneLineInTheToolsFormat) {
  const CommandRun r = spread("calibrate rate --mass 25kg --time 60 --gate 40 --target-rate 50 --width 24 --speed 12");
  expect_one_error_line(r, "spread calibrate rate", "--mass: '25kg' is not a value it takes (a number without its unit");
  expect_one_error_line(spread("calibrate tray"), "spread calibrate tray", "file is required");
}

TEST(CalibrateCliFiles, BinaryFileIsRefusedWithoutItsBytes) {
  const fs::path copy = work_dir() / "program.csv";
  fs::copy_file(kSpread, copy, fs::copy_options::overwrite_existing);
  const CommandRun r = spread("calibrate tray '" + copy.string() + "'");
  expect_one_error_line(r, "spread calibrate tray", "not a text file: binary content");
  EXPECT_EQ(r.err.find("ELF"), std::string::npos);
}

TEST(CalibrateCliFiles, HugeCellIsQuotedCut) {
  std::vector<std::string> lines = example_lines();
  lines[1] = lines[1].substr(0, lines[1].find(',')) + "," + std::string(5'000'000, '9') + ",1,1";
  const CommandRun r = spread("calibrate tray '" + write_file("bigcell.csv", joined(lines, "\n")).string() + "'");
  expect_one_error_line(r, "spread calibrate tray", "bigcell.csv:2: pass1_g: '999");
  EXPECT_NE(r.err.find("…' is not a number"), std::string::npos) << r.err.substr(0, 300);
}

TEST(CalibrateCliFiles, DirectoryIsNamedAsOne) {
  expect_one_error_line(spread("calibrate tray '" + work_dir().string() + "'"), "spread calibrate tray",
                        ": is a directory, not a tray-test file");
}

TEST(CalibrateCliFiles, CarriageReturnFileGivesTheExamplesCv) {
  const fs::path mac = write_file("mac.csv", joined(example_lines(), "\r"));
  const CommandRun r = spread("calibrate tray '" + mac.string() + "' --width 3.5");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("72 trays of 0.50 m, 3 pass(es)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("at W = 3.50 m: CV 15.1 % to-and-fro"), std::string::npos) << r.out;
}

TEST(CalibrateCliFiles, EveryMassColumnIsReadOrRefusedByName) {
  std::vector<std::string> lines = example_lines();
  lines[0] = "position_m,pass1_g,pass2 (g),pass3_g";
  const CommandRun r = spread("calibrate tray '" + write_file("paren.csv", joined(lines, "\n")).string() + "' --width 3.5");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("3 pass(es)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("CV 15.1 % to-and-fro"), std::string::npos) << r.out;
  lines[0] = "position_m,pass1_lb,pass2_g,pass3_g";
  expect_one_error_line(spread("calibrate tray '" + write_file("lb.csv", joined(lines, "\n")).string() + "'"),
                        "spread calibrate tray", "lb.csv:1: column 'pass1_lb': mass in 'lb' is not read");
}

TEST(CalibrateCliFiles, GramsInKilogramColumnsAreNamed) {
  std::vector<std::string> lines = example_lines();
  lines[0] = "position_m,pass1_kg,pass2_kg,pass3_kg";
  const CommandRun r = spread("calibrate tray '" + write_file("gkg.csv", joined(lines, "\n")).string() +
                              "' --width 3.5 --tray-area 0.25 --rate-kg-ha 850");
  expect_one_error_line(r, "spread calibrate tray", "grams in a kilogram column?");
  EXPECT_EQ(r.out, "");
}

TEST(CalibrateCliFiles, WidthBeyondTheTraysIsRefused) {
  expect_one_error_line(spread("calibrate tray '" + kExample + "' --width 50"), "spread calibrate tray",
                        "--width 50 m is wider than the trays reach (36.00 m");
}

TEST(CalibrateCliFiles, RateWithAMissingTraySaysItIsLow) {
  std::vector<std::string> lines = example_lines();
  for (std::string& line : lines) {
    if (line.rfind("4.750,", 0) == 0) line = "4.750,NA,NA,NA";  // the fullest tray
  }
  const std::string file = write_file("missing.csv", joined(lines, "\n")).string();
  const std::string rate = "' --width 3.5 --tray-area 0.25 --rate-kg-ha 850";
  const CommandRun text = spread("calibrate tray '" + file + rate);
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("note: the caught rate counts the trays read only: missing trays lower it"), std::string::npos)
      << text.out;
  const CommandRun json = spread("calibrate tray '" + file + rate + " --json");
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const nlohmann::json j = nlohmann::json::parse(json.out);
  bool noted = false;
  for (const auto& note : j["notes"]) noted |= note.get<std::string>().find("missing trays lower it") != std::string::npos;
  EXPECT_TRUE(noted) << j["notes"].dump();
  // Without a missing tray, no such note.
  EXPECT_EQ(spread("calibrate tray '" + kExample + rate).out.find("missing trays lower it"), std::string::npos);
}

TEST(CalibrateCliFiles, NoCvWhereTooFewTraysOfTheBoutRemain) {
  // 47 trays (a triangle), the one at -4.5 m missing: at W = 1 m the to-and-fro bout keeps 1.5 trays' weight.
  std::string text = "position_m,mass_g\n";
  for (int k = -23; k <= 23; ++k) {
    text += std::to_string(0.5 * k) + "," + (k == -9 ? std::string("NA") : std::to_string(24 - std::abs(k))) + "\n";
  }
  const std::string file = write_file("t47.csv", text).string();
  const CommandRun r = spread("calibrate tray '" + file + "' --width 1");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("at W = 1.00 m: CV none (missing trays leave under two trays of the bout measured) to-and-fro"),
            std::string::npos)
      << r.out;
  const CommandRun json = spread("calibrate tray '" + file + "' --width 1 --json");
  ASSERT_EQ(json.exit_code, 0) << json.err;
  EXPECT_TRUE(nlohmann::json::parse(json.out)["cv_to_and_fro_percent"].is_null()) << json.out;
}

TEST(CalibrateCliFiles, FitAtTheWrongDiscSpeedIsWarned) {
#ifndef SPREAD_LOOKUP_BUILDER
  GTEST_SKIP() << "needs lookup_builder";
#else
  // A small analytic table (256 samples per row, the narrow Case 1 inlet, 450-750 rpm), a synthetic tray
  // test at 600 rpm, fitted at 750 rpm: launch speed factor about 0.8.
  const fs::path table = work_dir() / "urea.sqlite", trays = work_dir() / "urea600.csv",
                 output = work_dir() / "urea750.sqlite";
  fs::remove(table);
  fs::remove(output);
  ASSERT_EQ(std::system(("'" + std::string(SPREAD_LOOKUP_BUILDER) + "' '" + SPREAD_SOURCE_DIR +
                         "/scenes/default.toml' --output '" + table.string() +
                         "' --set sweep.source=analytic --set 'sweep.materials=[\"Urea\"]' --set sweep.samples_per_run=256 "
                         "--set inlet.radius_m=0.0145 --set inlet.offset_m=0.1 --set inlet.angle_rad=1.0 > /dev/null")
                            .c_str()),
            0);
  ASSERT_EQ(spread("calibrate synth --tables '" + table.string() + "' --material Urea --rpm 600 --output '" +
                   trays.string() + "' --force --mass 150 --granule-mass 0.02 --seed 3 --samples 256")
                .exit_code,
            0);
  const CommandRun r = spread("calibrate pattern --tables '" + table.string() + "' --material Urea --rpm 750 --trays '" +
                              trays.string() + "' --output '" + output.string() + "' --fit speed,offset --samples 256");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("launch speed factor      0.7957"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("warning: the launch speed factor 0.796 is 20 % from 1 (warning beyond 15 %"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("this test looks like one at about 597 rpm fitted at --rpm 750"), std::string::npos) << r.out;
#endif
}

// The unit slips a technician makes, each refused before any arithmetic with the likely unit named —
// not a rate of 0.1 kg/ha, a "FAIL 0.0 %" or a number running off the page.
TEST(CalibrateCliFiles, APassInKilogramsUnderAGramsHeaderIsNamed) {
  std::vector<std::string> lines = example_lines();
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const std::size_t last = lines[i].rfind(',');
    lines[i] = lines[i].substr(0, last + 1) + std::to_string(std::stod(lines[i].substr(last + 1)) / 1000.0);
  }
  const CommandRun r = spread("calibrate tray '" + write_file("kgpass.csv", joined(lines, "\n")).string() + "' --width 3.5");
  expect_one_error_line(r, "spread calibrate tray", "kgpass.csv: pass3_g holds 0.1553 g in the trays read in every pass");
  EXPECT_NE(r.err.find("kilograms in a grams column? enter it in grams (× 1000)"), std::string::npos) << r.err;
  EXPECT_EQ(r.out, "");
}

TEST(CalibrateCliFiles, ReportNumbersOutsideAFieldAreRefusedWithTheirUnit) {
  const std::string tray = "calibrate tray '" + kExample + "' --width 3.5 ";
  expect_one_error_line(spread(tray + "--tray-area 2500 --rate-kg-ha 300"), "spread calibrate tray",
                        "--tray-area 2500: a collecting tray's area is 0.01-0.5 m²; 2500 cm² is 0.25 m² — give it in m²");
  expect_one_error_line(spread(tray + "--tray-area 1e-300"), "spread calibrate tray",
                        "--tray-area 1e-300: a collecting tray's area is 0.01-0.5 m²");
  expect_one_error_line(spread(tray + "--tray-area 0.25 --rate-kg-ha 1e300"), "spread calibrate tray",
                        "--rate-kg-ha 1e+300: an application rate is 1-20000 kg/ha");
  expect_one_error_line(spread(tray + "--tray-area 0.25 --rate-kg-ha " + std::string("1") + std::string(62, '0')),
                        "spread calibrate tray", "--rate-kg-ha 1e+62: an application rate is 1-20000 kg/ha");
  expect_one_error_line(spread(tray + "--speed 12000"), "spread calibrate tray", "12000 m/h is 12 km/h");
  expect_one_error_line(spread("calibrate tray '" + kExample + "' --width 350"), "spread calibrate tray",
                        "--width 350: a bout width is 1-100 m; 350 cm is 3.5 m");
}

TEST(CalibrateCliFiles, CatchTestNumbersOutsideAFieldAreRefusedWithTheirUnit) {
  const std::string rate = "calibrate rate --time 60 --gate 40 ";
  expect_one_error_line(spread(rate + "--mass 25000 --target-rate 300 --width 24 --speed 12"), "spread calibrate rate",
                        "--mass 25000: a catch test's mass is 0.1-5000 kg; 25000 g is 25 kg — give it in kg");
  expect_one_error_line(spread(rate + "--mass 25 --target-rate 0.3 --width 24 --speed 12"), "spread calibrate rate",
                        "0.3 t/ha is 300 kg/ha");
  expect_one_error_line(spread(rate + "--mass 25 --target-rate 300 --width 2400 --speed 12"), "spread calibrate rate",
                        "2400 cm is 24 m");
  expect_one_error_line(spread(rate + "--mass 25 --target-rate 1e300 --width 24 --speed 12"), "spread calibrate rate",
                        "--target-rate 1e+300: an application rate is 1-20000 kg/ha");
  expect_one_error_line(spread(rate + "--mass 25 --target-rate 300 --width 24 --speed 1e-300"), "spread calibrate rate",
                        "--speed 1e-300: a forward speed is 1-50 km/h");
}
