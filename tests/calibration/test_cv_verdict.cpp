// The verdict rule every report opens with (cv_verdict.hpp), at and around its edges.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "libspread/analysis/calibration/cv_verdict.hpp"

namespace cal = spread::calibration;

TEST(CvVerdict, TheIntervalAgainstTheTarget) {
  EXPECT_EQ(cal::cv_verdict(0.10, 0.08, 0.12, 0.15).verdict, cal::Verdict::kPass);
  EXPECT_EQ(cal::cv_verdict(0.14, 0.12, 0.15, 0.15).verdict, cal::Verdict::kPass);     // top on the target
  EXPECT_EQ(cal::cv_verdict(0.14, 0.12, 0.1501, 0.15).verdict, cal::Verdict::kMarginal);
  EXPECT_EQ(cal::cv_verdict(0.151, 0.146, 0.156, 0.15).verdict, cal::Verdict::kMarginal);
  EXPECT_EQ(cal::cv_verdict(0.16, 0.15, 0.17, 0.15).verdict, cal::Verdict::kMarginal);  // bottom on the target
  EXPECT_EQ(cal::cv_verdict(0.22, 0.216, 0.224, 0.15).verdict, cal::Verdict::kFail);
  // An interval unbounded above (a large CV from four trays) can still pass nothing.
  EXPECT_EQ(cal::cv_verdict(0.30, 0.14, std::numeric_limits<double>::infinity(), 0.15).verdict,
            cal::Verdict::kMarginal);
}

TEST(CvVerdict, WithoutAnIntervalTheCvItself) {
  const double none = std::nan("");
  EXPECT_EQ(cal::cv_verdict(0.15, none, none, 0.15).verdict, cal::Verdict::kPass);
  EXPECT_EQ(cal::cv_verdict(0.151, none, none, 0.15).verdict, cal::Verdict::kFail);
  EXPECT_EQ(cal::cv_verdict(none, none, none, 0.15).verdict, cal::Verdict::kNoCv);
  EXPECT_EQ(cal::cv_verdict(std::numeric_limits<double>::infinity(), none, none, 0.15).verdict, cal::Verdict::kFail);
}

TEST(CvVerdict, InWords) {
  EXPECT_EQ(cal::verdict_sentence("CV at the 8.00 m bout", cal::cv_verdict(0.22, 0.216, 0.224, 0.15)),
            "CV at the 8.00 m bout: FAIL, 22.0 % (95 % interval 21.6-22.4 %), above the target 15 %");
  EXPECT_EQ(cal::verdict_detail(cal::cv_verdict(0.151, 0.146, 0.156, 0.15)),
            "15.1 % (95 % interval 14.6-15.6 %), the interval holds the target 15 %");
  EXPECT_EQ(cal::verdict_detail(cal::cv_verdict(0.10, std::nan(""), std::nan(""), 0.15)),
            "10.0 % (no interval), within the target 15 %");
  EXPECT_STREQ(cal::verdict_key(cal::Verdict::kMarginal), "marginal");
}
