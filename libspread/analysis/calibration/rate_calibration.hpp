#pragma once
// Spread-rate calibration from a catch test (docs/field-calibration.md, step 1).
//
// Metering model: the mass flow through the metering gate is linear in the gate opening above a dead
// zone,
//     Q [kg/s] = flow_factor [kg/s per unit] · (opening − zero_opening),   Q = 0 below zero_opening.
// "unit" is whatever the gate's scale reads (mm of opening, % of the slide, scale number): the factor
// is only ever used with the same scale. One catch test fixes the factor with zero_opening = 0 (a line
// through zero — the usual assumption of a spreader's setting chart); two catches at different openings
// fix both (a two-point fit), which absorbs the gate's dead zone.
//
// Application rate (docs/design.md §3): Q [kg/s] = rate [kg/ha] · W [m] · v [km/h] / 36000
// (W · v / 3.6 is the area covered in m²/s, and 1 ha = 10 000 m²).
//
// Every function throws std::invalid_argument naming the input when it is not finite or out of range.

namespace spread::calibration {

// One catch: the mass collected from ALL outlets of the machine while the discs were stopped (or the
// catch bags were fitted over the outlets) during duration_s at one gate opening.
struct CatchTest {
  double mass_kg = 0.0;       // > 0
  double duration_s = 0.0;    // > 0
  double gate_opening = 0.0;  // > zero_opening, in the gate scale's unit
};

struct MeteringModel {
  double flow_factor_kg_s_per_unit = 0.0;  // kg/s per unit of gate opening
  double zero_opening = 0.0;               // opening at which the flow stops (gate scale unit)
};

// Q = mass / time of one catch.
double catch_mass_flow_kg_s(const CatchTest& test);

// Line through zero from one catch.
MeteringModel metering_from_catch(const CatchTest& test);
// Two-point fit; the catches must be at different openings and give a flow that grows with the opening.
MeteringModel metering_from_two_catches(const CatchTest& first, const CatchTest& second);

// Mass flow (kg/s) at an opening; 0 at or below zero_opening.
double mass_flow_at_opening_kg_s(const MeteringModel& model, double gate_opening);
// Inverse: the opening that meters mass_flow_kg_s (> 0).
double gate_opening_for_mass_flow(const MeteringModel& model, double mass_flow_kg_s);

// Q [kg/s] for rate [kg/ha] at working width W [m] and forward speed v [km/h].
double required_mass_flow_kg_s(double rate_kg_ha, double working_width_m, double speed_km_h);
// The rate [kg/ha] a mass flow spreads at W and v (inverse of the above).
double application_rate_kg_ha(double mass_flow_kg_s, double working_width_m, double speed_km_h);

// What the technician needs to set: the opening for the target rate, and what the current opening
// actually spreads.
struct RateSetting {
  double required_mass_flow_kg_s = 0.0;  // for the target rate
  double required_gate_opening = 0.0;    // gate scale unit
  double current_gate_opening = 0.0;     // the setting checked (the catch's opening by default)
  double current_mass_flow_kg_s = 0.0;
  double current_rate_kg_ha = 0.0;       // what the current opening spreads at W and v
  double rate_error = 0.0;               // (current − target) / target, fraction (+0.05 = 5 % too much)
};
RateSetting rate_setting(const MeteringModel& model, double target_rate_kg_ha, double working_width_m,
                         double speed_km_h, double current_gate_opening);

}  // namespace spread::calibration
