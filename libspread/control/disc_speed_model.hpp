#pragma once
// Disc drive dynamics: the hydraulic or electric disc drive follows its set-point as a first-order lag,
// d(rpm)/dt = (rpm_setpoint - rpm) / tau. Stepped with the exact solution of the linear ODE over dt,
// rpm += (setpoint - rpm) * (1 - exp(-dt / tau)), which is stable and exact for any step length.

namespace spread::firmware {

class DiscSpeedModel {
 public:
  // time_constant_s: tau [s], > 0; initial_rpm: disc speed at start [r/min].
  explicit DiscSpeedModel(double time_constant_s, double initial_rpm = 0.0);

  void step(double setpoint_rpm, double dt_s);
  double rpm() const { return rpm_; }
  double time_constant_s() const { return time_constant_s_; }

 private:
  double time_constant_s_;
  double rpm_;
};

}  // namespace spread::firmware
