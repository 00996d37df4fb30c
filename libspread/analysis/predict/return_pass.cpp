// The return pass of a to-and-fro field (predictor.hpp; docs/metrics.md "To-and-fro in wind"). To-and-fro
// drives every other pass the other way, so the machine meets the wind from the other side there: a wind
// (w_x, w_y) in the outgoing machine frame is (−w_x, −w_y) in the returning one. The field gets the return
// pass's pattern in its own frame laid down mirrored (metrics::cv_at_trays with a return pattern). Three
// cases, cheapest first:
//   - still air (or asked for: ReturnPassSettings::kOutgoingMirrored): the return pass is the outgoing
//     pattern, each bout mirror-symmetric (the tray test's rule);
//   - a lateral wind only (w_y = 0) on two discs whose settings on the way back are the outgoing ones
//     mirrored (alike discs that keep their settings, or discs that swap them): the machine is its own
//     mirror image (docs/design.md §3), so its pattern in the wind −w_x is its pattern in w_x mirrored, and
//     mirrored once more onto the field the return pass lies exactly where the outgoing one does — the
//     racetrack overlap, with no second flight;
//   - otherwise (a wind along the track, a one-disc machine, discs at settings of their own that they
//     keep): the return pass is landed and binned in its own wind and settings, before the outgoing pass
//     (whose landings the standard errors read), and put on the outgoing pass's trays.
#include <algorithm>
#include <span>

#include "libspread/analysis/predict/prediction_context.hpp"
#include "libspread/analysis/predict/predictor.hpp"

namespace spread::predict {

ReturnPass Predictor::return_pass_of(const Context& c) const {
  const double wind_x_m_s = c.air.wind_m_s.x(), wind_y_m_s = c.air.wind_m_s.y();
  const bool windy = (c.effects & flight::kWind) != 0 && (wind_x_m_s != 0.0 || wind_y_m_s != 0.0);
  if (!windy || c.request.return_pass == ReturnPassSettings::kOutgoingMirrored) return ReturnPass::kOutgoing;
  const bool swapped = c.request.return_pass == ReturnPassSettings::kSwapped;
  const bool mirror_settings = swapped || c.settings[kLeftDisc] == c.settings[kRightDisc];
  if (c.two_discs && wind_y_m_s == 0.0 && mirror_settings) return ReturnPass::kRacetrack;
  return ReturnPass::kFlown;
}

PredictStatus Predictor::fly_return_pass(Context& c) const {
  PredictionRequest back = c.request;
  back.wind_x_m_s = -c.request.wind_x_m_s;
  back.wind_y_m_s = -c.request.wind_y_m_s;
  if (c.two_discs) {
    const bool swapped = c.request.return_pass == ReturnPassSettings::kSwapped;
    const DiscSetting& left = c.settings[swapped ? kRightDisc : kLeftDisc];
    const DiscSetting& right = c.settings[swapped ? kLeftDisc : kRightDisc];
    back.rpm = 0.0;
    back.drop_point_turn_rad = 0.0;
    back.disc_rpm = {left.rpm, right.rpm};
    back.disc_drop_point_turn_rad = {left.drop_point_turn_rad, right.drop_point_turn_rad};
  }
  Context r{back, c.out, c.w};
  if (const PredictStatus s = check_request(r); s != PredictStatus::kOk) return s;
  land_discs(r);
  bin_transverse(r);
  const auto count = static_cast<std::size_t>(r.trays.tray_count);
  std::copy_n(c.w.tray_mass_.begin(), count, c.w.return_tray_mass_.begin());
  c.return_tray_count = r.trays.tray_count;
  c.return_flights = r.landed.flights;
  return PredictStatus::kOk;
}

namespace {

// A pattern on an even, centred layout of `from` trays moved onto the centred layout of `to` >= from trays
// of the same width (the layouts nest: both have their edges at whole tray widths from the centre line).
void widen_centred(std::span<double> trays, int from, int to) {
  const auto pad = static_cast<std::size_t>((to - from) / 2);
  std::copy_backward(trays.begin(), trays.begin() + from, trays.begin() + from + static_cast<std::ptrdiff_t>(pad));
  std::fill_n(trays.begin(), pad, 0.0);
  std::fill(trays.begin() + from + static_cast<std::ptrdiff_t>(pad), trays.begin() + to, 0.0);
}

}  // namespace

void Predictor::align_return_pass(Context& c) const {
  PredictorWorkspace& w = c.w;
  const auto outgoing = std::span(w.tray_mass_);
  if (c.return_pass == ReturnPass::kFlown) {
    // Both layouts are centred with an even count of trays of the request's width: the narrower one nests.
    const int t = std::max(c.trays.tray_count, c.return_tray_count);
    if (c.trays.tray_count < t) widen_centred(outgoing, c.trays.tray_count, t);
    if (c.return_tray_count < t) widen_centred(std::span(w.return_tray_mass_), c.return_tray_count, t);
    c.trays.tray_count = t;
    c.return_trays = std::span(w.return_tray_mass_).first(static_cast<std::size_t>(t));
    return;
  }
  const auto t = static_cast<std::size_t>(c.trays.tray_count);
  c.return_trays = outgoing.first(t);  // the outgoing pattern itself: the one-pattern metrics, bit for bit
  if (c.return_pass == ReturnPass::kRacetrack) {
    // What the answer shows as the return pass: the outgoing one mirrored (its CVs are the racetrack ones).
    std::reverse_copy(outgoing.begin(), outgoing.begin() + static_cast<std::ptrdiff_t>(t), w.return_tray_mass_.begin());
  }
}

}  // namespace spread::predict
