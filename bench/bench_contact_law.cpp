// The contact law alone (ComposedLaw::kernel: normal force, carried spring, Coulomb clip), on 256 contacts
// held in L1, by lane width: one contact (T = double), two in an SSE2 register (Lanes2), eight in an AVX-512
// one (Lanes8, where the processor has it; the pair pass's batched form). Two ways to feed it:
//   independent  every group of contacts stands alone: what the processor makes of the law when it may
//                overlap consecutive groups (throughput);
//   chained      each group's slip waits on the force of the group before (adds f − f, zero): one group's
//                dependency chain after the other (latency).
// `items_per_second` counts contacts. The contacts: the drum's linear spring–dashpot (bench_drum's beads:
// k_n 1000 N/m, k_t 2/7 k_n, d 4 mm, 2500 kg/m³, μ 0.5; overlaps up to 40 µm) and the disc's Hertz–Thornton
// (Case 1's granules, scenes/case1.toml: E 50 MPa, ν 0.25, 1800 kg/m³, d 3.2 mm, μ 0.35; overlaps up to
// 10 µm), both with restitution 0.5, the pair's parameters formed by PairTable; the stored tangential spring
// up to 1.3 μ F_n, so that about a quarter slide, in the plane of a normal turned slightly since.
// docs/drum.md ("Within the pair pass") reads it.
#include <benchmark/benchmark.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <random>
#include <utility>
#include <vector>

// The law's templates take eight-lane values here, inlined into the AVX-512 sweep only (lanes.hpp).
#pragma GCC diagnostic ignored "-Wpsabi"
#include "libspread/core/cpu_features.hpp"
#include "libspread/physics/dem/contact_laws.hpp"
#include "libspread/physics/dem/material.hpp"
#include "libspread/physics/dem/particles.hpp"

