// Settings per pass and their stamps (machine_settings.hpp).
#include "libspread/analysis/field/machine_settings.hpp"

#include <cmath>
#include <map>
#include <numbers>

#include "libspread/core/error.hpp"

namespace spread::field {
namespace {

[[noreturn]] void refuse_setting(const std::string& what) {
  throw Error(ErrorKind::kArgument, "field setting", "field setting: " + what);
}

// The heading bin of a direction (unit vector, east and north components): bin k is centred on the
// compass heading k · 360°/kHeadingBins.
int heading_bin(Point forward) {
  const double compass = std::atan2(forward.x_m, forward.y_m);  // clockwise from north
  const double turns = compass / (2.0 * std::numbers::pi);
  return static_cast<int>(std::lround(turns * kHeadingBins + kHeadingBins)) % kHeadingBins;
}
Point bin_forward(int bin) {
  const double compass = 2.0 * std::numbers::pi * bin / kHeadingBins;
  return {std::sin(compass), std::cos(compass)};
}

// Each pass cut into its straight pieces, each labelled with its base setting · kHeadingBins + its bin.
std::vector<Pass> pieces_by_heading(const std::vector<Pass>& passes) {
  std::vector<Pass> out;
  for (const Pass& pass : passes) {
    for (std::size_t k = 1; k < pass.path.size(); ++k) {
      const Point d = pass.path[k] - pass.path[k - 1];
      if (!(length(d) > 0.0)) continue;
      Pass piece = pass;
      piece.path = {pass.path[k - 1], pass.path[k]};
      piece.setting = pass.setting * kHeadingBins + heading_bin((1.0 / length(d)) * d);
      out.push_back(std::move(piece));
    }
  }
  return out;
}

predict::PredictionRequest border_request(const predict::PredictionRequest& field, const predict::EdgeSetting& s,
                                          int edge_side) {
  predict::PredictionRequest r = field;
  const int field_side = 1 - edge_side;
  r.disc_rpm[edge_side] = s.disc.rpm;
  r.disc_drop_point_turn_rad[edge_side] = s.disc.drop_point_turn_rad;
  const predict::DiscSetting field_disc = predict::disc_setting(field, field_side);
  r.disc_rpm[field_side] = field_disc.rpm;
  r.disc_drop_point_turn_rad[field_side] =
      std::isnan(s.field_side_drop_point_turn_rad) ? field_disc.drop_point_turn_rad : s.field_side_drop_point_turn_rad;
  r.rpm = 0.0;
  r.drop_point_turn_rad = 0.0;
  return r;
}

// One setting's stamp at one wind in the machine frame; with border, the right (edge-side) disc metering
// edge_flow_fraction of its normal flow.
StampPattern stamp_at(predict::Predictor& predictor, predict::PredictionRequest request, Point wind_machine,
                      bool border, double edge_flow_fraction, double cell_m) {
  request.wind_x_m_s = wind_machine.x_m;
  request.wind_y_m_s = wind_machine.y_m;
  request.standard_errors = false;
  predict::Prediction p;
  const predict::PredictStatus status = predictor.predict(request, p);
  if (status != predict::PredictStatus::kOk) refuse_setting(std::string("the predictor refuses: ") + predict::to_string(status));
  if (!border) return stamp_pattern(p, cell_m);
  const int edge = predict::kRightDisc, field_side = predict::kLeftDisc;
  return combine_discs(stamp_pattern_of_disc(p, field_side, cell_m), disc_share(p, field_side),
                       stamp_pattern_of_disc(p, edge, cell_m), disc_share(p, edge), edge_flow_fraction);
}

}  // namespace

Point wind_in_machine_frame(Point forward, double wind_east_m_s, double wind_north_m_s) {
  const Point f = bin_forward(heading_bin(forward));
  const Point w{wind_east_m_s, wind_north_m_s};
  return {dot(w, {f.y_m, -f.x_m}), dot(w, f)};
}

MachineStamps machine_stamps(predict::Predictor& predictor, const predict::PredictionRequest& field,
                             std::vector<Pass> passes, const FieldConditions& conditions, double cell_m) {
  MachineStamps out;
  if (conditions.border) {
    predict::EdgeRequest edge;
    edge.kind = predict::EdgeKind::kBorder;
    edge.side = predict::kRightDisc;
    predict::PredictionRequest still = field;
    still.wind_x_m_s = still.wind_y_m_s = 0.0;
    const predict::EdgeResult found = predict::find_edge_setting(predictor, still, edge);
    if (found.status != predict::PredictStatus::kOk) {
      refuse_setting(std::string("no border setting: ") + predict::to_string(found.status));
    }
    out.border = found.setting;
    out.border_meets = found.profile.meets;
    out.predictions += found.predictions;
    for (Pass& pass : passes) pass.setting = pass.outermost ? 1 : 0;
  }
  const bool windy = conditions.wind_east_m_s != 0.0 || conditions.wind_north_m_s != 0.0;
  out.passes = windy ? pieces_by_heading(passes) : std::move(passes);
  const int settings = conditions.border ? 2 : 1;
  out.stamps.resize(static_cast<std::size_t>(windy ? settings * kHeadingBins : settings));
  std::map<int, bool> used;
  for (const Pass& pass : out.passes) used[pass.setting] = true;
  for (const auto& [index, _] : used) {
    const int base = windy ? index / kHeadingBins : index;
    const Point wind = windy ? wind_in_machine_frame(bin_forward(index % kHeadingBins), conditions.wind_east_m_s,
                                                     conditions.wind_north_m_s)
                             : Point{0.0, 0.0};
    const bool border = base == 1;
    const predict::PredictionRequest request = border ? border_request(field, *out.border, predict::kRightDisc) : field;
    out.stamps[static_cast<std::size_t>(index)] =
        stamp_at(predictor, request, wind, border, border ? out.border->flow_fraction : 1.0, cell_m);
    ++out.predictions;
  }
  // Settings no pass uses keep an empty stamp of the right cell size (the run checks sizes, not use).
  for (StampPattern& s : out.stamps) s.cell_m = cell_m;
  return out;
}

}  // namespace spread::field
