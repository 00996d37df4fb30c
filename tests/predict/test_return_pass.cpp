// The return pass of a to-and-fro field in wind (return_pass.cpp, docs/metrics.md "To-and-fro in wind"):
// which way the predictor reads to-and-fro, and that the return pass it flies is the machine's own
// prediction in the wind from the other side.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "libspread/analysis/metrics/metrics.hpp"
#include "libspread/analysis/predict/predictor.hpp"
#include "tests/predict/synthetic_table.hpp"

namespace spread::predict {
namespace {

PredictionRequest at_bout(double wind_x_m_s, double wind_y_m_s) {
  PredictionRequest r;
  r.material = "can";
  r.rpm = 650.0;
  r.bout_width_m = 12.0;
  r.wind_x_m_s = wind_x_m_s;
  r.wind_y_m_s = wind_y_m_s;
  return r;
}

PredictionRequest own_discs(PredictionRequest r, double left_rpm, double right_rpm) {
  r.rpm = 0.0;
  r.disc_rpm = {left_rpm, right_rpm};
  return r;
}

std::vector<double> copy(std::span<const double> s) { return {s.begin(), s.end()}; }

// The pattern of `r` on a centred layout of `count` trays (both layouts centred with whole trays: the
// narrower one nests in the wider).
std::vector<double> on_layout(std::span<const double> pattern, int count) {
  std::vector<double> out(static_cast<std::size_t>(count), 0.0);
  const std::size_t pad = (static_cast<std::size_t>(count) - pattern.size()) / 2;
  for (std::size_t k = 0; k < pattern.size(); ++k) out[pad + k] = pattern[k];
  return out;
}

TEST(ReturnPass, StillAirIsTheOutgoingPatternItself) {
  Predictor p(testing::synthetic_contents());
  Prediction out;
  ASSERT_EQ(p.predict(at_bout(0.0, 0.0), out), PredictStatus::kOk);
  EXPECT_EQ(out.return_pass, ReturnPass::kOutgoing);
  EXPECT_EQ(out.return_tray_mass_fraction.data(), out.tray_mass_fraction.data());
  EXPECT_EQ(out.cv_to_and_fro, metrics::cv_at_trays(out.tray_mass_fraction, out.trays, 24, metrics::Overlap::kToAndFro));
}

TEST(ReturnPass, ALateralWindOnAlikeDiscsReadsAsRacetrack) {
  Predictor p(testing::synthetic_contents());
  Prediction out;
  ASSERT_EQ(p.predict(at_bout(3.0, 0.0), out), PredictStatus::kOk);
  EXPECT_EQ(out.return_pass, ReturnPass::kRacetrack);
  EXPECT_EQ(out.flights, 512);  // both discs once: no return pass flown
  EXPECT_EQ(out.cv_to_and_fro, out.cv_racetrack);
  EXPECT_EQ(out.working_width_to_and_fro_m, out.working_width_racetrack_m);
  // Its return pass is its pattern in the wind from the other side, which is the outgoing one mirrored.
  const std::vector<double> outgoing = copy(out.tray_mass_fraction), back = copy(out.return_tray_mass_fraction);
  Prediction other_side;
  ASSERT_EQ(p.predict(at_bout(-3.0, 0.0), other_side), PredictStatus::kOk);
  ASSERT_EQ(other_side.tray_mass_fraction.size(), back.size());
  for (std::size_t k = 0; k < back.size(); ++k) {
    EXPECT_EQ(back[k], outgoing[back.size() - 1 - k]);
    EXPECT_NEAR(back[k], other_side.tray_mass_fraction[k], 1e-9) << k;
  }
  // The tray test's rule, asked for: the outgoing pattern mirrored, as before the return pass.
  PredictionRequest tray_rule = at_bout(3.0, 0.0);
  tray_rule.return_pass = ReturnPassSettings::kOutgoingMirrored;
  Prediction mirrored;
  ASSERT_EQ(p.predict(tray_rule, mirrored), PredictStatus::kOk);
  EXPECT_EQ(mirrored.return_pass, ReturnPass::kOutgoing);
  EXPECT_EQ(mirrored.cv_to_and_fro, metrics::cv_at_trays(outgoing, out.trays, 24, metrics::Overlap::kToAndFro));
  EXPECT_NE(mirrored.cv_to_and_fro, out.cv_to_and_fro);
}

TEST(ReturnPass, DiscsThatKeepTheirOwnSettingsFlyTheReturnPassAndThoseThatSwapDoNot) {
  Predictor p(testing::synthetic_contents());
  const PredictionRequest outgoing = own_discs(at_bout(3.0, 0.0), 600.0, 700.0);
  Prediction kept;
  ASSERT_EQ(p.predict(outgoing, kept), PredictStatus::kOk);
  EXPECT_EQ(kept.return_pass, ReturnPass::kFlown);
  const std::vector<double> back = copy(kept.return_tray_mass_fraction), ahead = copy(kept.tray_mass_fraction);
  const metrics::TrayLayout trays = kept.trays;
  const double cv = kept.cv_to_and_fro;
  // The return pass is the same machine, the same settings, in the wind from the other side.
  Prediction independent;
  ASSERT_EQ(p.predict(own_discs(at_bout(-3.0, 0.0), 600.0, 700.0), independent), PredictStatus::kOk);
  ASSERT_LE(independent.tray_mass_fraction.size(), back.size());
  const std::vector<double> expected = on_layout(independent.tray_mass_fraction, trays.tray_count);
  for (std::size_t k = 0; k < back.size(); ++k) EXPECT_NEAR(back[k], expected[k], 1e-12) << k;
  EXPECT_NEAR(cv, metrics::cv_at_trays(ahead, back, trays, 24, {}), 1e-15);
  // Swapped with the heading, the return pass lands as the outgoing one: no second flight.
  PredictionRequest swapped = outgoing;
  swapped.return_pass = ReturnPassSettings::kSwapped;
  Prediction compensating;
  ASSERT_EQ(p.predict(swapped, compensating), PredictStatus::kOk);
  EXPECT_EQ(compensating.return_pass, ReturnPass::kRacetrack);
  EXPECT_EQ(compensating.flights * 2, kept.flights);
  EXPECT_EQ(compensating.cv_to_and_fro, compensating.cv_racetrack);
}

TEST(ReturnPass, AWindAlongTheTrackFliesTheTailwindPass) {
  Predictor p(testing::synthetic_contents());
  Prediction out;
  ASSERT_EQ(p.predict(at_bout(1.0, 4.0), out), PredictStatus::kOk);
  EXPECT_EQ(out.return_pass, ReturnPass::kFlown);
  EXPECT_TRUE(std::isfinite(out.cv_to_and_fro_se));
  EXPECT_GT(out.cv_to_and_fro_se, 0.0);
  // Copied before the next prediction, which reuses the predictor's workspace the spans point into.
  const std::vector<double> back = copy(out.return_tray_mass_fraction), ahead = copy(out.tray_mass_fraction);
  Prediction tailwind;
  ASSERT_EQ(p.predict(at_bout(-1.0, -4.0), tailwind), PredictStatus::kOk);
  const std::vector<double> expected = on_layout(tailwind.tray_mass_fraction, out.trays.tray_count);
  for (std::size_t k = 0; k < back.size(); ++k) EXPECT_NEAR(back[k], expected[k], 1e-12) << k;
  // Every band and the headline read with the return pass: the working width is the two-bout scan's.
  EXPECT_EQ(out.working_width_to_and_fro_m == 0.0,
            metrics::working_width(ahead, back, out.trays, 0.15).width_m == 0.0);
  EXPECT_EQ(out.bands_to_and_fro[0].upper_m, metrics::working_width(ahead, back, out.trays, 0.15).bands[0].upper_m);
}

}  // namespace
}  // namespace spread::predict