namespace {

using namespace spread::dem;
using lanes::V3;

constexpr std::size_t kContacts = 256;
constexpr double kDt_s = 5.36e-5;  // the drum's step (docs/drum.md)

// Each field of every contact in one flat array, contact by contact: lanes are consecutive contacts.
struct Contacts {
  enum Field { kNx, kNy, kNz, kOverlap, kSx, kSy, kSz, kHx, kHy, kHz, kHOverlap, kFields };
  std::vector<double> in[kFields];
  std::vector<double> force[3], history[4];
};

template <class Law>
struct Setup {
  PairParams params;
  typename Law::Coeffs coeffs;
  Contacts contacts;
};

// Unit normals in random directions; overlaps uniform in (0, max_overlap_m]; slips of about 1 mm/s; the
// stored spring in the plane of a normal turned by about 1e-3 rad, its magnitude up to 1.3 μ F_n (elastic).
template <class Law>
Setup<Law> make_setup(const PairParams& params, double radius_m, double density_kg_m3, double max_overlap_m) {
  Setup<Law> s;
  s.params = params;
  const double mass_kg = sphere_mass(density_kg_m3, radius_m);
  s.coeffs = Law::coeffs(params, radius_m / 2.0, mass_kg / 2.0);
  std::mt19937_64 rng(2026);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  for (auto& v : s.contacts.in) v.resize(kContacts);
  for (auto& v : s.contacts.force) v.resize(kContacts);
  for (auto& v : s.contacts.history) v.resize(kContacts);
  for (std::size_t c = 0; c < kContacts; ++c) {
    const spread::Vec3 n = spread::Vec3(normal(rng), normal(rng), normal(rng)).normalized();
    const double overlap_m = max_overlap_m * (1.0 - uniform(rng));
    // The elastic normal force for the friction limit (the kernel adds the dashpot).
    LawHistory<double> none{{0.0, 0.0, 0.0}, 0.0};
    const LawForce<double> loaded = Law::kernel(s.coeffs, params.friction, ContactNormal<double>{{n.x(), n.y(), n.z()}, {n.x(), n.y(), n.z()}, 1.0},
                                                overlap_m, V3<double>{0.0, 0.0, 0.0}, kDt_s, none);
    spread::Vec3 t = spread::Vec3(normal(rng), normal(rng), normal(rng));
    t = (t - t.dot(n) * n).normalized() + 1e-3 * n;  // a plane turned since the spring was stored
    const spread::Vec3 spring = t.normalized() * (1.3 * uniform(rng) * params.friction * loaded.normal_force_n);
    const double values[Contacts::kFields] = {n.x(), n.y(), n.z(), overlap_m, 1e-3 * normal(rng), 1e-3 * normal(rng),
                                              1e-3 * normal(rng), spring.x(), spring.y(), spring.z(), overlap_m};
    for (int f = 0; f < Contacts::kFields; ++f) s.contacts.in[f][c] = values[f];
  }
  return s;
}

template <class T>
SPREAD_CONTACT_INLINE T load(const double* p) {
  T v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
template <class T>
SPREAD_CONTACT_INLINE void store(double* p, const T& v) {
  std::memcpy(p, &v, sizeof v);
}

// Every contact through the law once, a group of lanes at a time.
template <class T, class Law, bool kChained>
SPREAD_CONTACT_INLINE void sweep(Setup<Law>& s) {
  constexpr std::size_t kLanes = sizeof(T) / sizeof(double);
  Contacts& k = s.contacts;
  T carry = lanes::splat<T>(0.0);
  for (std::size_t c = 0; c < kContacts; c += kLanes) {
    const auto in = [&](int f) { return load<T>(k.in[f].data() + c); };
    const V3<T> n{in(Contacts::kNx), in(Contacts::kNy), in(Contacts::kNz)};
    V3<T> slip{in(Contacts::kSx), in(Contacts::kSy), in(Contacts::kSz)};
    if constexpr (kChained) slip.x = slip.x + carry;
    LawHistory<T> h{{in(Contacts::kHx), in(Contacts::kHy), in(Contacts::kHz)}, in(Contacts::kHOverlap)};
    const LawForce<T> r = Law::kernel(s.coeffs, s.params.friction, ContactNormal<T>{n, n, lanes::splat<T>(1.0)},
                                      in(Contacts::kOverlap), slip, kDt_s, h);
    if constexpr (kChained) carry = r.force_n.x - r.force_n.x;
    store(k.force[0].data() + c, r.force_n.x);
    store(k.force[1].data() + c, r.force_n.y);
    store(k.force[2].data() + c, r.force_n.z);
    store(k.history[0].data() + c, h.elastic.x);
    store(k.history[1].data() + c, h.elastic.y);
    store(k.history[2].data() + c, h.elastic.z);
    store(k.history[3].data() + c, h.overlap_m);
  }
}

template <class T, class Law, bool kChained>
__attribute__((noinline)) SPREAD_CONTACT_FLATTEN void sweep_portable(Setup<Law>& s) {
  sweep<T, Law, kChained>(s);
}
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
template <class Law, bool kChained>
__attribute__((noinline, target("avx512f"))) SPREAD_CONTACT_FLATTEN void sweep_avx512(Setup<Law>& s) {
  sweep<lanes::Lanes8, Law, kChained>(s);
}
#endif

template <class Law, bool kChained>
void run(benchmark::State& state, Setup<Law> s, int lanes) {
  void (*sweep_fn)(Setup<Law>&) = lanes == 1 ? sweep_portable<double, Law, kChained> : sweep_portable<lanes::Lanes2, Law, kChained>;
  if (lanes == 8) {
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
    if (!spread::cpu_has_avx512f()) {
      state.SkipWithError("no AVX-512 on this processor");
      return;
    }
    sweep_fn = sweep_avx512<Law, kChained>;
#else
    state.SkipWithError("eight lanes are built with GCC on x86-64 only");
    return;
#endif
  }
  for (auto _ : state) {
    sweep_fn(s);
    benchmark::DoNotOptimize(s.contacts.force[0].data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(kContacts) * state.iterations());
}

// The pair's parameters as an engine forms them (PairTable: the mixing rules, damping from the restitution).
PairParams particle_pair(const Material& material, const ContactLaw& law, const LinearSprings& springs) {
  return PairTable({material}, {}, law, springs)(0, 0);
}
Setup<LinearSpringDashpot> drum_contacts() {
  Material bead;
  bead.density_kg_m3 = 2500.0;
  bead.restitution = 0.5;
  bead.friction_particle = 0.5;
  const PairParams p = particle_pair(bead, kLinearSpringDashpotLaw, LinearSprings{1000.0, 2.0 / 7.0});
  return make_setup<LinearSpringDashpot>(p, 0.002, bead.density_kg_m3, 4e-5);
}
Setup<HertzThornton> disc_contacts() {
  Material granule;  // scenes/case1.toml
  granule.density_kg_m3 = 1800.0;
  granule.youngs_modulus_pa = 5e7;
  granule.poisson_ratio = 0.25;
  granule.restitution = 0.5;
  granule.friction_particle = 0.35;
  const PairParams p = particle_pair(granule, kHertzThorntonLaw, LinearSprings{});
  return make_setup<HertzThornton>(p, 0.0016, granule.density_kg_m3, 1e-5);
}

template <class Law>
void run(benchmark::State& state, Setup<Law> s) {
  const int lanes = static_cast<int>(state.range(0));
  if (state.range(1) != 0)
    run<Law, true>(state, std::move(s), lanes);
  else
    run<Law, false>(state, std::move(s), lanes);
}
void BM_LinearLaw(benchmark::State& state) { run(state, drum_contacts()); }
void BM_HertzThorntonLaw(benchmark::State& state) { run(state, disc_contacts()); }
BENCHMARK(BM_LinearLaw)->ArgNames({"lanes", "chained"})->ArgsProduct({{1, 2, 8}, {0, 1}});
BENCHMARK(BM_HertzThorntonLaw)->ArgNames({"lanes", "chained"})->ArgsProduct({{1, 2, 8}, {0, 1}});

}  // namespace

BENCHMARK_MAIN();
