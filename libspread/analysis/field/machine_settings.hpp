#pragma once
// The discs' settings along a field's passes and the stamps they put down, from the predictor:
//   - the field's setting (the request) on every pass;
//   - border mode: the outermost pass at the border setting predict::find_edge_setting finds for the
//     edge on the driver's right (the side a headland round, driven counter-clockwise, has the boundary on), found once
//     in still air as a driver sets it once;
//   - a wind over the field (east and north components, m/s) is a different wind in the machine frame on
//     every heading: each pass is cut into its straight pieces, each piece given the nearest of
//     kHeadingBins headings, and each setting predicted at each heading used with the wind turned into the
//     machine frame (x to the right: (f_y, −f_x) for the heading's unit vector f; y forward: f).
#include <optional>
#include <vector>

#include "libspread/analysis/field/pass.hpp"
#include "libspread/analysis/field/stamp_pattern.hpp"
#include "libspread/analysis/predict/edge_spreading.hpp"

namespace spread::field {

inline constexpr int kHeadingBins = 16;  // 22.5° apart: a wind's cross and along components within 20 % of its speed

// A wind over the field (east, north; m/s) in the machine frame of a machine heading along the unit vector
// `forward` (east, north), the heading taken to the nearest of kHeadingBins: (x to the right, y forward).
Point wind_in_machine_frame(Point forward, double wind_east_m_s, double wind_north_m_s);

struct FieldConditions {
  double wind_east_m_s = 0.0;
  double wind_north_m_s = 0.0;
  bool border = false;        // border mode on the outermost pass
};

struct MachineStamps {
  std::vector<Pass> passes;            // with Pass::setting indexing `stamps`
  std::vector<StampPattern> stamps;
  std::optional<predict::EdgeSetting> border;  // the border setting, when asked
  bool border_meets = false;           // whether it meets the border thresholds (predict::EdgeProfile::meets)
  int predictions = 0;
};

// Throws spread::Error (kArgument, "field setting") naming the refusal when the predictor refuses a request
// (the status and, for the border search, that it found no setting).
MachineStamps machine_stamps(predict::Predictor& predictor, const predict::PredictionRequest& field,
                             std::vector<Pass> passes, const FieldConditions& conditions, double cell_m);

}  // namespace spread::field
