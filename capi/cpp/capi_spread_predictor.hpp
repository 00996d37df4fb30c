#pragma once
// SpreadPredictor over the C API (capi/include/spread/spread.h): a launch-table file opened once,
// each prediction one spread_predict() call (no allocation). Built only when target spreadc exists.
#include <string>
#include <string_view>
#include <vector>

#include "libspread/control/spread_predictor.hpp"

struct spread_tables;

namespace spread::firmware {

class CapiSpreadPredictor final : public SpreadPredictor {
 public:
  // Opens `table_path` read-only; throws std::runtime_error with the C API's status text.
  // cv_target_percent: CV target of the effective working width [%] (> 0).
  explicit CapiSpreadPredictor(const std::string& table_path, double cv_target_percent = 15.0);
  // Over a handle opened elsewhere (a command's table session, which reads the file once), borrowed: it must
  // outlive the predictor and is not closed by it. Throws as above when its materials cannot be listed.
  explicit CapiSpreadPredictor(spread_tables* borrowed, double cv_target_percent = 15.0);
  ~CapiSpreadPredictor() override;
  CapiSpreadPredictor(const CapiSpreadPredictor&) = delete;
  CapiSpreadPredictor& operator=(const CapiSpreadPredictor&) = delete;

  std::size_t material_count() const override { return names_.size(); }
  std::string_view material_name(std::size_t index) const override { return names_.at(index); }
  bool has_material(std::string_view material) const override;
  double cv_target_percent() const override { return cv_target_percent_; }
  RpmRange rpm_range(std::string_view material) const override;
  PredictionOutcome predict(std::string_view material, double rpm, double bout_width_m,
                            SpreadPrediction& out) override;
  // Through spread_find_edge_setting; the profile's trays averaged over each strip.
  PredictionOutcome narrow_side(const NarrowingRequest& request, std::span<const SideStrip> strips,
                                std::span<double> strip_rate_percent, SideNarrowing& out) override;
  // Through spread_compensate_wind.
  PredictionOutcome compensate_wind(std::string_view material, double rpm, double bout_width_m, double wind_x_m_s,
                                    double wind_y_m_s, std::array<SideNarrowing, 2>& out) override;

  const std::vector<std::string>& materials() const { return names_; }
  // Text of the last C API error (empty when none).
  const std::string& last_error() const { return last_error_; }

 private:
  int find(std::string_view material) const;  // index or -1
  void list_materials(const std::string& where);  // names_ and ranges_; closes an owned handle on failure

  spread_tables* tables_ = nullptr;
  bool owned_ = true;
  double cv_target_percent_;
  std::vector<std::string> names_;
  std::vector<RpmRange> ranges_;
  std::string last_error_;
  std::vector<double> profile_rate_percent_;  // narrow_side's tray rates (sized on first use)
};

}  // namespace spread::firmware
