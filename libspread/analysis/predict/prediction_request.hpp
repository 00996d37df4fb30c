#pragma once
// What a prediction is asked: the request (material, each disc's speed and drop point, disc height, wind,
// effects, bout and trays), why one is refused (PredictStatus, RequestProblem) and the bounds a Predictor
// holds requests to (PredictorLimits). Predictor::request_problem and the request-check stage
// (request_check.cpp) apply them.
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string_view>

#include "libspread/physics/flight/flight.hpp"

namespace spread::predict {

// Why a request was refused. kOk = success. (Not exceptions: the C API maps these without unwinding,
// and a refused request must not allocate either.)
enum class PredictStatus : std::uint8_t {
  kOk,
  kNotFinite,          // a NaN/Inf in rpm, height, wind, CV target, bout or tray width
  kOutOfRange,         // height < 0 (or disc below the ground) or > max_disc_height_m, |drop point turn| > π
                       // (either disc's), |wind| component > max_wind_m_s, CV target <= 0 or > max_cv_target,
                       // bout width < 0 or > max_bout_width_m, tray width outside [min_tray_width_m,
                       // max_half_extent_m], a right-disc setting on a one-disc machine, rpm or
                       // drop_point_turn_rad not 0 while both discs' own are given
  kUnknownEffect,      // bits outside flight::kAllEffects | kTableEffects
  kUnknownMaterial,
  kRpmOutsideTable,    // rpm (or a disc's own rpm) outside the material's rows
  kOutsideDomain,      // PredictorLimits::refuse_outside_domain and a request the landing grid does not
                       // cover (landing_domain_miss) without fly_outside_domain
};
const char* to_string(PredictStatus status);

// The request field a refusal is about (Predictor::request_problem), as PredictionRequest names them.
enum class RequestField : std::uint8_t {
  kNone, kRpm, kDiscHeight, kWindX, kWindY, kCvTarget, kBoutWidth, kTrayWidth, kKernelHalfWidth, kDropPointTurn,
  kLeftDiscRpm, kRightDiscRpm, kLeftDiscDropPointTurn, kRightDiscDropPointTurn, kEffects
};
// The first field of a request that validation refuses: its value and the range it must lie in (the
// field's own units; cv_target a fraction), or, with lower == upper, the rule it breaks as a phrase that
// follows the value ("given while every disc has its own speed (set it to 0)"); rule "above" marks a
// range open below.
struct RequestProblem {
  PredictStatus status = PredictStatus::kOk;
  RequestField field = RequestField::kNone;
  double value = 0.0, lower = 0.0, upper = 0.0;
  const char* rule = "";
};

inline constexpr flight::EffectSet kTableEffects = 1u << 31;

// The discs' settings on the return pass of a to-and-fro field. The return pass is driven the other way,
// so it meets the wind from the other side: the wind (w_x, w_y) of the way out is (−w_x, −w_y) in the
// machine's own frame on the way back.
enum class ReturnPassSettings : std::uint8_t {
  kSame,     // each disc keeps its setting (a machine set once for the field)
  kSwapped,  // the discs swap settings (a controller that compensates the wind for each heading)
  // The tray test's rule whatever the wind: the outgoing pattern mirrored (a search that reads only the
  // landings, or a comparison with a tray test driven in wind).
  kOutgoingMirrored,
};

struct PredictionRequest {
  std::string_view material;
  double rpm = 0.0;                                              // r/min
  double disc_height_m = std::numeric_limits<double>::quiet_NaN();  // NaN: the machine's stored height
  double wind_x_m_s = 0.0;                                       // lateral wind (used with kWind)
  double wind_y_m_s = 0.0;                                       // wind along the driving direction
  double cv_target = 0.15;                                       // fraction (0.15 = 15 %)
  // flight::Effect bits, or kTableEffects: the flight effects the table was built with (each run records
  // them), plus any bits given beside it. With kTableEffects a non-zero wind adds flight::kWind: the wind
  // is a condition of the day, not of the machine.
  flight::EffectSet effects = kTableEffects;
  double bout_width_m = 0.0;                                     // 0: at the to-and-fro working width
  double tray_width_m = 0.5;
  // Half-width h (m) of the Epanechnikov kernel each landing's mass is spread over
  // (metrics::accumulate_transverse_kernel). NaN: the automatic rule (kernel_half_width_for); 0: each
  // landing falls into one tray as a point mass.
  double kernel_half_width_m = std::numeric_limits<double>::quiet_NaN();
  // The drop point (feed position on the disc) turned from the table's by this angle (rad) about the disc
  // axis, counter-clockwise seen from above for the left disc, mirrored for the right (both discs set
  // alike, as a twin-disc spreader's mirrored scales are); within [−π, π].
  double drop_point_turn_rad = 0.0;
  // Each disc's own setting (kLeftDisc, kRightDisc as the driver sees them), NaN: the both-discs value above.
  // A disc turned by its own drop point turns as drop_point_turn_rad does for it (mirrored on the right).
  // When both discs' rpm are given `rpm` is unused and must be 0, and likewise drop_point_turn_rad
  // (a value that would be dropped is refused). A one-disc machine has only kLeftDisc.
  std::array<double, 2> disc_rpm = {std::numeric_limits<double>::quiet_NaN(),
                                    std::numeric_limits<double>::quiet_NaN()};
  std::array<double, 2> disc_drop_point_turn_rad = {std::numeric_limits<double>::quiet_NaN(),
                                                    std::numeric_limits<double>::quiet_NaN()};
  // Opt-in for a Predictor that refuses requests outside its landing grid's domain
  // (PredictorLimits::refuse_outside_domain): fly every launch sample instead, at the cost of one flight
  // per sample and disc (tens of milliseconds; docs/c-api.md "Landing grid").
  bool fly_outside_domain = false;
  // The to-and-fro figures in wind come from the outgoing pass and the return pass
  // (metrics::cv_at_trays with a return pattern): see ReturnPassSettings.
  ReturnPassSettings return_pass = ReturnPassSettings::kSame;
  // False: no standard errors (all NaN) — for a search that compares many settings, at about half the
  // cost. The headline rule then takes a band as established when its lowest CV meets the target, with
  // no confidence test.
  bool standard_errors = true;
  // With standard errors, between DEM rows: include the interpolation's own error (interpolation_error.hpp:
  // the answer's trays binned again from each row's granules alone). False: the launch samples' error
  // alone.
  bool interpolation_error = true;
};
inline constexpr int kLeftDisc = 0, kRightDisc = 1;

// Drop-point turns (rad), [low_rad, high_rad] with low_rad <= 0 <= high_rad.
struct TurnRange {
  double low_rad = 0.0, high_rad = 0.0;
  bool contains(double turn_rad) const { return turn_rad >= low_rad - 1e-12 && turn_rad <= high_rad + 1e-12; }
};

// The speed (r/min) and drop-point turn (rad) disc `disc` runs at under this request.
struct DiscSetting {
  double rpm = 0.0;
  double drop_point_turn_rad = 0.0;
  bool operator==(const DiscSetting&) const = default;
};
DiscSetting disc_setting(const PredictionRequest& request, int disc);

struct PredictorLimits {
  double max_half_extent_m = 100.0;  // trays cover at most [-100 m, 100 m]; landings beyond are "lost"
  double min_tray_width_m = 0.05;
  // Upper bounds of the request fields (kOutOfRange above them). Far beyond any spreader, but they keep
  // a finite yet absurd value (a bout width of 3.6e59 m) out of the metrics and flight code.
  double max_bout_width_m = 1000.0;   // m
  double max_disc_height_m = 100.0;   // m above the ground
  double max_wind_m_s = 100.0;        // each wind component, absolute value
  double max_cv_target = 10.0;        // fraction (1000 %)
  double max_kernel_half_width_m = 10.0;  // m
  // Requests outside the landing grid's domain (another height or wind than it covers, effects beyond the
  // table's drag) are refused with kOutsideDomain unless they opt in (fly_outside_domain): a controller's
  // time is then bounded by the grid's cost. False: they fly every launch sample (tools, studies).
  // Tables without a landing grid (runs that fly more than drag) fly every request.
  bool refuse_outside_domain = false;
};

}  // namespace spread::predict
