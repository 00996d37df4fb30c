// The pair pass evaluates touching pairs two at a time in lanes (lanes.hpp): a contact must get bit for
// bit the same force and history whether it went through a lane or alone, whatever its neighbour lane
// does (slipping or sticking, loading or unloading, new or carried spring, spring along the normal,
// normal turned a little — the carry-over's series — or a lot).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "libspread/physics/dem/contact_laws.hpp"

using namespace spread::dem;
using lanes::Lanes2;
using lanes::V3;

namespace {

struct Contact {
  V3<double> normal, slip;
  V3<double> axis;  // the pair vector: the normal times a centre distance
  double overlap_m;
  LawHistory<double> history;
};

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

V3<double> unit(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  const V3<double> v{g(rng), g(rng), g(rng)};
  return v * (1.0 / std::sqrt(squared_norm(v)));
}

// Contacts of every kind the kernel branches on; `kind` picks one so every pairing of kinds is covered.
Contact make_contact(std::mt19937_64& rng, int kind) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Contact c;
  c.normal = unit(rng);
  c.axis = c.normal * (2e-3 + 2e-3 * u(rng));
  c.overlap_m = 1e-6 + 4e-5 * u(rng);
  c.slip = unit(rng) * (0.5 * u(rng));
  const V3<double> spring = unit(rng) * (0.05 * u(rng));
  switch (kind) {
    case 0: c.history = {lanes::zero3<double>(), 0.0}; break;                    // new contact
    case 1: c.history = {spring, c.overlap_m * 1.3}; break;                      // unloading
    case 2: c.history = {spring, c.overlap_m * 0.7}; break;                      // loading
    case 3: c.history = {spring * 200.0, c.overlap_m}; break;                    // far beyond Coulomb: slips
    case 4: c.history = {c.normal * 0.01, c.overlap_m}; break;                   // spring along the normal
    case 5: {                                                                     // normal turned a little
      const V3<double> tangent = spring - dot(spring, c.normal) * c.normal;
      c.history = {tangent + c.normal * (1e-3 * std::sqrt(squared_norm(tangent))), c.overlap_m};
      break;
    }
    default: c.history = {spring, c.overlap_m}; c.slip = c.slip * 1e-6; break;  // sticks
  }
  return c;
}

template <class Law>
void expect_lanes_match_scalar(const PairParams& params) {
  const auto coeffs = Law::coeffs(params, 1e-3, 2e-5);
  const double dt = 2e-6;
  std::mt19937_64 rng(42);
  constexpr int kKinds = 7;
  for (int trial = 0; trial < 245; ++trial) {
    const Contact c[2] = {make_contact(rng, trial % kKinds), make_contact(rng, (trial / kKinds) % kKinds)};
    LawForce<double> alone[2];
    LawHistory<double> alone_history[2];
    for (int l = 0; l < 2; ++l) {
      alone_history[l] = c[l].history;
      const ContactNormal<double> normal{c[l].normal, c[l].axis, 1.0 / squared_norm(c[l].axis)};
      alone[l] = Law::kernel(coeffs, params.friction, normal, c[l].overlap_m, c[l].slip, dt, alone_history[l]);
    }
    auto pack3 = [&](V3<double> Contact::*member) {
      const V3<double>& a = c[0].*member;
      const V3<double>& b = c[1].*member;
      return V3<Lanes2>{lanes::pack(a.x, b.x), lanes::pack(a.y, b.y), lanes::pack(a.z, b.z)};
    };
    LawHistory<Lanes2> h{{lanes::pack(c[0].history.elastic.x, c[1].history.elastic.x),
                          lanes::pack(c[0].history.elastic.y, c[1].history.elastic.y),
                          lanes::pack(c[0].history.elastic.z, c[1].history.elastic.z)},
                         lanes::pack(c[0].history.overlap_m, c[1].history.overlap_m)};
    const ContactNormal<Lanes2> normal{pack3(&Contact::normal), pack3(&Contact::axis),
                                       lanes::pack(1.0 / squared_norm(c[0].axis), 1.0 / squared_norm(c[1].axis))};
    const LawForce<Lanes2> both = Law::kernel(coeffs, params.friction, normal,
                                              lanes::pack(c[0].overlap_m, c[1].overlap_m), pack3(&Contact::slip), dt, h);
    for (int l = 0; l < 2; ++l) {
      const V3<double> f = lanes::lane3(both.force_n, l), ft = lanes::lane3(both.tangential_n, l);
      const V3<double> spring = lanes::lane3(h.elastic, l);
      const double expected[] = {alone[l].force_n.x, alone[l].force_n.y, alone[l].force_n.z,
                                 alone[l].tangential_n.x, alone[l].tangential_n.y, alone[l].tangential_n.z,
                                 alone[l].normal_force_n, alone_history[l].elastic.x, alone_history[l].elastic.y,
                                 alone_history[l].elastic.z, alone_history[l].overlap_m};
      const double got[] = {f.x, f.y, f.z, ft.x, ft.y, ft.z, both.normal_force_n[l], spring.x, spring.y, spring.z, h.overlap_m[l]};
      for (int q = 0; q < 11; ++q)
        EXPECT_TRUE(same_bits(expected[q], got[q])) << "trial " << trial << " lane " << l << " value " << q << ": alone "
                                                    << expected[q] << ", in lanes " << got[q];
    }
  }
}

}  // namespace

