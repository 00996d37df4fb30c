// Particle–particle contacts over the Verlet pair list (CSR half list, neighbor_list.hpp; the direct form
// looks only at the near list's pairs): the engine's side of the pass. DemEngine::particle_forces fills the
// pass's context by name (pair_pass_context.hpp), gives it the batched pass's rows and the next step's drift
// where they apply, and runs the pass for the processor (pair_pass below): the portable stages
// (pair_pass_stages.hpp), the batched pass over lanes (pair_pass_batched.hpp) at each register width
// (pair_pass_widths.hpp), the AVX-512 stages (pair_pass_avx512.hpp), the integrator's kicks and drift inside
// the pass (pair_kicks.hpp). The stored form's results are gathered here (gather_stored_pair_forces).
#include <algorithm>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

// The contact laws' templates take eight-lane values here, inlined into the AVX-512 pass only (lanes.hpp).
#pragma GCC diagnostic ignored "-Wpsabi"
// SPREAD_UNROLL (contact_kernel.hpp) on the short loops over lanes, components and history slots: GCC at
// -O2 left most of them as loops, with a group's history lanes and i's sums on the stack (-O3's
// -fpeel-loops unrolls them; the pragma does it in the build users get; docs/drum.md).
#include "libspread/core/cpu_features.hpp"
#include "libspread/physics/dem/contact_laws.hpp"
#include "libspread/physics/dem/engine.hpp"
#include "libspread/physics/dem/engine_detail.hpp"
#include "libspread/physics/dem/pair_pass_avx512.hpp"
#include "libspread/physics/dem/pair_pass_context.hpp"
#include "libspread/physics/dem/pair_pass_stages.hpp"
#include "libspread/physics/dem/pair_pass_widths.hpp"

