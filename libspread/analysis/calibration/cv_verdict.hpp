#pragma once
// The verdict a report states first: a CV against its target, read with the CV's 95 % interval.
//
//   PASS      the whole interval is within the target (its top <= target);
//   MARGINAL  the target lies inside the interval: the test cannot tell whether the spread meets it;
//   FAIL      even the bottom of the interval is above the target.
//
// The same rule as the quick check's meets / undecided / fails (quick_check.hpp) and the setting chart's
// "marginal" (a best setting whose interval reaches over the target), so every report reads alike.
// Without an interval (a tray test of one pass has no repeatability to estimate one from) the CV
// itself is compared: PASS or FAIL.
#include <limits>
#include <string>

namespace spread::calibration {

enum class Verdict { kPass, kMarginal, kFail, kNoCv };
// "PASS", "MARGINAL", "FAIL", "NO CV".
const char* verdict_word(Verdict verdict);
// "pass", "marginal", "fail", "no_cv" (JSON).
const char* verdict_key(Verdict verdict);

struct CvVerdict {
  Verdict verdict = Verdict::kNoCv;
  double cv = std::numeric_limits<double>::quiet_NaN();    // fraction; NaN: no CV
  double low = std::numeric_limits<double>::quiet_NaN();   // the 95 % interval, fractions; NaN: none
  double high = std::numeric_limits<double>::quiet_NaN();  // +inf: unbounded above
  double target = 0.15;                                    // fraction
  bool has_interval() const { return !(low != low) && !(high != high); }
};

// cv, low and high as above (low <= cv <= high when given); target a fraction in (0, 1]. A NaN cv is
// kNoCv; an infinite cv (a bout without mass) is kFail.
CvVerdict cv_verdict(double cv, double low, double high, double target);

// The verdict's grounds, e.g. "22.0 % (95 % interval 21.6-22.4 %), above the target 15 %".
std::string verdict_detail(const CvVerdict& v);
// The verdict in words for a report's first lines, e.g. "CV at 8.00 m, to-and-fro: FAIL, 22.0 % (95 %
// interval 21.6-22.4 %), above the target 15 %". `what` names the CV.
std::string verdict_sentence(const std::string& what, const CvVerdict& v);

}  // namespace spread::calibration