TEST(DemLanes, HertzThorntonInLanesIsBitIdenticalToAlone) {
  PairParams p;
  p.e_star_pa = 1e8;
  p.g_star_pa = 4e7;
  p.damping_ratio = 0.2;
  p.friction = 0.35;
  expect_lanes_match_scalar<HertzThornton>(p);
}

TEST(DemLanes, LinearSpringDashpotInLanesIsBitIdenticalToAlone) {
  PairParams p;
  p.kn_linear_n_m = 1000.0;
  p.kt_linear_n_m = 2000.0 / 7.0;
  p.damping_ratio = 0.2155;
  p.friction = 0.5;
  expect_lanes_match_scalar<LinearSpringDashpot>(p);
}

// The kernel's carried spring keeps its magnitude in the new tangent plane and vanishes when it lies
// along the normal (the zero-denominator lane is selected away, not divided by).
TEST(DemLanes, CarriedSpringKeepsMagnitudeAndDropsItsNormalPart) {
  const V3<double> n{0.0, 0.0, 1.0};
  const V3<double> f = detail::carry_into_plane(V3<double>{3.0, 0.0, 4.0}, n);
  EXPECT_DOUBLE_EQ(f.x, 5.0);
  EXPECT_EQ(f.z, 0.0);
  const V3<double> along = detail::carry_into_plane(V3<double>{0.0, 0.0, 2.0}, n);
  EXPECT_EQ(squared_norm(along), 0.0);
  const V3<Lanes2> mixed = detail::carry_into_plane(
      V3<Lanes2>{lanes::pack(3.0, 0.0), lanes::pack(0.0, 0.0), lanes::pack(4.0, 2.0)},
      V3<Lanes2>{lanes::pack(0.0, 0.0), lanes::pack(0.0, 0.0), lanes::pack(1.0, 1.0)});
  EXPECT_DOUBLE_EQ(mixed.x[0], 5.0);
  EXPECT_EQ(mixed.x[1], 0.0);
  EXPECT_FALSE(std::isnan(mixed.x[1]));
}

// The carry-over's series (normal turned by less than ~0.6°) against the exact ratio, and its
// independence of the axis' length: the magnitude is kept to rounding either way.
TEST(DemLanes, CarriedSpringSeriesMatchesTheExactRescale) {
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 100; ++trial) {
    const V3<double> n = unit(rng);
    const V3<double> f0 = unit(rng);
    const V3<double> tangent = f0 - dot(f0, n) * n;
    for (double tilt : {0.0, 1e-4, 3e-3, 9e-3, 2e-2, 0.3}) {  // (f·n)/|f| ≈ tilt: series below 1e-2
      const V3<double> f = tangent + n * (tilt * std::sqrt(squared_norm(tangent)));
      const V3<double> g = f - dot(f, n) * n;
      const V3<double> exact = g * std::sqrt(squared_norm(f) / squared_norm(g));
      for (double length : {1.0, 3.7e-3}) {
        const V3<double> carried = detail::carry_into_plane(f, n * length, 1.0 / (length * length));
        EXPECT_NEAR(std::sqrt(squared_norm(carried)), std::sqrt(squared_norm(f)), 4e-16 * std::sqrt(squared_norm(f)));
        EXPECT_NEAR(dot(carried, n), 0.0, 4e-16 * std::sqrt(squared_norm(f)));
        for (double V3<double>::*c : {&V3<double>::x, &V3<double>::y, &V3<double>::z})
          EXPECT_NEAR(carried.*c, exact.*c, 4e-16 * std::sqrt(squared_norm(f))) << "tilt " << tilt << " length " << length;
      }
    }
  }
}