namespace spread::dem {

using detail::kMinParallelItems;

namespace {
using namespace pairs;

// The pass for the processor. The direct form: the batched pass, eight pairs a register where the processor
// has AVX-512 (on several threads, a range of particles each), four in AVX2 registers where it has AVX2, else
// four in pairs of SSE2 registers (pair_pass_widths.hpp). The stored form: the particle-by-particle pass,
// compiled for AVX-512 where the processor has it (the law's lanes two doubles wide, 32 vector registers
// instead of 16, less of a contact's state spilled). The same bits every way
// (DemPairPass.EveryRegisterWidthGivesTheSameBits; docs/drum.md "Where the time goes"). Returns the largest
// squared move since the near list's build where the pass drifted the particles (a.drift_dt_s), else 0.
template <class V, PairForm kForm>
double pair_pass(PairPassArrays<typename V::Law> a, long long count, int threads) {
  if constexpr (!kForm.store_pairs) {
#if defined(__x86_64__) || defined(__i386__)
    if (cpu_has_avx512f()) {
      if (threads > 1 && count >= kMinParallelItems) return pair_pass_batched_threads_avx512<V, kForm>(a, count, threads);
      return pair_pass_batched_avx512<V, kForm>(a, count);
    }
    if (cpu_has_avx2()) return pair_pass_batched_avx2<V, kForm>(a, count);
#endif
    return pair_pass_batched_portable<V, kForm>(a, count);
  } else {
#if defined(__x86_64__) || defined(__i386__)
    if (cpu_has_avx512f()) return pair_pass_avx512<V, kForm>(a, count, threads);
#endif
    return pair_pass_portable<V, kForm>(a, 0, count, threads);
  }
}

#if defined(__x86_64__) || defined(__i386__)
// `count` doubles of `storage` from an `align`-byte boundary (one row per load), grown when short; fresh
// storage holds no rows, so `kept` is cleared then.
double* aligned_rows(std::vector<double>& storage, std::size_t count, std::size_t align, bool& kept) {
  const std::size_t pad = align / sizeof(double);
  if (storage.size() < count + pad) {
    storage.resize(count + pad);
    kept = false;
  }
  const auto address = reinterpret_cast<std::uintptr_t>(storage.data());
  return storage.data() + (align - address % align) % align / sizeof(double);
}
#endif

// Whether the direct pass runs batched (AVX-512): then several threads add straight into the sums too, since
// the batched pass keeps the order of the additions for any thread count (pair_pass_batched_threads_avx512).
bool batched_pair_pass() {
#if defined(__x86_64__) || defined(__i386__)
  return cpu_has_avx512f();
#else
  return false;
#endif
}

}  // namespace

// The pass's context, every field by name (a field left out fails the build: -Werror=missing-field-initializers,
// cmake/SpreadWarnings.cmake). What only some passes use starts empty: the near list, the batched pass's rows
// (pair_pass_rows) and the next step's drift (pair_pass_drift).
template <class V>
pairs::PairPassArrays<typename V::Law> DemEngine::pair_pass_arrays() {
  using Law = typename V::Law;
  constexpr bool with_spin = V::kRotation;
  const auto spin = [&](std::vector<double>& v) { return with_spin ? v.data() : nullptr; };
  return pairs::PairPassArrays<Law>{
      .x = p_.x.data(), .y = p_.y.data(), .z = p_.z.data(),
      .vx = p_.vx.data(), .vy = p_.vy.data(), .vz = p_.vz.data(),
      .wx = spin(p_.wx), .wy = spin(p_.wy), .wz = spin(p_.wz),
      .radius = p_.radius_m.data(), .mass = p_.mass_kg.data(), .inertia = p_.inertia_kg_m2.data(),
      .material = p_.material.data(), .active = p_.active.data(),
      .pair_start = pairs_.first_start.data(), .partner = pairs_.second.data(),
      .history = pairs_.history.data(), .held = pairs_.held.data(),
      .pair_force = pairs_.force.data(), .pair_torque_i = pairs_.torque_first.data(),
      .pair_torque_j = pairs_.torque_second.data(), .sums = pair_sum_.data(),
      .fx = p_.fx.data(), .fy = p_.fy.data(), .fz = p_.fz.data(),
      .tx = spin(p_.tx), .ty = spin(p_.ty), .tz = spin(p_.tz),
      .params = &pair_table_(0, 0), .coeffs = coeffs_table<Law>(pair_coeffs_),
      .material_count = pair_table_.material_count(),
      .period_m = params_.periodic_z.length_m(), .dt_s = dt_s_,
      .kick_dt_s = kick_in_pass_dt_s_,
      .gravity_m_s2 = {params_.gravity_m_s2.x(), params_.gravity_m_s2.y(), params_.gravity_m_s2.z()},
      .inv_mass = p_.inv_mass_kg.data(), .inv_inertia = spin(p_.inv_inertia_kg_m2),
      .kick_v = {p_.vx.data(), p_.vy.data(), p_.vz.data()},
      .kick_w = {spin(p_.wx), spin(p_.wy), spin(p_.wz)},
      .near_start = nullptr, .near_pairs = nullptr,
      .near_first = nullptr, .near_second = nullptr,
      .touch_rows = nullptr, .law_rows = nullptr, .near_held = nullptr,
      .drift_dt_s = 0.0, .drift_clears_sums = false,
      .position = {nullptr, nullptr, nullptr},
      .x0 = nullptr, .y0 = nullptr, .z0 = nullptr};
}

// The batched pass's touch test reads each body's x, y, z, r in one load (r NaN: inactive, never touching),
// its law each body's v, ω, r, I in one. Kept by the last pass's drift (the steps between: nothing else moved
// a particle), else written here.
template <class V>
void DemEngine::pair_pass_rows(pairs::PairPassArrays<typename V::Law>& a) {
#if defined(__x86_64__) || defined(__i386__)
  constexpr bool with_spin = V::kRotation;
  const std::size_t n = p_.size();
  double* const rows = aligned_rows(touch_rows_, 4 * n, 32, touch_rows_kept_);
  double* const law_rows = aligned_rows(law_rows_, 8 * n, 64, touch_rows_kept_);
  for (std::size_t i = 0; i < (touch_rows_kept_ ? 0 : n); ++i) {
    rows[4 * i] = p_.x[i];
    rows[4 * i + 1] = p_.y[i];
    rows[4 * i + 2] = p_.z[i];
    rows[4 * i + 3] = p_.active[i] ? p_.radius_m[i] : std::numeric_limits<double>::quiet_NaN();
    double* const row = law_rows + 8 * i;
    row[0] = p_.vx[i];
    row[1] = p_.vy[i];
    row[2] = p_.vz[i];
    row[3] = with_spin ? p_.wx[i] : 0.0;
    row[4] = with_spin ? p_.wy[i] : 0.0;
    row[5] = with_spin ? p_.wz[i] : 0.0;
    row[6] = p_.radius_m[i];
    row[7] = p_.inertia_kg_m2[i];
  }
  if (!near_.held_synced) {
    for (std::size_t e = 0; e < near_.pairs.size(); ++e) near_.held[e] = pairs_.held[near_.pairs[e]];
    near_.held_synced = true;
  }
  a.law_rows = law_rows;
  a.touch_rows = rows;
  a.near_first = near_.first.data();
  a.near_held = near_.held.data();
  a.near_second = near_.second.data();
#else
  (void)a;
#endif
}

// The next step's opening kick and drift handed to the pass (its drift form), with the positions at the
// near list's build where the move since is measured.
template <class Law>
void DemEngine::pair_pass_drift(pairs::PairPassArrays<Law>& a, bool measure_near) {
  a.drift_dt_s = dt_s_;
  a.drift_clears_sums = opening_kick_clears_sums();
  a.position[0] = p_.x.data();
  a.position[1] = p_.y.data();
  a.position[2] = p_.z.data();
  if (measure_near) {
    a.x0 = near_.x0.data();
    a.y0 = near_.y0.data();
    a.z0 = near_.z0.data();
  }
}

template <class V>
void DemEngine::particle_forces() {
  const std::size_t n = p_.size();
  if (pair_sum_.size() != n) pair_sum_.assign(n, PairSum{});
  // Per-pair results are stored (and gathered in a second pass) when threads share the pairs or an
  // energy monitor reads them; one thread adds them straight into the sums. Same sums, same order.
  // Where the batched pass runs several threads add them straight into the sums too.
  const bool batched = batched_pair_pass();
  const bool shared = threads_share_pairs();
  const bool store = (shared && !batched) || monitor_ != nullptr;
  if (store) prepare_stored_pairs(n, pairs_);
  pairs::PairPassArrays<typename V::Law> a = pair_pass_arrays<V>();
  const bool periodic = params_.periodic_z.enabled;
  if (!store && near_.start.size() == n + 1) {
    a.near_start = near_.start.data();
    a.near_pairs = near_.pairs.data();
    // The rows only where the law runs in eight-pair registers anyway: on a processor that lowers its clock
    // for 512-bit instructions, a pass of scalar laws (sizes mixed within a material) with this test in
    // 512-bit registers made the disc's whole step slower (bench_dem: 0.634–0.651 s → 0.703–0.707 s).
    if (batched && !periodic && one_size_per_material_ && near_.first.size() == near_.pairs.size()) pair_pass_rows<V>(a);
  }
  kicked_in_pass_ = kick_in_pass_dt_s_ != 0.0;
  touch_rows_kept_ = false;
  if (a.touch_rows == nullptr) near_.held_synced = false;  // this pass updates the pairs' held bytes only
  // The next step's opening kick and drift (steps()) go with the direct pass's closing kick; the stored
  // form kicks in its gather, and a periodic axis wraps between the steps.
  const bool drift = fuse_next_step_ && kicked_in_pass_ && !store && !periodic;
  const bool measure_near = near_.x0.size() == n;
  if (drift) pair_pass_drift(a, measure_near);
  if (store) {
    run_stored_pair_pass<V>(a);
    return;
  }
  const int threads = shared ? params_.threads : 1;
  double moved2 = 0.0;
  const long long count = static_cast<long long>(n);
  if (periodic) pair_pass<V, PairForm{false, true, false}>(a, count, threads);
  else if (drift) moved2 = pair_pass<V, PairForm{false, false, true}>(a, count, threads);
  else pair_pass<V, PairForm{false, false, false}>(a, count, threads);
  if (drift) {
    drifted_in_pass_ = true;
    touch_rows_kept_ = a.touch_rows != nullptr;
    sums_cleared_ = a.drift_clears_sums;
    moved2_since_near_ = measure_near ? moved2 : -1.0;
  }
}

// The stored form: per-pair results, then the gather adds them in pair order (and kicks).
template <class V>
void DemEngine::run_stored_pair_pass(pairs::PairPassArrays<typename V::Law>& a) {
  const long long count = static_cast<long long>(p_.size());
  if (params_.periodic_z.enabled) pair_pass<V, PairForm{true, true, false}>(a, count, params_.threads);
  else pair_pass<V, PairForm{true, false, false}>(a, count, params_.threads);
  gather_stored_pair_forces<V::kRotation>();
}

template <bool kRotation>
void DemEngine::gather_stored_pair_forces() {
  const long long nn = static_cast<long long>(p_.size());
  const bool parallel = params_.threads > 1 && nn >= kMinParallelItems;
#pragma omp parallel for schedule(static) num_threads(params_.threads) if (parallel)
  for (long long ii = 0; ii < nn; ++ii) {
    const std::size_t i = static_cast<std::size_t>(ii);
    // The partners' share, from zero in pair order — the order in which the direct pass adds it.
    double f[3] = {0.0, 0.0, 0.0}, t[3] = {0.0, 0.0, 0.0};
    for (std::uint32_t q = pairs_.second_start[i]; q < pairs_.second_start[i + 1]; ++q) {
      const std::uint32_t k = pairs_.second_pairs[q];
SPREAD_UNROLL(3)
      for (int c = 0; c < 3; ++c) {
        f[c] -= pairs_.force[k * 3 + c];
        if constexpr (kRotation) t[c] += pairs_.torque_second[k * 3 + c];
      }
    }
    PairSum& si = pair_sum_[i];
    p_.fx[i] += f[0] + si.f[0];
    p_.fy[i] += f[1] + si.f[1];
    p_.fz[i] += f[2] + si.f[2];
    if constexpr (kRotation) {
      p_.tx[i] += t[0] + si.t[0];
      p_.ty[i] += t[1] + si.t[1];
      p_.tz[i] += t[2] + si.t[2];
    }
    si = PairSum{};
    if (kick_in_pass_dt_s_ != 0.0 && p_.active[i]) {  // as kick_particle
      const double dt = kick_in_pass_dt_s_, inv_m = p_.inv_mass_kg[i];
      const Vec3& g = params_.gravity_m_s2;
      p_.vx[i] += dt * (p_.fx[i] * inv_m + g.x());
      p_.vy[i] += dt * (p_.fy[i] * inv_m + g.y());
      p_.vz[i] += dt * (p_.fz[i] * inv_m + g.z());
      if constexpr (kRotation) {
        const double inv_i = p_.inv_inertia_kg_m2[i];
        p_.wx[i] += dt * p_.tx[i] * inv_i;
        p_.wy[i] += dt * p_.ty[i] * inv_i;
        p_.wz[i] += dt * p_.tz[i] * inv_i;
      }
    }
  }
}

const ForcePassTable kParticlePasses = ForcePassTables::particle(std::make_index_sequence<kForceVariantCount>{});

}  // namespace spread::dem