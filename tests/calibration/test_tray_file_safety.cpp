// Tray files that are not what they should be — huge cells, binary files, directories, devices, files
// over the size limit, old Mac line endings — are read or refused with a short, printable message.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

#include "libspread/analysis/calibration/text_excerpt.hpp"
#include "libspread/analysis/calibration/tray_csv.hpp"
#include "tests/calibration/calibration_test_support.hpp"
#include "tests/support/temp_path.hpp"

namespace cal = spread::calibration;
namespace fs = std::filesystem;

namespace {

using spread::testing::tray_csv_error;

// The message of the TrayCsvError reading `path` raises ("" when it reads).
std::string read_error(const std::string& path) {
  try {
    cal::read_tray_csv(path);
  } catch (const cal::TrayCsvError& e) {
    return e.what();
  }
  return "";
}

void write(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out << bytes;
}

const std::string kTrays = "-1.0,1,1\n-0.5,2,2\n0.0,3,3\n0.5,2,2\n1.0,1,1\n";

}  // namespace

TEST(TrayFileSafety, ExcerptCutsAndEscapes) {
  EXPECT_EQ(cal::excerpt("pass1_g"), "pass1_g");
  EXPECT_EQ(cal::excerpt(std::string(100, '9'), 10), "9999999999…");
  EXPECT_EQ(cal::excerpt("a\x01\x7f\tb"), "a\\x01\\x7F\\tb");
  EXPECT_EQ(cal::excerpt("\xff\xfe"), "\\xFF\\xFE");                     // not UTF-8
  EXPECT_EQ(cal::excerpt("10 \xC2\xB0" "C, M\xC3\xA4rz"), "10 °C, März");  // UTF-8 kept
  EXPECT_EQ(cal::excerpt("\xE2\x82"), "\\xE2\\x82");                     // a cut sequence
}

TEST(TrayFileSafety, HugeCellIsQuotedCut) {
  const std::string message = tray_csv_error("position_m,pass1_g\n-1.0," + std::string(5'000'000, '9') + "\n" + kTrays);
  EXPECT_NE(message.find("t.csv:2: pass1_g: '"), std::string::npos) << message.substr(0, 200);
  EXPECT_NE(message.find("…' is not a number"), std::string::npos) << message.substr(0, 200);
  EXPECT_LT(message.size(), 200u);
}

TEST(TrayFileSafety, HugeHeaderIsQuotedCut) {
  const std::string message = tray_csv_error("position_m," + std::string(1'000'000, 'x') + "\n" + kTrays);
  EXPECT_NE(message.find("column 'xxx"), std::string::npos) << message.substr(0, 200);
  EXPECT_LT(message.size(), 400u);
}

TEST(TrayFileSafety, ControlBytesInACellAreEscaped) {
  const std::string message = tray_csv_error("position_m,pass1_g\n-1.0,1\x1b[2J\n" + kTrays);
  EXPECT_NE(message.find("'1\\x1B[2J' is not a number"), std::string::npos) << message;
  EXPECT_EQ(message.find('\x1b'), std::string::npos);
}

TEST(TrayFileSafety, BinaryFileIsRefusedAsBinary) {
  const spread::testing::TempPath file("binary.csv");
  std::string bytes = "\x7f" "ELF\x02\x01\x01";
  bytes += std::string(200, '\0') + "position_m,pass1_g\n";
  write(file.path(), bytes);
  const std::string message = read_error(file.path());
  EXPECT_NE(message.find("not a text file: binary content"), std::string::npos) << message;
  EXPECT_EQ(message.find('\0'), std::string::npos);
  EXPECT_EQ(message.find("ELF"), std::string::npos) << "bytes of the file echoed: " << message;
}

TEST(TrayFileSafety, DirectoryIsSaidToBeOne) {
  const spread::testing::TempPath dir("folder.csv");
  fs::create_directory(dir.path());
  const std::string message = read_error(dir.path());
  fs::remove(dir.path());
  EXPECT_NE(message.find("is a directory"), std::string::npos) << message;
}

TEST(TrayFileSafety, FileOverTheLimitIsRefusedNamingSizeAndLimit) {
  const spread::testing::TempPath file("large.csv");
  write(file.path(), "position_m,pass1_g\n");
  fs::resize_file(file.path(), cal::kLargestTrayFile_bytes + 1'000'000);  // sparse: no disk written
  const std::string message = read_error(file.path());
  EXPECT_NE(message.find("the file is 65.0 MB: a tray-test file is read up to 64 MB"), std::string::npos) << message;
}

TEST(TrayFileSafety, EndlessDeviceIsRefusedAtOnce) {
  if (!fs::exists("/dev/zero")) GTEST_SKIP() << "no /dev/zero";
  const auto start = std::chrono::steady_clock::now();
  const std::string message = read_error("/dev/zero");
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_NE(message.find("not a text file"), std::string::npos) << message;
  // Not a timing test: reading to the limit or to the end of memory would take seconds or fail.
  std::printf("/dev/zero refused after %.3f s\n", seconds);
}

TEST(TrayFileSafety, CarriageReturnLineEndingsAreRead) {
  const cal::TrayTest t = cal::parse_tray_csv("# old Mac export\rposition_m,pass1_g\r-1.0,1\r-0.5,2\r0.0,3\r0.5,2\r1.0,1\r",
                                              "t.csv");
  ASSERT_EQ(t.mass_kg.size(), 5u);
  EXPECT_NEAR(t.mass_kg[2], 3e-3, 1e-15);
  // Line numbers count CR-ended lines: the bad cell is on line 4.
  EXPECT_NE(tray_csv_error("position_m,pass1_g\r-1.0,1\r-0.5,2\r0.0,x\r0.5,2\r1.0,1\r").find("t.csv:4: pass1_g"),
            std::string::npos);
  // Mixed CRLF and LF.
  EXPECT_EQ(cal::parse_tray_csv("position_m,pass1_g\r\n-1.0,1\n-0.5,2\r\n0.0,3\n0.5,2\r\n1.0,1", "t.csv").mass_kg.size(),
            5u);
}

TEST(TrayFileSafety, Utf16FileIsNamedAsSuchNotAsBinary) {
  const spread::testing::TempPath file("utf16.csv");
  std::string bytes("\xFF\xFE", 2);
  for (const char c : std::string("position_m,mass_g\n")) bytes += std::string{c, '\0'};
  write(file.path(), bytes);
  EXPECT_NE(read_error(file.path()).find("UTF-16"), std::string::npos) << read_error(file.path());
}
