// The machine's drop-point scale: a turn in degrees read as the marks a technician sets, and a scales
// file that cannot be one refused naming its key.
#include <gtest/gtest.h>

#include <string>

#include "libspread/analysis/calibration/machine_scales.hpp"
#include "libspread/io/scene/scene.hpp"

namespace cal = spread::calibration;

namespace {

const char* kLettered = "[drop_point_scale]\nmarks = [\"A\", \"B\", \"C\", \"D\", \"E\"]\nturn_deg = [-30, -15, 0, 15, 30]\n";

std::string refusal(const std::string& text) {
  try {
    cal::parse_machine_scales(text, "s.toml");
  } catch (const spread::scene::SceneError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(MachineScales, ATurnReadsAsItsMark) {
  const cal::DropPointScale scale = cal::parse_machine_scales(kLettered, "s.toml").drop_point;
  EXPECT_EQ(cal::drop_point_mark(scale, 0.0), "C");
  EXPECT_EQ(cal::drop_point_mark(scale, 15.4), "D");  // within a twentieth of the 15 deg step
  EXPECT_EQ(cal::drop_point_mark(scale, 9.5), "C+0.6 towards D");
  EXPECT_EQ(cal::drop_point_mark(scale, -4.8), "B+0.7 towards C");
  EXPECT_EQ(cal::drop_point_mark(scale, 30.0), "E");
  EXPECT_EQ(cal::drop_point_mark(scale, 45.0), "beyond E, which is +30.0 deg");
  EXPECT_EQ(cal::drop_point_mark(scale, -40.0), "beyond A, which is -30.0 deg");
}

TEST(MachineScales, TheBundledMachinesScaleIsRead) {
  const cal::MachineScales scales =
      cal::read_machine_scales(std::string(SPREAD_SOURCE_DIR) + "/scenes/field/default_scales.toml");
  ASSERT_EQ(scales.drop_point.marks.size(), 8u);
  EXPECT_EQ(cal::drop_point_mark(scales.drop_point, 0.0), "D");  // the table's drop point
  EXPECT_EQ(cal::drop_point_mark(scales.drop_point, 60.0), "H");
}

TEST(MachineScales, AFileThatCannotBeAScaleIsRefusedByItsKey) {
  EXPECT_NE(refusal("[drop_point_scale]\nmarks = [\"A\", \"B\"]\nturn_deg = [0]\n").find("turn_deg: 1 turns for 2 marks"),
            std::string::npos);
  EXPECT_NE(refusal("[drop_point_scale]\nmarks = [\"A\", \"B\"]\nturn_deg = [10, 5]\n").find("the turns must rise"),
            std::string::npos);
  EXPECT_NE(refusal("[drop_point_scale]\nmarks = [\"A\"]\nturn_deg = [0]\n").find("at least two marks"), std::string::npos);
  EXPECT_NE(refusal("[drop_point_scale]\nmarks = [\"A\", \"A\"]\nturn_deg = [0, 5]\n").find("empty or repeated"),
            std::string::npos);
  EXPECT_NE(refusal("[drop_point_scale]\nmarks = [\"A\", \"B\"]\nturn_deg = [0, 500]\n").find("beyond ±180"),
            std::string::npos);
  EXPECT_NE(refusal("[drop_point_scale]\nmarks = [\"A\", \"B\"]\nturn_deg = [0, 5]\ncolour = 1\n").find("unknown key"),
            std::string::npos);
  EXPECT_NE(refusal("[gate]\nmarks = [1]\n").find("unknown key"), std::string::npos);
  EXPECT_NE(refusal("[drop_point_scale]\nturn_deg = [0, 5]\n").find("marks: missing"), std::string::npos);
}
