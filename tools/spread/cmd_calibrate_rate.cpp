// spread calibrate rate: catch test → flow factor → gate opening for a target rate; the rate error of the current opening.
#include "tools/spread/calibrate_report.hpp"

namespace spread::cli::calibrate {

namespace {

// Before the arithmetic: each number within what a catch test and a field can be (field_ranges.hpp).
void require_field_ranges(const RateOptions& o) {
  const struct {
    const cal::FieldRange& range;
    const char* option;
    double value;  // NaN: an optional input not given (the required ones CLI11 insists on)
  } inputs[] = {{cal::kCatchMassRange, "--mass", o.mass_kg},
                {cal::kCatchTimeRange, "--time", o.time_s},
                {cal::kGateRange, "--gate", o.gate},
                {cal::kCatchMassRange, "--mass2", o.mass2_kg},
                {cal::kCatchTimeRange, "--time2", o.time2_s},
                {cal::kGateRange, "--gate2", o.gate2},
                {cal::kRateRange, "--target-rate", o.target_rate_kg_ha},
                {cal::kBoutWidthRange, "--width", o.width_m},
                {cal::kSpeedRange, "--speed", o.speed_km_h},
                {cal::kGateRange, "--current-gate", o.current_gate}};
  for (const auto& input : inputs) {
    if (std::isnan(input.value)) continue;
    if (const std::string problem = cal::field_range_problem(input.range, input.option, input.value); !problem.empty()) {
      throw BadInput(problem);
    }
  }
}

}  // namespace

void run_rate(const RateOptions& o) {
  require_field_ranges(o);
  const cal::CatchTest first{o.mass_kg, o.time_s, o.gate};
  const int second_given = !std::isnan(o.mass2_kg) + !std::isnan(o.time2_s) + !std::isnan(o.gate2);
  if (second_given != 0 && second_given != 3) {
    throw BadInput("a second catch needs all of --mass2, --time2 and --gate2");
  }
  const bool two_point = second_given == 3;
  const std::optional<cal::CatchTest> second =
      two_point ? std::optional<cal::CatchTest>(cal::CatchTest{o.mass2_kg, o.time2_s, o.gate2}) : std::nullopt;
  const cal::MeteringModel model = two_point ? cal::metering_from_two_catches(first, *second) : cal::metering_from_catch(first);
  const double current = std::isnan(o.current_gate) ? o.gate : o.current_gate;
  const cal::RateSetting s = cal::rate_setting(model, o.target_rate_kg_ha, o.width_m, o.speed_km_h, current);
  const std::vector<std::string> warnings = cal::rate_warnings(first, second, s);
  const std::vector<spread::cli::NextStep> steps =
      spread::cli::rate_next_steps(s.required_gate_opening, s.current_gate_opening, o.width_m);
  if (o.json) {
    json out{{"model", two_point ? "two-point line" : "line through zero"},
             {"flow_factor_kg_s_per_unit", model.flow_factor_kg_s_per_unit},
             {"zero_opening", model.zero_opening},
             {"catch_mass_flow_kg_s", cal::catch_mass_flow_kg_s(first)},
             {"target_rate_kg_ha", o.target_rate_kg_ha},
             {"bout_width_m", o.width_m},
             {"speed_km_h", o.speed_km_h},
             {"required_mass_flow_kg_s", s.required_mass_flow_kg_s},
             {"required_gate_opening", s.required_gate_opening},
             {"current_gate_opening", s.current_gate_opening},
             {"current_mass_flow_kg_s", s.current_mass_flow_kg_s},
             {"current_rate_kg_ha", s.current_rate_kg_ha},
             {"rate_error_percent", 100.0 * s.rate_error},
             {"warnings", warnings},
             {"next_steps", spread::cli::next_steps_json(steps)}};
    std::cout << out.dump(2) << "\n";
    return;
  }
  std::printf("metering: %s, flow factor %.6g kg/s per gate unit, zero at %.4g\n",
              two_point ? "two-point line" : "line through zero", model.flow_factor_kg_s_per_unit, model.zero_opening);
  std::printf("target %.1f kg/ha at %.2f m, %.2f km/h: mass flow %.4f kg/s → set the gate to %.2f\n",
              o.target_rate_kg_ha, o.width_m, o.speed_km_h, s.required_mass_flow_kg_s, s.required_gate_opening);
  std::printf("gate at %.2f spreads %.1f kg/ha: %+.1f %% against the target\n", s.current_gate_opening,
              s.current_rate_kg_ha, 100.0 * s.rate_error);
  for (const std::string& w : warnings) std::printf("warning: %s\n", w.c_str());
  spread::cli::print_next_steps(steps);
}

}  // namespace spread::cli::calibrate
