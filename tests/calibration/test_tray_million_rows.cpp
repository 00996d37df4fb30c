// A million-row tray file is read in linear time. Not a timing test (timed unit tests measure the
// machine): it checks what was read, and prints how long reading took. Registered on its own with the
// label `nosan` (tests/calibration/CMakeLists.txt): under a sanitizer a million rows take minutes.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <limits>
#include <string>

#include "libspread/analysis/calibration/tray_csv.hpp"
#include "tests/support/temp_path.hpp"

namespace cal = spread::calibration;

TEST(TrayMillionRows, ReadInOnePass) {
  constexpr int kRows = 1'000'000;
  const spread::testing::TempPath file("million.csv");
  {
    std::ofstream out(file.path());
    out << "position_m,pass1_g,pass2_g\n";
    char row[64];
    for (int k = 0; k < kRows; ++k) {
      // 0.5 m trays from -250 km, centres on the half-tray grid; masses cycling 1..7 and 1..5 g.
      std::snprintf(row, sizeof row, "%.2f,%d,%d\n", (k - kRows / 2) * 0.5 + 0.25, k % 7 + 1, k % 5 + 1);
      out << row;
    }
  }
  // Beyond any throw (tray_plausibility.hpp): refused at its first row, parsing no further.
  try {
    cal::read_tray_csv(file.path());
    ADD_FAILURE() << "a 500 km row of trays was read";
  } catch (const cal::TrayCsvError& e) {
    EXPECT_EQ(e.line(), 2) << e.what();
  }
  // With the physical limits lifted, every row is read.
  cal::TrayCsvOptions options;
  options.farthest_tray_m = std::numeric_limits<double>::infinity();
  const auto start = std::chrono::steady_clock::now();
  const cal::TrayTest t = cal::read_tray_csv(file.path(), options);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("read %d rows in %.2f s\n", kRows, seconds);
  // Linear reading takes 0.5 s here; the quadratic reader it replaced took 8.4 s of CPU for 16,000 rows and
  // did not finish 400,000 in 120 s. Ten seconds leaves a loaded machine twenty times the room.
  EXPECT_LT(seconds, 10.0);
  ASSERT_EQ(t.mass_kg.size(), static_cast<std::size_t>(kRows));
  EXPECT_EQ(t.layout.tray_count, kRows);
  EXPECT_EQ(t.padded_trays, 0);
  EXPECT_NEAR(t.tray_width_m, 0.5, 1e-9);
  EXPECT_NEAR(t.mass_kg[123'456], 1e-3 * 0.5 * (123'456 % 7 + 1 + 123'456 % 5 + 1), 1e-15);
  double expected_kg = 0.0;
  for (int k = 0; k < kRows; ++k) expected_kg += 1e-3 * 0.5 * (k % 7 + 1 + k % 5 + 1);
  EXPECT_NEAR(t.total_mass_kg(), expected_kg, 1e-9 * expected_kg);
}
