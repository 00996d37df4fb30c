// The rough wall of fixed beads (dem/sphere_wall.hpp, drum wall = "rough_particles"): the bead lookup
// against brute force, the bead contact against the particle–particle contact with the same overlap
// (linear and Hertz), and the scene keys.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "libspread/physics/dem/engine.hpp"
#include "libspread/physics/dem/sphere_wall.hpp"
#include "libspread/physics/drum/drum_packing.hpp"
#include "libspread/physics/drum/drum_scene.hpp"
#include "libspread/io/scene/scene.hpp"

namespace dem = spread::dem;
namespace drum = spread::drum;
using spread::Vec3;

TEST(SphereWall, LiningTouchesMantleWithoutOverlaps) {
  const double R = 0.04, L = 0.009, d = 0.004;
  const auto beads = dem::make_cylinder_bead_lining(R, L, d);
  // ρ_c = 0.038: ⌊π / asin(0.002/0.038)⌋ = 59 per ring, ⌊9/4⌋ = 2 rings.
  EXPECT_EQ(beads.size(), 118u);
  for (std::size_t a = 0; a < beads.size(); ++a) {
    const Vec3 c = beads.centre(a);
    EXPECT_NEAR(std::hypot(c.x(), c.y()) + beads.radius(a), R, 1e-12);
    EXPECT_GE(c.z() - beads.radius(a), 0.0);
    EXPECT_LE(c.z() + beads.radius(a), L);
    for (std::size_t b = a + 1; b < beads.size(); ++b) EXPECT_GE((c - beads.centre(b)).norm(), 2.0 * d / 2.0 - 1e-12);
  }
  EXPECT_NEAR(beads.max_axis_distance_m(), R, 1e-12);
  EXPECT_THROW(dem::make_cylinder_bead_lining(R, L, 0.03), std::invalid_argument);   // > R/2
  EXPECT_THROW(dem::make_cylinder_bead_lining(R, 0.002, d), std::invalid_argument);  // longer than the drum
  EXPECT_THROW(dem::SphereWall({Vec3::Zero()}, {-1.0}), std::invalid_argument);
}

// The grid lookup finds exactly the beads a brute-force scan finds, closest first.
TEST(SphereWall, QueryMatchesBruteForce) {
  const auto beads = dem::make_cylinder_bead_lining(0.04, 0.012, 0.003);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int touching = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const double rho = 0.034 + 0.006 * (0.5 + 0.5 * u(rng)), a = 3.2 * u(rng);
    const Vec3 c(rho * std::cos(a), rho * std::sin(a), 0.006 + 0.006 * u(rng));
    const double r = 0.0015 + 0.001 * (0.5 + 0.5 * u(rng));
    dem::BeadContact out[8];
    const int n = beads.query(c, r, out, 8);
    int expected = 0;
    for (std::size_t b = 0; b < beads.size(); ++b)
      if ((c - beads.centre(b)).norm() < r + beads.radius(b)) ++expected;
    ASSERT_EQ(n, std::min(expected, 8)) << "trial " << trial;
    for (int i = 0; i < n; ++i) {
      const Vec3 cb = beads.centre(out[i].bead);
      EXPECT_NEAR(out[i].distance_m, (c - cb).norm() - beads.radius(out[i].bead), 1e-15);
      EXPECT_NEAR((out[i].normal - (c - cb).normalized()).norm(), 0.0, 1e-12);
      if (i > 0) {
        EXPECT_LE(out[i - 1].distance_m, out[i].distance_m);
      }
    }
    touching += n > 0;
  }
  EXPECT_GT(touching, 500);  // the sample does probe the lining
}

