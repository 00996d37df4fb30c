#pragma once
// Metering gate response: the gate in front of each disc is moved by an actuator of finite speed, so the
// flow it lets through follows the ECU's command with a delay. The opening (as a share of the field
// setting's flow to that disc) travels towards its target at a constant rate, the whole way from shut to
// the field's flow in `full_travel_s`:
//   opening += clamp(target − opening, −dt / full_travel_s, +dt / full_travel_s).
// A gate switched off therefore still delivers a falling flow for up to full_travel_s, and one switched on
// a rising flow: the latency a task controller's look-ahead makes up for (ISO 11783-10 "turn-on time",
// "turn-off time"). full_travel_s = 0 is an ideal gate (the opening is the target at once).

namespace spread::firmware {

class GateResponse {
 public:
  // full_travel_s: time from shut to the field's flow [s], >= 0 (0: no delay).
  explicit GateResponse(double full_travel_s = 0.0);

  void step(double target_fraction, double dt_s);
  double opening() const { return opening_; }  // delivered flow, of the field setting's to this disc [-]
  double full_travel_s() const { return full_travel_s_; }

 private:
  double full_travel_s_;
  double opening_ = 0.0;
};

}  // namespace spread::firmware
