// spread predict --tables FILE --material NAME --rpm N [--height M] [--wind VX,VY] [--cv-target PCT]
//                [--width W] [--tray-width W] [--effects LIST] [--repeat K] [--size-classes] [--json]
// Goes through the C API (spread.h) on purpose: the CLI is the C API's first user (dogfooding), so what
// it prints is what an integrator gets. Bad input → a message naming it on stderr and exit code 2.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "libspread/core/error.hpp"
#include "libspread/physics/flight/flight.hpp"
#include "libspread/analysis/metrics/metrics.hpp"
#include "spread/spread.h"
#include "tools/spread/chart_json.hpp"
#include "tools/spread/command_registry.hpp"
#include "tools/spread/prediction_args.hpp"
#include "tools/spread/report_args.hpp"
#include "tools/spread/setting_guidance.hpp"
#include "tools/spread/blend_output.hpp"
#include "tools/spread/size_class_output.hpp"
#include "tools/spread/table_session.hpp"
#include "tools/spread/verdicts.hpp"
#include "tools/spread/next_steps.hpp"
#include "tools/spread/number_format.hpp"
#include "libspread/analysis/plot/report_pdf.hpp"
#include "libspread/analysis/predict/width_stability.hpp"

namespace spread::cli::cmd_predict {
namespace {

using nlohmann::json;
using spread::cli::BadInput;

struct Options : spread::cli::PredictionArgs {
  double bout_width_m = 0.0;
  std::string effects = "table";
  double kernel_half_width_m = std::numeric_limits<double>::quiet_NaN();
  int repeat = 0;
  int stability = 0;
  bool compensate_wind = false;
  bool fly_outside_domain = false;
  bool size_classes = false;
  std::string size_class_mm;  // class boundaries (mm); given: --size-classes
  std::string size_class_png;  // the fine and coarse halves' patterns; given: --size-classes
  bool json = false;
  spread::cli::ReportArgs report;
};

std::uint32_t parse_effects(const std::string& text) {
  if (text == "table") return SPREAD_EFFECTS_AS_TABLE;
  if (text == "all") return SPREAD_EFFECT_ALL;
  try {
    return spread::flight::parse_effects(text);
  } catch (const std::invalid_argument& e) {
    throw BadInput(std::string("--effects: ") + e.what());
  }
}

// The request the Predictor (the C API's own engine) gets beside the C API's: the options' setting, bout,
// kernel, effects (the table's, or the bits the C API gets) and the opt-in to fly outside the grid's domain.
spread::predict::PredictionRequest predictor_request(const Options& o) {
  spread::predict::PredictionRequest request = spread::cli::prediction_request(o);
  request.bout_width_m = o.bout_width_m;
  request.kernel_half_width_m = o.kernel_half_width_m;
  request.effects = o.effects == "table" ? spread::predict::kTableEffects : parse_effects(o.effects);
  request.fly_outside_domain = o.fly_outside_domain;
  return request;
}

// An explanation of a refused prediction that names the input and the allowed values.
std::string explain(spread_status status, const Options& o, spread_tables* tables) {
  std::ostringstream out;
  int32_t count = 0;
  spread_material_count(tables, &count);
  switch (status) {
    case SPREAD_ERROR_UNKNOWN_MATERIAL: {
      out << "--material '" << o.material << "' is not in " << o.tables << "; materials:";
      for (int32_t i = 0; i < count; ++i) {
        const char* name = nullptr;
        if (spread_material_name(tables, i, &name) == SPREAD_OK) out << " " << name;
      }
      return out.str();
    }
    case SPREAD_ERROR_RPM_OUTSIDE_TABLE:
      for (int32_t i = 0; i < count; ++i) {
        const char* name = nullptr;
        double lo = 0, hi = 0;
        if (spread_material_name(tables, i, &name) == SPREAD_OK && o.material == name &&
            spread_material_rpm_range(tables, i, &lo, &hi) == SPREAD_OK) {
          out << spread::cli::disc_speed_outside(o, lo, hi) << " is outside the table rows of '" << o.material
              << "' [" << lo << ", " << hi << "] rpm";
        }
      }
      return out.str();
    case SPREAD_ERROR_NOT_FINITE: return "an argument is not finite (NaN or Inf) in --rpm/--height/--wind/--cv-target/--width/--tray-width";
    case SPREAD_ERROR_OUT_OF_RANGE:
      return "out of range: --height must be >= 0, --cv-target > 0, --width >= 0, --tray-width in [0.1, 100] m (" +
             std::string(spread_last_error_detail()) + ")";
    case SPREAD_ERROR_OUTSIDE_DOMAIN: {
      // The C API names the quantity and the covered range; its opt-in is this command's flag.
      std::string detail = spread_last_error_detail();
      const std::size_t opt_in = detail.find(" (set fly_outside_domain");
      if (opt_in != std::string::npos) detail.erase(opt_in);
      if (detail.rfind("spread_predict: ", 0) == 0) detail.erase(0, 16);
      // The definition's field names as this command's options.
      for (const auto& [field, option] : {std::pair<std::string, std::string>{"disc_height_m ", "--height "},
                                          {"wind_m_s ", "--wind "}, {"effects ", "--effects "}}) {
        if (detail.rfind(field, 0) == 0) detail.replace(0, field.size(), option);
      }
      return detail + "; --fly-outside-domain flies every launch sample instead (tens of ms)";
    }
    default: return spread_status_str(status);
  }
}

// A refused call as the CLI's failures are (error_exit.hpp, mapped once in main): the table file could not
// be read, or memory or the library failed — a failure; anything else is the user's input.
[[noreturn]] void throw_status(spread_status status, const std::string& message) {
  if (status == SPREAD_ERROR_IO) throw spread::Error(spread::ErrorKind::kIo, {}, message);
  if (status == SPREAD_ERROR_OUT_OF_MEMORY || status == SPREAD_ERROR_INTERNAL) throw std::runtime_error(message);
  throw BadInput(message);
}

std::string effects_label(std::uint32_t effects) {
  const std::string names = spread::flight::effects_to_string(effects);
  return names.empty() ? "none (gravity only)" : names;
}

// Below this many launch samples per prediction the sampling study (docs/metrics.md "Uncertainty")
// found the working width bimodal and the delta-method standard error three times too small.
constexpr std::int32_t kFewSamples = 1000;

json number_or_null(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

// " ± x" with the 95 % half-interval of a standard error, or nothing when it is undefined.
std::string plus_minus(double standard_error) {
  if (!std::isfinite(standard_error)) return "";
  std::ostringstream out;
  out << std::fixed << std::setprecision(2) << " ± " << 1.96 * standard_error;
  return out.str();
}

// CV(W) at every whole-tray width from two trays to the layout, both overlaps (fractions), on the trays
// the C API returned (libspread's metrics: the same overlap code the prediction used). The JSON's
// cv_curve and the report's table are both read off it.
struct CvCurve {
  std::vector<double> widths_m, to_and_fro, racetrack;
};

// The return pass of a to-and-fro field in wind (docs/metrics.md "To-and-fro in wind"): it meets the wind
// from the other side, so its pattern is not the outgoing one mirrored. The C API's answer already reads
// its figures so; the curve needs the pattern itself, from the Predictor (the C API's own engine) on the
// same request: the present setting kept on the return pass, or the compensated one swapped.
struct ReturnPassInWind {
  spread::predict::ReturnPass read_as = spread::predict::ReturnPass::kOutgoing;
  std::vector<double> trays;  // on the C API's trays; empty: the outgoing pattern
};

ReturnPassInWind return_pass_in_wind(const Options& o, const spread_prediction& r, spread::cli::TableSession& session) {
  spread::predict::PredictionRequest request = predictor_request(o);
  if (request.wind_x_m_s == 0.0 && request.wind_y_m_s == 0.0) return {};
  request.standard_errors = false;
  if (o.compensate_wind) {
    request.rpm = 0.0;
    request.drop_point_turn_rad = 0.0;
    request.disc_rpm = {r.disc_rpm[0], r.disc_rpm[1]};
    request.disc_drop_point_turn_rad = {r.disc_drop_point_turn_rad[0], r.disc_drop_point_turn_rad[1]};
    request.return_pass = spread::predict::ReturnPassSettings::kSwapped;
  }
  spread::predict::Prediction p;
  if (session.predictor().predict(request, p) != spread::predict::PredictStatus::kOk ||
      p.trays.tray_count != r.tray_count) {
    return {};
  }
  ReturnPassInWind back;
  back.read_as = p.return_pass;
  if (p.return_pass != spread::predict::ReturnPass::kOutgoing) back.trays.assign(p.return_tray_mass_fraction.begin(), p.return_tray_mass_fraction.end());
  return back;
}

CvCurve cv_curve_of(const spread_prediction& r, const std::vector<double>& trays, const ReturnPassInWind& back) {
  spread::metrics::TrayLayout layout;
  layout.tray_width_m = r.tray_width_m;
  layout.tray_count = r.tray_count;
  const std::span<const double> mass(trays.data(), static_cast<std::size_t>(r.tray_count));
  const std::span<const double> return_mass = back.trays.empty() ? mass : std::span<const double>(back.trays);
  CvCurve curve;
  for (int n = 2; n <= r.tray_count; ++n) {
    curve.widths_m.push_back(n * r.tray_width_m);
    curve.to_and_fro.push_back(spread::metrics::cv_at_trays(mass, return_mass, layout, n, {}));
    curve.racetrack.push_back(spread::metrics::cv_at_trays(mass, layout, n, spread::metrics::Overlap::kRacetrack));
  }
  return curve;
}

// One point per whole-tray bout width, named as the scalars at --width are (and as `calibrate tray`
// writes its curve).
json cv_curve_json(const CvCurve& c) {
  json curve = json::array();
  for (std::size_t i = 0; i < c.widths_m.size(); ++i) {
    curve.push_back({{"bout_width_m", c.widths_m[i]},
                     {"cv_to_and_fro_percent", number_or_null(100.0 * c.to_and_fro[i])},
                     {"cv_racetrack_percent", number_or_null(100.0 * c.racetrack[i])}});
  }
  return curve;
}

// Every band of bout widths within the target, as the C API reports them (docs/metrics.md "Effective
// working width"); `headline` marks the working width's band.
json bands_json(const spread_band* bands, int count, int headline) {
  json out = json::array();
  for (int b = 0; b < std::min(count, SPREAD_MAX_BANDS); ++b) {
    const spread_band& band = bands[b];
    out.push_back({{"lower_m", band.lower_m},
                   {"upper_m", band.upper_m},
                   {"upper_se_m", number_or_null(band.upper_se_m)},
                   {"bout_width_m", band.bout_width_m},
                   {"cv_percent", number_or_null(band.cv_percent)},
                   {"cv_se_percent", number_or_null(band.cv_se_percent)},
                   {"lowest_cv_percent", number_or_null(band.lowest_cv_percent)},
                   {"lowest_cv_se_percent", number_or_null(band.lowest_cv_se_percent)},
                   {"lowest_cv_bout_width_m", band.lowest_cv_bout_width_m},
                   {"established", band.established != 0},
                   {"limited_by_layout", band.limited_by_layout != 0},
                   {"headline", b == headline}});
  }
  return out;
}

bool own_disc_settings(const Options& o) {
  for (int d = 0; d < 2; ++d) {
    if (!std::isnan(o.disc_rpm[d]) || !std::isnan(o.disc_drop_point_turn_deg[d])) return true;
  }
  return false;
}

// "600 rpm", or with the discs at their own settings "600 / 650 rpm (left / right), drop point +10 / 0°".
std::string setting_label(const Options& o, const spread_prediction& r) {
  if (!own_disc_settings(o)) return format("%.2f rpm", o.rpm);
  return format("%.2f", r.disc_rpm[0]) + " / " + format("%.2f rpm (left / right)", r.disc_rpm[1]) +
         format(", drop point turned %+.1f", r.disc_drop_point_turn_rad[0] / spread::cli::kRadPerDeg) +
         format(" / %+.1f deg", r.disc_drop_point_turn_rad[1] / spread::cli::kRadPerDeg);
}

// The guidance when the CV at --width is above the target (setting_guidance.hpp): the same table and
// conditions through the Predictor, the C API's own engine.
spread::cli::SettingGuidance guidance_for(const Options& o, const spread_prediction& r, spread::cli::TableSession& session) {
  if (!(o.bout_width_m > 0.0) || !(r.cv_percent > o.cv_target_percent)) return {};
  if (o.compensate_wind) return {};  // the setting shown is the search's already
  if (own_disc_settings(o)) {
    spread::cli::SettingGuidance note;
    note.lines.push_back("setting guidance turns both discs alike: `spread chart` finds the best setting at this width");
    return note;
  }
  return spread::cli::setting_guidance(session.predictor(), predictor_request(o));
}

// The predicted CV at the bout width against the target with its 95 % interval over the launch samples
// (1.96 standard errors, as the text prints it): the rule of every report (calibration/cv_verdict.hpp).
// None without a bout width.
std::vector<spread::cli::Verdict> prediction_verdicts(const Options& o, const spread_prediction& r) {
  if (!(r.bout_width_m > 0.0)) return {};
  const double cv = r.cv_percent / 100.0, half = 1.96 * r.cv_se_percent / 100.0;
  const bool interval = std::isfinite(half);
  spread::cli::Verdict v = spread::cli::cv_verdict(
      "predicted CV at the " + format("%.2f m", r.bout_width_m) + " bout, to-and-fro",
      spread::calibration::cv_verdict(cv, interval ? std::max(0.0, cv - half) : NAN, interval ? cv + half : NAN,
                                      o.cv_target_percent / 100.0));
  v.numbers["bout_width_m"] = r.bout_width_m;
  return {v};
}

// The report's pattern page of a prediction: the trays as shares of the discharged mass, the CVs with
// their 95 % intervals.
spread::plot::PatternReport report_page(const Options& o, const std::string& machine_name, const spread_prediction& r,
                                        const std::vector<double>& trays,
                                        const CvCurve& curve, std::int64_t time_s,
                                        const spread::cli::SettingGuidance& guidance,
                                        const std::vector<spread::cli::Verdict>& verdicts) {
    spread::plot::PatternReport page;
    page.header.title = "Spread pattern report: prediction";
    page.header.source = o.tables;
    page.header.machine = machine_name;
    page.header.material = o.material;
    page.header.rpm = o.rpm;
    if (own_disc_settings(o)) page.header.rpm_text = setting_label(o, r);
    page.header.speed_km_h = o.report.speed_km_h;
    page.header.time_s = time_s;
    page.header.made_by = spread::cli::command_line();
    page.summary.push_back(std::to_string(r.sample_count) + " simulated granules, disc " +
                           format("%.2f m", r.disc_height_m) + " above ground, in the air: " +
                           effects_label(r.effects) + format(", throw width %.1f m", r.throw_width_m) +
                           plus_minus(r.throw_width_se_m));
    if (r.bout_width_m > 0.0) {
      page.summary.push_back("at W = " + format("%.2f m", r.bout_width_m) + ": CV " + format("%.1f %%", r.cv_percent) +
                             plus_minus(r.cv_se_percent) + " to-and-fro, " + format("%.1f %%", r.cv_racetrack_percent) +
                             plus_minus(r.cv_racetrack_se_percent) + " racetrack (± = 95 % interval over the simulated granules)");
    }
    // Every band, and which is the working width (the headline rule, docs/metrics.md "Effective working
    // width"): the same as the text and JSON outputs. A note under the chart.
    std::string bands_note;
    if (r.band_count_to_and_fro > 0) {
      std::string bands = "bands of bout widths within the target (to-and-fro):";
      for (int b = 0; b < std::min(r.band_count_to_and_fro, SPREAD_MAX_BANDS); ++b) {
        const spread_band& band = r.bands_to_and_fro[b];
        bands += (b ? "; " : " ") + format("%.2f", band.lower_m) + format("-%.2f m", band.upper_m) + " (CV " +
                 format("%.1f %%", band.cv_percent) + plus_minus(band.cv_se_percent) + " at " +
                 format("%.2f m", band.bout_width_m) + ")";
        if (b == r.headline_band_to_and_fro) bands += " = working width";
        if (!band.established) bands += " [not established]";
      }
      bands_note = bands + "; the working width is the widest band whose lowest CV meets the target at 95 % confidence";
    }
    page.tray_mass_kg.assign(trays.begin(), trays.begin() + r.tray_count);
    page.trays.tray_width_m = r.tray_width_m;
    page.trays.tray_count = r.tray_count;
    page.chart.units = spread::plot::MassUnits::kFraction;
    page.chart.series_label = "predicted";
    page.chart.bout_width_m = r.bout_width_m;
    page.chart.bout_cv = r.cv_percent / 100.0;
    page.chart_title = "prediction: the machine's trays across the driving direction";
    page.cv_target = o.cv_target_percent / 100.0;
    page.working_width_to_and_fro_m = r.working_width_to_and_fro_m;
    page.working_width_racetrack_m = r.working_width_racetrack_m;
    page.cv_table = spread::plot::cv_table(
        spread::plot::with_bout_width_m(spread::plot::cv_table_widths_m(r.throw_width_m, curve.widths_m),
                                        r.bout_width_m, curve.widths_m),
        curve.widths_m, curve.to_and_fro, curve.racetrack);
    page.verdicts = spread::cli::page_verdicts(verdicts);
    if (!bands_note.empty()) page.notes.push_back(bands_note);
    page.notes.push_back("a prediction from the launch table: shares of the mass the machine discharges; the rate "
                         "in kg/ha and its check need a tray test with the trays' catching area");
    for (const std::string& line : guidance.notes) page.notes.push_back(line);
    return page;
}

// ISO 565's R 20 main sieve series from 2 to 5 mm: the sizes a fertiliser's sieve analysis reports.
constexpr const char* kDefaultSizeClassMm = "2,2.5,3.15,4,5";

// --size-classes: each size class of the table's launch samples predicted alone at the bout just
// predicted (the same setting, effects and trays).
std::optional<spread::size_classes::SizeClassPatterns> size_classes_for(const Options& o, const spread_prediction& r,
                                                                         const spread::cli::TableSession& session) {
  if (!o.size_classes && o.size_class_mm.empty() && o.size_class_png.empty()) return std::nullopt;
  if (o.compensate_wind) throw BadInput("--size-classes: not with --compensate-wind (give the discs' own settings instead)");
  if (!(r.bout_width_m > 0.0)) throw BadInput("--size-classes: no bout width meets the target; give one with --width");
  const std::vector<double> boundaries =
      spread::cli::parse_size_class_boundaries_mm(o.size_class_mm.empty() ? kDefaultSizeClassMm : o.size_class_mm);
  spread::predict::PredictionRequest request = predictor_request(o);
  request.bout_width_m = r.bout_width_m;
  return spread::size_classes::size_class_patterns(session.contents(), request, boundaries);
}

// A blend's name: each component predicted from its row at the request, the blend evaluated at --width
// (or at the widest bout every component meets the target).
void run_blend(const Options& o, const spread::tables::Blend& blend, spread::cli::TableSession& session) {
  if (o.compensate_wind || o.size_classes || !o.report.path.empty() || o.stability > 0 || o.repeat > 0)
    throw BadInput("--material " + o.material + " is a blend: --compensate-wind, --size-classes, --report, --stability "
                   "and --repeat are for a single material (predict a component by its row, \"" +
                   blend.components.front().material + "\")");
  const spread::predict::PredictionRequest request = predictor_request(o);
  const spread::blends::BlendPatterns b = spread::blends::blend_patterns(session.predictor(), blend, request);
  if (b.status != spread::predict::PredictStatus::kOk)
    throw BadInput("blend " + blend.name + ": " + spread::predict::to_string(b.status));
  if (o.json) {
    std::cout << json{{"material", o.material}, {"rpm", o.rpm}, {"blend", spread::cli::blend_json(b, request.cv_target)}}.dump(2) << "\n";
    return;
  }
  spread::cli::print_blend(b, request.cv_target);
}

void run(const Options& o, int& exit_code) {
  const std::string report_problem = spread::cli::check_report_args(o.report);
  const std::int64_t report_time_s = o.report.path.empty() ? 0 : spread::cli::report_time_s();
  if (o.compensate_wind && !(o.bout_width_m > 0.0)) {
    throw BadInput("--compensate-wind needs --width (the bout width to compensate at, m)");
  }
  spread_prediction_def def = spread_prediction_def_default();
  def.material = o.material.c_str();
  def.rpm = o.rpm;
  def.disc_height_m = o.height_m;
  const auto wind = spread::cli::parse_wind(o.wind);
  def.wind_m_s[0] = wind.x_m_s;
  def.wind_m_s[1] = wind.y_m_s;
  def.cv_target_percent = o.cv_target_percent;
  def.bout_width_m = o.bout_width_m;
  def.tray_width_m = o.tray_width_m;
  def.effects = parse_effects(o.effects);
  def.kernel_half_width_m = o.kernel_half_width_m;
  def.drop_point_turn_rad = spread::cli::drop_point_turn_rad(o);
  def.fly_outside_domain = o.fly_outside_domain ? 1u : 0u;
  spread::cli::check_disc_settings(o);
  for (int d = 0; d < 2; ++d) {
    def.disc_rpm[d] = o.disc_rpm[d];
    def.disc_drop_point_turn_rad[d] = spread::cli::disc_drop_point_turn_rad(o, d);
  }

  // The table read once; the C API's handle over it (the guidance and --stability use the same contents).
  spread::cli::TableSession session(o.tables);
  if (const spread::tables::Blend* blend = session.contents().find_blend(o.material)) {
    run_blend(o, *blend, session);
    return;
  }
  spread_tables* const tables = session.capi();

  size_t capacity = 0;
  spread_status status = spread_transverse_bound(tables, def.tray_width_m, &capacity);
  std::vector<double> trays(status == SPREAD_OK ? capacity : 0);
  spread_prediction result{};
  if (status == SPREAD_OK) status = spread_predict(tables, &def, &result, trays.data(), trays.size());
  // --compensate-wind: the present setting's CV in this wind, then the prediction at the compensated setting.
  const double present_cv_percent = result.cv_percent, present_cv_se_percent = result.cv_se_percent;
  const auto predict_once = [&] {
    return o.compensate_wind ? spread_compensate_wind(tables, &def, &result, trays.data(), trays.size())
                             : spread_predict(tables, &def, &result, trays.data(), trays.size());
  };
  if (status == SPREAD_OK && o.compensate_wind) status = predict_once();
  if (status != SPREAD_OK) throw_status(status, explain(status, o, tables));

  // --repeat K: the median wall time of K further predictions (the first, above, warmed the caches).
  double median_us = std::numeric_limits<double>::quiet_NaN();
  if (o.repeat > 0) {
    std::vector<double> times_us(static_cast<std::size_t>(o.repeat));
    for (double& t : times_us) {
      const auto start = std::chrono::steady_clock::now();
      predict_once();
      t = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
    }
    std::sort(times_us.begin(), times_us.end());
    const std::size_t n = times_us.size();
    median_us = n % 2 == 1 ? times_us[n / 2] : 0.5 * (times_us[n / 2 - 1] + times_us[n / 2]);
  }

  // --stability N: the headline under N bootstrap resamples of the table's launch samples.
  std::optional<spread::predict::WidthStability> stability;
  if (o.stability > 0) {
    stability = spread::predict::width_stability(session.contents(), predictor_request(o), o.stability);
  }

  const std::optional<spread::size_classes::SizeClassPatterns> classes = size_classes_for(o, result, session);
  if (classes && !o.size_class_png.empty()) spread::cli::write_size_halves_png(*classes, o.size_class_png);

  const auto tray_count = static_cast<std::size_t>(result.tray_count);
  const ReturnPassInWind return_pass = return_pass_in_wind(o, result, session);
  const CvCurve curve = cv_curve_of(result, trays, return_pass);
  const spread::cli::SettingGuidance guidance = guidance_for(o, result, session);
  const std::vector<spread::cli::Verdict> verdicts = prediction_verdicts(o, result);
  const std::vector<spread::cli::NextStep> steps =
      spread::cli::predict_next_steps(verdicts, o.tables, o.material, o.bout_width_m);
  // The page, made whether or not it is written: --json gives its chart's numbers too.
  spread::plot::PatternReport page = report_page(o, session.machine().name, result, trays, curve, report_time_s, guidance, verdicts);
  for (const std::string& n : spread::cli::next_steps_notes(steps)) page.notes.push_back(n);
  std::string report_error;
  if (!o.report.path.empty() && report_problem.empty()) {
    try {
      spread::plot::write_report_pdf(o.report.path, &page);
    } catch (const std::exception& e) {
      report_error = e.what();
    }
  }
  if (o.json) {
    json centres = json::array(), fractions = json::array();
    for (std::size_t k = 0; k < tray_count; ++k) {
      centres.push_back(result.tray_left_edge_m + (static_cast<double>(k) + 0.5) * result.tray_width_m);
      fractions.push_back(trays[k]);
    }
    json out = {{"tables", o.tables},
                {"material", o.material},
                {"rpm", o.rpm},
                {"disc_height_m", result.disc_height_m},
                {"wind_m_s", {def.wind_m_s[0], def.wind_m_s[1]}},
                {"drop_point_turn_deg", o.drop_point_turn_deg},
                {"discs", {{{"disc", "left"},
                            {"rpm", result.disc_rpm[0]},
                            {"drop_point_turn_deg", result.disc_drop_point_turn_rad[0] / spread::cli::kRadPerDeg}},
                           {{"disc", "right"},
                            {"rpm", number_or_null(result.disc_rpm[1])},
                            {"drop_point_turn_deg",
                             number_or_null(result.disc_drop_point_turn_rad[1] / spread::cli::kRadPerDeg)}}}},
                {"effects", spread::effect::names_in(result.effects)},
                {"cv_target_percent", o.cv_target_percent},
                {"throw_width_m", result.throw_width_m},
                {"throw_width_se_m", number_or_null(result.throw_width_se_m)},
                {"working_width_to_and_fro_m", result.working_width_to_and_fro_m},
                {"working_width_racetrack_m", result.working_width_racetrack_m},
                {"working_width_to_and_fro_se_m", number_or_null(result.working_width_to_and_fro_se_m)},
                {"working_width_racetrack_se_m", number_or_null(result.working_width_racetrack_se_m)},
                {"cv_target_crossings", {{"to_and_fro", result.cv_crossings_to_and_fro},
                                         {"racetrack", result.cv_crossings_racetrack}}},
                {"bout_width_m", result.bout_width_m},
                {"cv_to_and_fro_percent", number_or_null(result.cv_percent)},
                {"cv_to_and_fro_se_percent", number_or_null(result.cv_se_percent)},
                {"cv_racetrack_percent", number_or_null(result.cv_racetrack_percent)},
                {"cv_racetrack_se_percent", number_or_null(result.cv_racetrack_se_percent)},
                {"mean_radius_m", result.mean_radius_m},
                {"radial_width_m", result.radial_width_m},
                {"lost_mass_fraction", result.lost_mass_fraction},
                {"flights", result.flights},
                {"sample_count", result.sample_count},
                {"kernel_half_width_m", result.kernel_half_width_m},
                {"transverse", {{"tray_width_m", result.tray_width_m},
                                {"centres_m", centres},
                                {"mass_fraction", fractions}}},
                {"cv_curve", cv_curve_json(curve)},
                {"bands", {{"to_and_fro", bands_json(result.bands_to_and_fro, result.band_count_to_and_fro,
                                                     result.headline_band_to_and_fro)},
                           {"racetrack", bands_json(result.bands_racetrack, result.band_count_racetrack,
                                                    result.headline_band_racetrack)}}},
                {"band_count", {{"to_and_fro", result.band_count_to_and_fro},
                                {"racetrack", result.band_count_racetrack}}},
                {"first_band_width_m", {{"to_and_fro", result.first_band_width_to_and_fro_m},
                                        {"racetrack", result.first_band_width_racetrack_m}}}};
    out["adjustments"] = spread::cli::setting_guidance_json(guidance);
    out["adjusted_from"] = spread::cli::setting_guidance_present_json(guidance);
    out["verdicts"] = spread::cli::verdicts_json(verdicts);
    out["chart"] = spread::cli::chart_json(page);
    out["next_steps"] = spread::cli::next_steps_json(steps);
    if (!std::isnan(o.report.speed_km_h)) out["speed_km_h"] = o.report.speed_km_h;
    if (o.compensate_wind) {
      out["wind_compensation"] = {{"present_cv_to_and_fro_percent", number_or_null(present_cv_percent)},
                                  {"present_cv_to_and_fro_se_percent", number_or_null(present_cv_se_percent)},
                                  {"meets_target", result.cv_percent <= o.cv_target_percent},
                                  {"return_pass", "discs swap settings"}};
    }
    if (return_pass.read_as != spread::predict::ReturnPass::kOutgoing) {
      out["to_and_fro_return_pass"] = return_pass.read_as == spread::predict::ReturnPass::kRacetrack ? "as racetrack" : "flown";
    }
    if (stability) {
      out["width_stability"] = {{"resamples", stability->resamples},
                                {"outside_interval_percent", 100.0 * stability->outside_interval_fraction},
                                {"beyond_1m_percent", 100.0 * stability->beyond_1m_fraction},
                                {"quantile_2_5_m", stability->quantile_025_m},
                                {"quantile_97_5_m", stability->quantile_975_m},
                                {"lowest_m", stability->lowest_m},
                                {"highest_m", stability->highest_m}};
    }
    if (classes) out["size_classes"] = spread::cli::size_classes_json(*classes);
    if (o.repeat > 0) {
      out["repeat"] = o.repeat;
      out["time_per_prediction_us"] = median_us;
    }
    spread::cli::add_report_outcome(out, o.report, report_problem, report_error);
    std::cout << out.dump(2) << "\n";
  } else {
    std::cout << std::fixed << std::setprecision(2) << o.material << " at " << setting_label(o, result) << ", disc "
              << result.disc_height_m << " m above ground, " << result.sample_count << " launch samples, "
              << (result.flights > 0 ? std::to_string(result.flights) + " trajectories"
                                     : std::string("landings from the landing grid"))
              << ", effects " << effects_label(result.effects) << "\n"
              << "  throw width (99 % of mass)   " << result.throw_width_m << " m" << plus_minus(result.throw_width_se_m) << "\n"
              << "  working width at CV <= " << o.cv_target_percent << " %: to-and-fro "
              << result.working_width_to_and_fro_m << " m" << plus_minus(result.working_width_to_and_fro_se_m)
              << ", racetrack " << result.working_width_racetrack_m << " m"
              << plus_minus(result.working_width_racetrack_se_m) << "\n";
    std::cout << std::flush;
    spread::cli::print_verdicts(verdicts);
    if (o.compensate_wind) {
      std::cout << "  wind compensation: CV at " << result.bout_width_m << " m in this wind " << present_cv_percent
                << " %" << plus_minus(present_cv_se_percent) << " at the present setting; each disc set apart:\n"
                << "    left " << result.disc_rpm[0] << " rpm, drop point "
                << format("%+.1f deg", result.disc_drop_point_turn_rad[0] / spread::cli::kRadPerDeg) << "; right "
                << result.disc_rpm[1] << " rpm, drop point "
                << format("%+.1f deg", result.disc_drop_point_turn_rad[1] / spread::cli::kRadPerDeg) << " ("
                << (result.cv_percent <= o.cv_target_percent ? "meets" : "does not meet") << " the target)\n"
                << "    on the way back the wind comes from the other side: swap the discs' settings on the return pass\n";
    }
    if (return_pass.read_as == spread::predict::ReturnPass::kRacetrack) {
      std::cout << "  to-and-fro in this wind: the return pass, meeting the wind from the other side, lands where the"
                   " outgoing one does (as racetrack)\n";
    } else if (return_pass.read_as == spread::predict::ReturnPass::kFlown) {
      std::cout << "  to-and-fro in this wind: the return pass flown in the wind from the other side, CVs over two bouts\n";
    }
    if (result.bout_width_m > 0.0) {
      std::cout << "  CV at " << result.bout_width_m << " m: to-and-fro " << result.cv_percent << " %"
                << plus_minus(result.cv_se_percent) << ", racetrack " << result.cv_racetrack_percent << " %"
                << plus_minus(result.cv_racetrack_se_percent) << "\n";
    } else {
      std::cout << "  CV: no bout width meets the target\n";
    }
    struct Bands {
      const char* mode;
      const spread_band* bands;
      int count, headline;
    };
    for (const Bands& c : {Bands{"to-and-fro", result.bands_to_and_fro, result.band_count_to_and_fro,
                                 result.headline_band_to_and_fro},
                           Bands{"racetrack", result.bands_racetrack, result.band_count_racetrack,
                                 result.headline_band_racetrack}}) {
      if (c.count == 0) continue;
      std::cout << "  " << c.mode << " bands within the target:";
      for (int b = 0; b < std::min(c.count, SPREAD_MAX_BANDS); ++b) {
        const spread_band& band = c.bands[b];
        std::cout << (b ? ";" : "") << " " << band.lower_m << "-" << band.upper_m << " m (CV "
                  << band.cv_percent << " %" << plus_minus(band.cv_se_percent) << " at " << band.bout_width_m
                  << " m";
        if (band.lowest_cv_bout_width_m != band.bout_width_m) {
          std::cout << ", lowest " << band.lowest_cv_percent << " %" << plus_minus(band.lowest_cv_se_percent)
                    << " at " << band.lowest_cv_bout_width_m << " m";
        }
        std::cout << ")";
        if (b == c.headline) std::cout << " = working width";
        if (!band.established && b == c.headline && b > 0) {
          std::cout << " [joined to the band before: the samples do not show the gap above the target]";
        } else if (!band.established) {
          std::cout << " [not established: the lowest CV's 95 % interval reaches over the target]";
        }
      }
      if (c.count > SPREAD_MAX_BANDS) std::cout << " (" << c.count << " bands; the first and the widest shown)";
      std::cout << "\n";
    }
    if (result.sample_count < kFewSamples) {
      std::cout << "  note: only " << result.sample_count << " launch samples: below " << kFewSamples
                << " the working width can stop at a noise spike and the ± understates its spread"
                   " (docs/metrics.md \"Uncertainty\"); build the table with more samples per row\n";
    }
    if (stability) {
      std::cout << "  working width over " << stability->resamples << " bootstrap resamples of the launch samples: "
                << 100.0 * (1.0 - stability->outside_interval_fraction) << " % within its ±, "
                << 100.0 * stability->beyond_1m_fraction << " % more than 1 m away (2.5-97.5 %: "
                << stability->quantile_025_m << "-" << stability->quantile_975_m << " m)\n";
    }
    std::cout << "  (± = 95 % interval, 1.96 standard errors over the launch samples and, between DEM rows, the "
                 "interpolation's own error; kernel half-width "
              << result.kernel_half_width_m << " m)\n";
    std::cout << "  mean radius R " << result.mean_radius_m << " m, radial width xi " << result.radial_width_m
              << " m (one disc)\n";
    if (classes) spread::cli::print_size_classes(*classes);
    for (const std::string& line : guidance.lines) std::cout << "  " << line << "\n";
    if (o.repeat > 0) std::cout << "  median time per prediction " << median_us << " us over " << o.repeat << "\n";
    if (!o.report.path.empty() && report_problem.empty() && report_error.empty()) {
      std::cout << "wrote " << o.report.path << "\n";
    }
    std::cout << std::flush;
    spread::cli::print_next_steps(steps);
  }
  spread::cli::throw_report_outcome(report_problem, report_error);
  exit_code = spread::cli::kExitOk;
}

spread::cli::CommandRegistration reg{"predict", [](CLI::App& app, int& exit_code) {
  static Options options;
  auto* sub = app.add_subcommand("predict", "predict the spread pattern and working widths from a launch table (via the C API)");
  spread::cli::add_prediction_args(*sub, options);
  sub->add_option("--width", options.bout_width_m, "bout width for the CV (m); 0 = the to-and-fro working width");
  sub->add_option("--effects", options.effects, "in-flight effects: table (as the table was built, the default), all, none, or a list of " +
                      spread::effect::to_string(spread::flight::kAllEffects));
  sub->add_option("--kernel", options.kernel_half_width_m,
                  "half-width (m) of the kernel each landing is spread over; default automatic, 0 = point masses");
  sub->add_flag("--compensate-wind", options.compensate_wind,
                "in the --wind, set each disc apart (speed and drop point) for the lowest CV at --width (C API "
                "spread_compensate_wind); the prediction shown is at that setting");
  sub->add_flag("--fly-outside-domain", options.fly_outside_domain,
                "a disc height, wind or effect outside the table's landing grid (spread inspect): fly every launch "
                "sample (tens of ms) instead of refusing");
  sub->add_option("--stability", options.stability,
                  "N bootstrap resamples of the table's launch samples: how often the working width leaves its ±")
      ->check(CLI::NonNegativeNumber);
  sub->add_option("--repeat", options.repeat, "time K more predictions and report the median")->check(CLI::NonNegativeNumber);
  sub->add_flag("--size-classes", options.size_classes,
                "each size class of the launched granules alone at the bout: mass share, mean landing radius, CV, "
                "pattern; and the launched SGN and UI (docs/products.md)");
  sub->add_option("--size-class-mm", options.size_class_mm,
                  std::string("class boundaries in mm, comma-separated (implies --size-classes; default ") +
                      kDefaultSizeClassMm + ")");
  sub->add_option("--size-class-png", options.size_class_png,
                  "PNG of the fine and coarse halves' patterns across the bout (implies --size-classes)");
  sub->add_flag("--json", options.json, "machine-readable output on stdout");
  spread::cli::add_report_args(*sub, options.report, false);
  sub->callback([&exit_code] { run(options, exit_code); });
}};

}  // namespace
}  // namespace spread::cli::cmd_predict