namespace {

struct Forces {
  Vec3 force, torque;
};

dem::Material grain() {
  dem::Material m;
  m.name = "grain";
  m.density_kg_m3 = 2500.0;
  m.youngs_modulus_pa = 5e7;
  m.poisson_ratio = 0.25;
  m.restitution = 0.5;
  m.friction_particle = m.friction_wall = 0.4;
  return m;
}

dem::EngineParams params(const dem::ContactLaw& model) {
  dem::EngineParams ep;
  ep.contact_law = model;
  ep.linear.normal_stiffness_n_m = 1000.0;
  ep.integrator = dem::Integrator::kSymplecticEuler;
  ep.dt_s = 1e-7;
  ep.min_particle_radius_m = 0.0015;
  ep.max_particle_radius_m = 0.0025;
  ep.gravity_m_s2 = Vec3::Zero();
  return ep;
}

// One contact, the bead turning with the drum at ω about z: as a second particle (infinitely heavy:
// density ×1e15, moving and spinning rigidly with the drum) or as a bead of the wall. Returns the force
// and torque on the free particle a at t = 0.
Forces particle_contact(const dem::ContactLaw& model, double ra, double rb, const Vec3& xa, const Vec3& va, const Vec3& wa,
                        const Vec3& xb, double omega) {
  dem::Material heavy = grain();
  heavy.name = "fixed particle";
  heavy.density_kg_m3 *= 1e15;
  dem::DemEngine e({grain(), heavy}, {}, dem::WallSet{}, params(model));
  e.add_particle(xa, va, ra, 0, wa);
  e.add_particle(xb, Vec3(-omega * xb.y(), omega * xb.x(), 0.0), rb, 1, Vec3(0.0, 0.0, omega));
  e.step();
  const auto& p = e.particles();
  return {Vec3(p.fx[0], p.fy[0], p.fz[0]), Vec3(p.tx[0], p.ty[0], p.tz[0])};
}

Forces bead_contact(const dem::ContactLaw& model, double ra, double rb, const Vec3& xa, const Vec3& va, const Vec3& wa,
                    const Vec3& xb, double omega) {
  dem::WallSet walls;
  dem::WallGroup g;
  g.name = "drum";
  g.material = 1;
  g.angular_velocity_rad_s = omega;
  dem::SphereWall beads({xb}, {rb});
  beads.materials_by_radius.push_back({ra, 1});
  g.bead_walls.push_back(beads);
  walls.groups.push_back(g);
  dem::DemEngine e({grain(), dem::bead_contact_material(grain(), ra, rb)}, {}, walls, params(model));
  e.add_particle(xa, va, ra, 0, wa);
  e.step();
  const auto& p = e.particles();
  return {Vec3(p.fx[0], p.fy[0], p.fz[0]), Vec3(p.tx[0], p.ty[0], p.tz[0])};
}

void expect_same_contact(const dem::ContactLaw& model, double force_rel_tol, double torque_rel_tol) {
  const double ra = 0.002, rb = 0.0017, omega = 3.0;
  const Vec3 xb(0.01, -0.035, 0.004);
  const Vec3 n = Vec3(-0.3, 0.9, 0.2).normalized();
  for (double overlap : {2e-6, 2e-5, 1e-4}) {
    const Vec3 xa = xb + (ra + rb - overlap) * n;
    // Approach plus sliding, and a spin: normal, damping, tangential and Coulomb terms all take part.
    const Vec3 va(0.05, -0.12, 0.03), wa(4.0, -2.0, 7.0);
    const Forces pp = particle_contact(model, ra, rb, xa, va, wa, xb, omega);
    const Forces pw = bead_contact(model, ra, rb, xa, va, wa, xb, omega);
    ASSERT_GT(pp.force.norm(), 0.0);
    EXPECT_NEAR(pw.force.dot(n), pp.force.dot(n), 1e-9 * pp.force.norm()) << "normal force, overlap " << overlap;
    EXPECT_LT((pw.force - pp.force).norm(), force_rel_tol * pp.force.norm()) << "overlap " << overlap << ": " << pp.force.transpose()
                                                                            << " vs " << pw.force.transpose();
    EXPECT_LT((pw.torque - pp.torque).norm(), torque_rel_tol * pp.torque.norm()) << "overlap " << overlap;
    // The bead's surface velocity matters: a bead at rest gives a different tangential force.
    const Forces still = bead_contact(model, ra, rb, xa, va, wa, xb, 0.0);
    EXPECT_GT((still.force - pp.force).norm(), 1e-3 * pp.force.norm());
  }
}

}  // namespace

TEST(SphereWall, LinearBeadContactEqualsParticleContact) {
  expect_same_contact(dem::kLinearSpringDashpotLaw, 1e-9, 1e-9);
}

// Hertz: the normal force is exact through the bead-contact material. The engine's lever for a wall
// contact takes the share f of the overlap instead of 1/2 (Eq. 10), here f = 0.34, δ/r ≤ 0.05: the
// contact point's spin velocity and so the tangential force differ by ~1e-4 (measured ≤ 6e-5 of |F|),
// the torque by at most (1/2 − f) δ/r = 0.8 %.
TEST(SphereWall, HertzBeadContactEqualsParticleContact) {
  expect_same_contact(dem::kHertzThorntonLaw, 2e-4, 1e-2);
}

TEST(DrumScene, RoughWallKeys) {
  const std::string base = "[drum]\nradius_m = 0.04\nlength_m = 0.009\nfroude = 0.1\n[[species]]\ndiameter_m = 0.004\n";
  const auto s = drum::parse_drum_scene(base, "x.toml", {"drum.wall=rough_particles"});
  EXPECT_EQ(s.wall, drum::DrumWall::kRoughParticles);
  EXPECT_DOUBLE_EQ(drum::bead_diameter_m(s), 0.004);  // the species' mean by default
  EXPECT_DOUBLE_EQ(drum::free_radius_m(s), 0.036);
  const auto t = drum::parse_drum_scene(base, "x.toml", {"drum.wall=rough_particles", "drum.wall_bead_diameter_m=0.003"});
  EXPECT_DOUBLE_EQ(drum::bead_diameter_m(t), 0.003);
  auto error_of = [&](const std::vector<std::string>& set) {
    try {
      drum::parse_drum_scene(base, "x.toml", set);
    } catch (const spread::scene::SceneError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error_of({"drum.wall=bumpy"}).find("x.toml: drum.wall: unknown value \"bumpy\""), std::string::npos);
  EXPECT_NE(error_of({"drum.wall_bead_diameter_m=0.003"}).find("drum.wall_bead_diameter_m: only used with"), std::string::npos);
  EXPECT_NE(error_of({"drum.wall=rough_particles", "drum.wall_bead_diameter_m=0.02"}).find("drum.wall_bead_diameter_m: must be <="),
            std::string::npos);
  // The bed fills the space within the bead tips: fewer particles than in the smooth drum.
  const auto smooth = drum::parse_drum_scene(base, "x.toml");
  EXPECT_LT(drum::particle_count(s), drum::particle_count(smooth));
  for (const auto& q : drum::grid_packing(s)) EXPECT_LE(std::hypot(q.position_m.x(), q.position_m.y()) + q.radius_m, 0.036);
}
