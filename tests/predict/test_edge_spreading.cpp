// Border and edge spreading on the synthetic table: the setting found meets its thresholds in its own
// profile, a border setting throws less over the line than the normal one, an edge on the left is the
// mirror image of one on the right, the profile of a setting is the same however it is asked for, and
// requests out of the domain are refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "libspread/analysis/predict/edge_spreading.hpp"
#include "tests/predict/synthetic_table.hpp"

namespace spread::predict {
namespace {

PredictionRequest field(double bout_width_m) {
  PredictionRequest r;
  r.material = "can";
  r.rpm = 650.0;
  r.bout_width_m = bout_width_m;
  return r;
}

TEST(EdgeSpreading, BorderAndEdgeSettingsMeetTheirThresholds) {
  Predictor predictor(testing::synthetic_contents());
  for (const EdgeKind kind : {EdgeKind::kBorder, EdgeKind::kEdge}) {
    EdgeRequest edge;
    edge.kind = kind;
    const EdgeResult r = find_edge_setting(predictor, field(18.0), edge);
    ASSERT_EQ(r.status, PredictStatus::kOk);
    const EdgeProfile& p = r.profile;
    ASSERT_TRUE(p.meets) << to_string(kind) << ": beyond " << p.mass_beyond_fraction << ", most over-applied "
                         << p.most_over_applied_m << " m in bout " << p.most_over_applied_bout << ", excess "
                         << p.max_excess << ", at the edge " << p.rate_at_edge;
    // Anywhere the last pass reaches, the bouts before the last included: at most 5 % of a bout over the
    // limit, none of it by more than the tolerance.
    EXPECT_LE(p.max_excess, edge.rate_tolerance);
    EXPECT_LE(p.most_over_applied_m, 0.05 * 18.0);
    EXPECT_LE(p.judged_from_m, -1.5 * 18.0);
    if (kind == EdgeKind::kBorder) {
      EXPECT_LE(p.mass_beyond_fraction, edge.max_beyond_fraction);
      EXPECT_GT(r.normal_profile.mass_beyond_fraction, edge.max_beyond_fraction);  // the check has power
    } else {
      EXPECT_GE(p.rate_at_edge, edge.min_edge_rate);
    }
    EXPECT_EQ(p.edge_line_m, 9.0);
    EXPECT_GE(r.setting.flow_fraction, kEdgeMinFlow);
    EXPECT_LE(r.setting.flow_fraction, kEdgeMaxFlow);
    EXPECT_GE(r.setting.disc.rpm, 500.0);
    EXPECT_LE(r.setting.disc.rpm, 800.0);
    // The edge-side disc alone meets the thresholds here: the field-side disc keeps the field's setting.
    EXPECT_TRUE(std::isnan(r.setting.field_side_drop_point_turn_rad));
    // The same setting's profile asked for directly.
    EdgeProfile again;
    ASSERT_EQ(edge_profile(predictor, field(18.0), edge, r.setting, again), PredictStatus::kOk);
    EXPECT_EQ(again.rate, p.rate);
    EXPECT_EQ(again.mass_beyond_fraction, p.mass_beyond_fraction);
    // An edge on the left: the mirror image.
    EdgeRequest left = edge;
    left.side = kLeftDisc;
    const EdgeResult l = find_edge_setting(predictor, field(18.0), left);
    EXPECT_EQ(l.setting.disc.rpm, r.setting.disc.rpm) << to_string(kind);
    EXPECT_EQ(l.setting.flow_fraction, r.setting.flow_fraction);
    EXPECT_NEAR(l.profile.mass_beyond_fraction, p.mass_beyond_fraction, 1e-12);
  }
}

// In wind the passes before the last are to and fro, every other one driven the other way and meeting the
// wind from the other side (docs/metrics.md "To-and-fro in wind"): in a crosswind on alike discs they land
// as the normal pass does, with a wind along the track the return pass is flown. The profile judged is then
// not the tray test's mirror rule's, and a setting is found in both.
TEST(EdgeSpreading, ThePassesBeforeTheLastMeetTheWindFromBothSides) {
  Predictor predictor(testing::synthetic_contents());
  EdgeRequest edge;
  edge.kind = EdgeKind::kBorder;
  for (const double wind_y_m_s : {0.0, 2.0}) {
    PredictionRequest windy = field(18.0);
    windy.wind_x_m_s = 3.0;
    windy.wind_y_m_s = wind_y_m_s;
    PredictionRequest mirror_rule = windy;
    mirror_rule.return_pass = ReturnPassSettings::kOutgoingMirrored;
    const EdgeResult r = find_edge_setting(predictor, windy, edge);
    ASSERT_EQ(r.status, PredictStatus::kOk) << wind_y_m_s;
    EdgeProfile by_return_pass, by_mirror_rule;
    ASSERT_EQ(edge_profile(predictor, windy, edge, r.setting, by_return_pass), PredictStatus::kOk);
    ASSERT_EQ(edge_profile(predictor, mirror_rule, edge, r.setting, by_mirror_rule), PredictStatus::kOk);
    ASSERT_EQ(by_return_pass.rate.size(), r.profile.rate.size());
    double largest_difference = 0.0;
    for (std::size_t k = 0; k < r.profile.rate.size(); ++k) {
      largest_difference = std::max(largest_difference, std::abs(by_return_pass.rate[k] - r.profile.rate[k]));
    }
    EXPECT_LT(largest_difference, 1e-12) << wind_y_m_s;  // in wind the search's sums round apart by an ulp
    EXPECT_NE(by_return_pass.rate, by_mirror_rule.rate) << wind_y_m_s;
    // The last pass is the same pass either way: its mass beyond the line does not depend on the others.
    EXPECT_EQ(by_return_pass.mass_beyond_fraction, by_mirror_rule.mass_beyond_fraction);
    for (double rate : by_return_pass.rate) EXPECT_TRUE(std::isfinite(rate));
  }
}

TEST(EdgeSpreading, RefusesRequestsOutOfTheDomain) {
  Predictor predictor(testing::synthetic_contents());
  EdgeRequest edge;
  EXPECT_EQ(find_edge_setting(predictor, field(0.0), edge).status, PredictStatus::kOutOfRange);
  EdgeRequest gap = edge;
  gap.gap_m = 6.0;  // the edge line on the tramline
  EXPECT_EQ(find_edge_setting(predictor, field(12.0), gap).status, PredictStatus::kOutOfRange);
  EdgeRequest side = edge;
  side.side = 2;
  EXPECT_EQ(find_edge_setting(predictor, field(12.0), side).status, PredictStatus::kOutOfRange);
  EdgeRequest share = edge;
  share.max_beyond_fraction = 0.0;
  EXPECT_EQ(find_edge_setting(predictor, field(12.0), share).status, PredictStatus::kOutOfRange);
  PredictionRequest outside = field(12.0);
  outside.rpm = 900.0;
  EXPECT_EQ(find_edge_setting(predictor, outside, edge).status, PredictStatus::kRpmOutsideTable);
  Predictor single(testing::synthetic_contents(testing::default_synthetic_materials(), 1));
  EXPECT_EQ(find_edge_setting(single, field(12.0), edge).status, PredictStatus::kOutOfRange);
}

}  // namespace
}  // namespace spread::predict
