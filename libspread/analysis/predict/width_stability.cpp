#include "libspread/analysis/predict/width_stability.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace spread::predict {

namespace {

// splitmix64 (Steele, Lea & Flood 2014): a small generator whose stream is the same on every platform
// (std::uniform_int_distribution's is not).
struct SplitMix64 {
  std::uint64_t state;
  std::uint64_t next() {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  // Uniform in [0, n) (the remainder's bias, below n / 2^64, is far under the bootstrap's own noise).
  std::size_t below(std::size_t n) { return static_cast<std::size_t>(next() % n); }
};

double headline_of(tables::TableContents contents, const PredictionRequest& request, double& interval_m) {
  Predictor predictor(std::move(contents));
  Prediction p;
  const PredictStatus status = predictor.predict(request, p);
  if (status != PredictStatus::kOk) {
    throw std::invalid_argument(std::string("width_stability: the request is refused: ") + to_string(status));
  }
  interval_m = kConfidence95 * p.working_width_to_and_fro_se_m;
  return p.working_width_to_and_fro_m;
}

// The q-quantile of sorted values (linear between order statistics, Hyndman & Fan type 7).
double quantile(const std::vector<double>& sorted, double q) {
  const double at = q * static_cast<double>(sorted.size() - 1);
  const auto below = static_cast<std::size_t>(std::floor(at));
  const std::size_t above = std::min(below + 1, sorted.size() - 1);
  return sorted[below] + (at - static_cast<double>(below)) * (sorted[above] - sorted[below]);
}

}  // namespace

WidthStability width_stability(const tables::TableContents& contents, const PredictionRequest& request, int resamples,
                               std::uint64_t seed) {
  if (resamples < 2) throw std::invalid_argument("width_stability: at least 2 resamples");
  if (!contents.pooled_offset.empty()) throw std::invalid_argument("width_stability: the samples must be in each run");
  WidthStability out;
  out.resamples = resamples;
  out.headline_m = headline_of(contents, request, out.interval_m);
  SplitMix64 random{seed};
  std::vector<double> headlines;
  headlines.reserve(static_cast<std::size_t>(resamples));
  for (int r = 0; r < resamples; ++r) {
    tables::TableContents resampled;
    resampled.machine = contents.machine;
    resampled.materials = contents.materials;
    resampled.drop_point_turn_validated_rad = contents.drop_point_turn_validated_rad;
    resampled.runs.reserve(contents.runs.size());
    for (const tables::Run& run : contents.runs) {
      tables::Run drawn = run;
      for (tables::LaunchSample& s : drawn.samples) s = run.samples[random.below(run.samples.size())];
      resampled.runs.push_back(std::move(drawn));
    }
    double unused = 0.0;
    headlines.push_back(headline_of(std::move(resampled), request, unused));
  }
  int outside = 0, beyond = 0;
  for (double h : headlines) {
    if (!(std::abs(h - out.headline_m) <= out.interval_m)) ++outside;
    if (std::abs(h - out.headline_m) > 1.0) ++beyond;
  }
  out.outside_interval_fraction = static_cast<double>(outside) / resamples;
  out.beyond_1m_fraction = static_cast<double>(beyond) / resamples;
  std::sort(headlines.begin(), headlines.end());
  out.quantile_025_m = quantile(headlines, 0.025);
  out.quantile_975_m = quantile(headlines, 0.975);
  out.lowest_m = headlines.front();
  out.highest_m = headlines.back();
  return out;
}

}  // namespace spread::predict
