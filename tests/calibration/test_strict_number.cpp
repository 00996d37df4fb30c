// The strict number reading every option, list option and tray-file cell shares
// (libspread/core/strict_number.hpp): the whole text one finite decimal number, nothing else.
#include <gtest/gtest.h>

#include <string_view>
#include <vector>

#include "libspread/core/strict_number.hpp"

namespace spread {
namespace {

TEST(StrictNumber, TakesTheWholeTextAsOneFiniteNumber) {
  EXPECT_EQ(parse_finite_number("0.221"), 0.221);
  EXPECT_EQ(parse_finite_number(" -3e2\t"), -300.0);
  EXPECT_EQ(parse_finite_number("+5"), 5.0);
  EXPECT_EQ(parse_finite_number("12."), 12.0);
  for (std::string_view bad : {"", " ", "abc", "1.5x", "1 2", "0,221", "inf", "-inf", "nan", "1e999", "0x10", "+-1",
                               "++1", "+"}) {
    EXPECT_FALSE(parse_finite_number(bad).has_value()) << "'" << bad << "'";
  }
}

TEST(StrictNumber, ListsStopAtTheFirstItemThatIsNotANumber) {
  std::vector<double> values;
  std::string_view bad;
  ASSERT_TRUE(parse_number_list("12, 15,18", values, bad));
  EXPECT_EQ(values, (std::vector<double>{12.0, 15.0, 18.0}));
  ASSERT_TRUE(parse_number_list("", values, bad));
  EXPECT_TRUE(values.empty());
  EXPECT_FALSE(parse_number_list("2,x,3", values, bad));
  EXPECT_EQ(bad, "x");
  EXPECT_EQ(values, (std::vector<double>{2.0}));
  EXPECT_FALSE(parse_number_list("2,", values, bad));  // a trailing comma is an empty item
  EXPECT_EQ(bad, "");
  EXPECT_FALSE(parse_number_list("2,,3", values, bad));
}

}  // namespace
}  // namespace spread
