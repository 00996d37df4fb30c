#pragma once
// Gear predictor–corrector (seed 001 Sect. 3; Allen & Tildesley 1987, Sect. 3.2 and Appendix E) with 4, 5
// or 6 values, in the scaled-derivative (Nordsieck) form:
//   translation (second-order ODE r̈ = a):  r_k = Δt^k/k! d^k x/dt^k,  k = 0 … V−1
//   spin        (first-order ODE  ω̇ = α):  w_k = Δt^k/k! d^k ω/dt^k,  k = 0 … V−1
// Predictor: the Taylor series, r_i ← Σ_{j≥i} C(j,i) r_j (Pascal's triangle).
// Evaluate: forces at the predicted state. Corrector: Δ = (Δt²/2) a(x_p, v_p) − r_2 (translation) or
// Δ = Δt α − w_1 (spin), then r_k += c_k Δ.
//
// Corrector coefficients (docs/design.md §2 correction of the seed's garbled table):
//   second order   4 values: 1/6, 5/6, 1, 1/3
//                  5 values: 19/120, 3/4, 1, 1/2, 1/12
//                  6 values: 3/16, 251/360, 1, 11/18, 1/6, 1/60   (A&T give c0 = 3/20 when forces depend on
//                                                                  velocity; docs/design.md §2 lists 3/16)
//   first order    4 values: 3/8, 1, 3/4, 1/6
//                  5 values: 251/720, 1, 11/12, 1/3, 1/24
//                  6 values: 95/288, 1, 25/24, 35/72, 5/48, 1/120
// Start-up: a particle added since the last step has no derivatives yet. The engine then evaluates the
// forces at the current state once and start() sets r_2 = Δt²/2 a (w_1 = Δt α); the higher ones start
// at zero, which is exact for a particle added at rest or in free flight (da/dt = 0). Without this an
// unknown r_2 costs one order: the global error falls only as O(Δt) (measured, tests/drum/test_gear.cpp).
#include <array>
#include <cstdint>
#include <vector>

#include "libspread/core/vec3.hpp"
#include "libspread/physics/dem/particles.hpp"

namespace spread::dem {

inline constexpr int kGearMaxValues = 6;

struct GearCoefficients {
  int values = 5;                              // V: number of stored scaled derivatives (4, 5 or 6)
  std::array<double, kGearMaxValues> c{};      // c_0 … c_{V−1}
};

// Throws std::invalid_argument unless values ∈ {4, 5, 6}.
GearCoefficients gear_second_order_coefficients(int values);
GearCoefficients gear_first_order_coefficients(int values);

// One degree of freedom, in place on r[0 … values−1]: the Taylor predictor.
inline void gear_predict_scaled(double* r, int values) {
  // In place, rising i: the new r_i needs only the old r_j, j > i, which are not yet overwritten.
  static constexpr double kBinomial[kGearMaxValues][kGearMaxValues] = {
      {1, 1, 1, 1, 1, 1}, {0, 1, 2, 3, 4, 5}, {0, 0, 1, 3, 6, 10}, {0, 0, 0, 1, 4, 10}, {0, 0, 0, 0, 1, 5}, {0, 0, 0, 0, 0, 1}};
  for (int i = 0; i < values - 1; ++i) {
    double sum = r[i];
    for (int j = i + 1; j < values; ++j) sum += kBinomial[i][j] * r[j];
    r[i] = sum;
  }
}
// The corrector: r_k += c_k Δ.
inline void gear_correct_scaled(double* r, const GearCoefficients& gc, double delta) {
  for (int k = 0; k < gc.values; ++k) r[k] += gc.c[static_cast<std::size_t>(k)] * delta;
}

// Gear state for the particles of a DemEngine: the scaled derivatives above the velocity (translation)
// and above the spin (rotation), kept per particle id so that added and removed particles are followed.
class GearPredictorCorrector {
 public:
  GearPredictorCorrector() = default;
  explicit GearPredictorCorrector(int values);

  // Moves every active particle (x, v, ω and the stored derivatives) to the predicted state at t + Δt.
  void predict(ParticleArrays& p, double dt_s);
  // Corrects with the forces and torques evaluated at the predicted state; gravity is added to F/m.
  void correct(ParticleArrays& p, const Vec3& gravity_m_s2, double dt_s);
  // True when particles were added since the last step (their start values are needed).
  bool needs_start(const ParticleArrays& p);
  // Start values of the newly added particles from the forces evaluated at the current state.
  void start(const ParticleArrays& p, const Vec3& gravity_m_s2, double dt_s);

  int values() const { return second_.values; }

 private:
  void sync(const ParticleArrays& p);  // follows compaction and additions by particle id
  GearCoefficients second_, first_;
  int hi_t_ = 0;  // stored translational values per component: r_2 … r_{V−1}
  int hi_w_ = 0;  // stored spin values per component: w_1 … w_{V−1}
  std::vector<std::uint32_t> ids_;
  std::vector<std::uint8_t> fresh_;  // 1: added, start values not set yet
  std::vector<double> trans_;  // [(slot·3 + comp)·hi_t_ + k − 2]
  std::vector<double> spin_;   // [(slot·3 + comp)·hi_w_ + k − 1]
};

}  // namespace spread::dem
