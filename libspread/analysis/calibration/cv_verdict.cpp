#include "libspread/analysis/calibration/cv_verdict.hpp"

#include <cmath>
#include <cstdio>

#include "libspread/analysis/plot/cv_text.hpp"

namespace spread::calibration {

const char* verdict_word(Verdict verdict) {
  switch (verdict) {
    case Verdict::kPass: return "PASS";
    case Verdict::kMarginal: return "MARGINAL";
    case Verdict::kFail: return "FAIL";
    case Verdict::kNoCv: return "NO CV";
  }
  return "NO CV";
}

const char* verdict_key(Verdict verdict) {
  switch (verdict) {
    case Verdict::kPass: return "pass";
    case Verdict::kMarginal: return "marginal";
    case Verdict::kFail: return "fail";
    case Verdict::kNoCv: return "no_cv";
  }
  return "no_cv";
}

CvVerdict cv_verdict(double cv, double low, double high, double target) {
  CvVerdict v;
  v.cv = cv;
  v.low = low;
  v.high = high;
  v.target = target;
  if (std::isnan(cv)) {
    v.verdict = Verdict::kNoCv;
  } else if (!v.has_interval()) {
    v.verdict = cv <= target ? Verdict::kPass : Verdict::kFail;
  } else if (high <= target) {
    v.verdict = Verdict::kPass;
  } else if (low > target) {
    v.verdict = Verdict::kFail;
  } else {
    v.verdict = Verdict::kMarginal;
  }
  return v;
}

std::string verdict_detail(const CvVerdict& v) {
  if (v.verdict == Verdict::kNoCv) return "missing trays leave under two trays of the bout measured";
  if (std::isinf(v.cv)) return "the bout holds no mass";
  char interval[96] = "";
  if (v.has_interval()) {
    if (std::isfinite(v.high)) {
      std::snprintf(interval, sizeof interval, " (95 %% interval %.1f-%.1f %%)", 100.0 * v.low, 100.0 * v.high);
    } else {
      std::snprintf(interval, sizeof interval, " (95 %% interval from %.1f %%, unbounded above)", 100.0 * v.low);
    }
  } else {
    std::snprintf(interval, sizeof interval, " (no interval)");
  }
  const char* meaning = v.verdict == Verdict::kPass   ? "within"
                        : v.verdict == Verdict::kFail ? "above"
                                                      : "the interval holds";
  char text[256];
  std::snprintf(text, sizeof text, "%s%s, %s the target %g %%", plot::cv_percent_text(v.cv, v.target).c_str(), interval,
                meaning, 100.0 * v.target);
  return text;
}

std::string verdict_sentence(const std::string& what, const CvVerdict& v) {
  return what + ": " + verdict_word(v.verdict) + ", " + verdict_detail(v);
}

}  // namespace spread::calibration
