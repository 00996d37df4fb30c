#pragma once
// Granule flight after launch-off (seed 000, Sect. 2.4): gravity always, and the effects a caller turns
// on — drag (Eq. 27, C_D from Eq. 32), Magnus lift (Eqs. 28–30), spin decay (Eqs. 34–36), wind (the
// relative air velocity replaces v_p in every air term). An effect that is off is not evaluated: the
// right-hand side is a template instantiated per effect combination and picked from a table.
//
// Integrators: fixed-step RK4 (Eqs. 44–48) and adaptive Dormand–Prince 5(4); both locate the ground
// crossing exactly (dense output / final partial step). No heap allocation in fly_to_ground().
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "libspread/core/effect_registry.hpp"
#include "libspread/core/vec3.hpp"

namespace spread::flight {

// In-flight effects: the flight rows of the effect registry (libspread/core/effect_registry.hpp), whose
// bits (kDrag, kMagnus, kSpinDecay, kWind, …) are all names of this namespace; each row says what it
// evaluates, flight_terms.hpp where. Without kSpinDecay ω stays constant in flight; without kWind the
// air is still. Gravity is not an effect: it always acts.
using effect::EffectSet;
using namespace effect::flight_bits;
inline constexpr EffectSet kAllEffects = effect::kFlightEffects;

// "drag,magnus,spin_decay,wind" (any order; "" or "none" → no effects). Throws std::invalid_argument
// naming the unknown effect (or the DEM effect, which does not act in flight).
EffectSet parse_effects(std::string_view comma_separated);
// Canonical order, comma separated; "" for no effects.
std::string effects_to_string(EffectSet effects);

enum class LiftModel : std::uint8_t {
  // C_L = 0.45 tanh(2Ω / 0.45): slope 2Ω at small spin ratio (Rubinow–Keller), saturating at the
  // Oesterle & Bui Dinh high-Re value 0.45. Vanishes smoothly as ω → 0. Default (see docs/physics-flight.md).
  kSmoothSaturating,
  // Oesterle & Bui Dinh (1998), seed Eq. 29 with the exponent Ω^0.4 of the original paper.
  kOesterleBuiDinh,
  // Seed Eq. 29 exactly as printed (Ω^0.04) — kept to show the difference, not for use.
  kOesterleBuiDinhAsPrinted,
};

struct Air {
  double density_kg_m3 = 1.225;
  double viscosity_pa_s = 1.81e-5;     // dynamic viscosity
  Vec3 wind_m_s = Vec3::Zero();        // used only when kWind is on (z component normally 0)
};

struct Granule {
  double diameter_m = 3e-3;
  double density_kg_m3 = 1500.0;
};

struct State {
  Vec3 position_m = Vec3::Zero();
  Vec3 velocity_m_s = Vec3::Zero();
  Vec3 spin_rad_s = Vec3::Zero();
};

enum class Scheme : std::uint8_t { kRk4, kDormandPrince45 };

struct Settings {
  Scheme scheme = Scheme::kDormandPrince45;
  double dt_s = 1e-3;          // RK4: the fixed step. Dormand–Prince: the first trial step.
  double rel_tol = 1e-6;       // Dormand–Prince only: relative error per step
  double abs_tol = 1e-7;       // Dormand–Prince only: absolute error per step (m, m/s, rad/s)
  double max_time_s = 60.0;    // a flight longer than this stops with landed = false
  int max_steps = 1'000'000;
  LiftModel lift = LiftModel::kSmoothSaturating;
  double gravity_m_s2 = kStandardGravity_m_s2;
};

struct Landing {
  State state;                 // at the ground crossing (position z == ground_z_m when landed)
  double flight_time_s = 0.0;
  int steps = 0;               // accepted steps
  int rejected_steps = 0;      // Dormand–Prince only
  bool landed = false;         // false: max_time_s / max_steps reached first
};

// Flies one granule from `launch` until z crosses ground_z_m (downward). Gravity is -z.
// Preconditions (checked, std::invalid_argument): finite inputs, diameter > 0, density > 0,
// air density >= 0, viscosity > 0, dt > 0; also rel_tol > 0, abs_tol >= 0, max_time_s > 0,
// max_steps > 0, gravity > 0, effects within kAllEffects, launch z >= ground_z_m; and with Scheme::kRk4,
// dt_s <= rk4_stable_step_bound_s() (the message names the "stable bound"). A launch exactly on the
// ground and not moving up has landed at t = 0.
Landing fly_to_ground(const Granule& granule, const State& launch, double ground_z_m, const Air& air,
                      EffectSet effects, const Settings& settings);

// Explicit stability of fixed-step RK4 (docs/physics-flight.md). RK4 on y' = -y/tau is stable for
// dt/tau <= 2.785 (the real-axis interval of its amplification polynomial); kRk4StabilityLimit keeps a
// hair of margin. Above it a fine granule's velocity grows without bound and "lands" at 1e8+ m/s.
inline constexpr double kRk4StabilityLimit = 2.78;
// The largest fixed RK4 step that is stable for this flight: kRk4StabilityLimit * tau, where 1/tau is the
// stiffest linearised rate of the right-hand side —
//   drag:       d|a_drag|/d|v_rel| (the drag slope divided by the mass) at the largest relative speed the
//               flight can reach, sqrt(|v_rel,0|^2 + 2 g (z0 - ground_z_m)) (+ 2 g |wind_z| max_time_s):
//               in the air's frame drag only removes energy and Magnus does no work;
//   spin decay: d|dω/dt|/d|ω| at the launch spin (spin only decays).
// +Inf when neither is on. Inputs as fly_to_ground (not re-validated here).
double rk4_stable_step_bound_s(const Granule& granule, const State& launch, double ground_z_m, const Air& air,
                               EffectSet effects, const Settings& settings);

// Optional per-step hook (tests, tools): called once at launch (t = 0), after every accepted step, and
// with the landing state. A plain function pointer + context: no allocation, no virtual call, and a
// null on_step costs one predictable branch per step.
struct StepObserver {
  void (*on_step)(void* context, double time_s, const State& state) = nullptr;
  void* context = nullptr;
};
Landing fly_to_ground(const Granule& granule, const State& launch, double ground_z_m, const Air& air,
                      EffectSet effects, const Settings& settings, const StepObserver& observer);

// Batch of independent flights, split over `threads` worker threads (<= 0: hardware concurrency).
// Results are identical for any thread count. granules.size() is launches.size() or 1 (one granule for
// all launches); out.size() == launches.size(). All inputs are validated before any thread starts.
void fly_batch(std::span<const Granule> granules, std::span<const State> launches, double ground_z_m,
               const Air& air, EffectSet effects, const Settings& settings, std::span<Landing> out,
               int threads);

// Many independent flights on the calling thread, without allocation: out[i] is fly_to_ground's landing
// of launches[i], bit for bit (granules as fly_batch: one per launch, or one for all). With Dormand–Prince
// and effects among kDrag | kWind (no spin state, no lift: what a drag-only table flies) the flights run
// several at a time in SIMD lanes (dormand_prince_lanes.hpp); otherwise one by one. Validation as fly_batch
// (std::invalid_argument naming the element, before any flight).
void fly_many(std::span<const Granule> granules, std::span<const State> launches, double ground_z_m,
              const Air& air, EffectSet effects, const Settings& settings, std::span<Landing> out);

// Coefficients, exposed for tests and tools.
double drag_coefficient(double reynolds);                                  // Eq. 32
double lift_coefficient(LiftModel model, double spin_ratio, double reynolds);  // Eq. 29 / smooth model
double spin_decay_alpha(double spin_reynolds);                             // Eq. 35

}  // namespace spread::flight
