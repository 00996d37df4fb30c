// Periodic axis: a pair across the periodic boundary interacts exactly as the same pair in the
// interior, positions stay wrapped, and a small periodic drum keeps its particles and rolls.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "libspread/physics/dem/engine.hpp"
#include "libspread/physics/drum/drum_scene.hpp"
#include "libspread/physics/drum/drum_simulation.hpp"
#include "tests/drum/small_test_drum.hpp"

namespace dem = spread::dem;
namespace drum = spread::drum;
using spread::Vec3;

namespace {

constexpr double kPeriod_m = 0.0625;   // 2^-4: the pair offsets below are exact binary fractions
constexpr double kOffset_m = 0.001953125;  // 2^-9; centres 2^-8 = 3.906 mm apart, beads 4 mm: touching

dem::DemEngine free_engine() {
  dem::Material m;
  m.name = "bead";
  m.density_kg_m3 = 2500.0;
  m.restitution = 0.5;
  m.friction_particle = m.friction_wall = 0.5;
  dem::EngineParams ep;
  ep.contact_law = dem::kLinearSpringDashpotLaw;
  ep.linear.normal_stiffness_n_m = 1000.0;
  ep.integrator = dem::Integrator::kSymplecticEuler;  // forces of step 1 at the exact start positions
  ep.min_particle_radius_m = 0.002;
  ep.gravity_m_s2 = Vec3::Zero();
  ep.periodic_z = {true, 0.0, kPeriod_m};
  return dem::DemEngine({m}, {}, dem::WallSet{}, ep);
}

// Two touching beads whose line of centres is along z, centred on z_mid, approaching with sliding and spin
// and drifting together along −z (0.4 m/s), so that after the collision the upper bead crosses z_mid − 2^-9.
void add_pair(dem::DemEngine& e, double z_mid) {
  e.add_particle(Vec3(0.01, 0.02, z_mid + kOffset_m), Vec3(0.05, 0.0, -0.6), 0.002, 0, Vec3(0.0, 3.0, 0.0));
  e.add_particle(Vec3(0.01, 0.02, z_mid - kOffset_m), Vec3(-0.05, 0.01, -0.2), 0.002, 0, Vec3(1.0, 0.0, 0.0));
}

}  // namespace

TEST(DrumPeriodic, PairAcrossTheBoundaryActsAsInTheInterior) {
  dem::DemEngine across = free_engine(), inside = free_engine();
  add_pair(across, 0.0);               // upper bead at z = 2^-9, lower one wrapped to L − 2^-9
  add_pair(inside, 0.5 * kPeriod_m);
  EXPECT_DOUBLE_EQ(across.particles().z[1], kPeriod_m - kOffset_m);  // wrapped on insertion
  across.step();
  inside.step();
  ASSERT_EQ(across.pair_count(), 1u);
  // Same minimum-image vector (exact in binary), so the very same forces, moments and new velocities.
  const auto& a = across.particles();
  const auto& b = inside.particles();
  ASSERT_NE(a.fz[0], 0.0);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(a.fx[i], b.fx[i]);
    EXPECT_EQ(a.fy[i], b.fy[i]);
    EXPECT_EQ(a.fz[i], b.fz[i]);
    EXPECT_EQ(a.tx[i], b.tx[i]);
    EXPECT_EQ(a.ty[i], b.ty[i]);
    EXPECT_EQ(a.vz[i], b.vz[i]);
  }
  // Through the whole collision and after: the same motion relative to the pair's centre, only the
  // rounding of positions near 0 and near L differs. The lower bead crosses z = 0 and is wrapped.
  bool wrapped = false;
  while (across.time_s() < 0.03) {  // the upper bead leaves at ~0.2 m/s: 6 mm, across z = 0
    across.step();
    inside.step();
    for (std::size_t i = 0; i < 2; ++i) {
      ASSERT_GE(a.z[i], 0.0);
      ASSERT_LT(a.z[i], kPeriod_m);
    }
    wrapped = wrapped || a.z[0] > 0.5 * kPeriod_m;
  }
  EXPECT_TRUE(wrapped) << "z " << a.z[0] << ", vz " << a.vz[0];
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_NEAR(a.vx[i], b.vx[i], 1e-12);
    EXPECT_NEAR(a.vz[i], b.vz[i], 1e-12);
    EXPECT_NEAR(a.wy[i], b.wy[i], 1e-9);
    const double dz_across = std::remainder(a.z[i] - b.z[i] + 0.5 * kPeriod_m, kPeriod_m);
    EXPECT_NEAR(dz_across, 0.0, 1e-12) << "bead " << i;
  }
  // The beads separate after the collision (restitution 0.5): the contact really happened.
  EXPECT_GT(b.vz[0] - b.vz[1], 0.1);
}

TEST(DrumPeriodic, PeriodShorterThanTheCutoffIsRefused) {
  const auto bad = drum::parse_drum_scene(
      "[drum]\nradius_m = 0.04\nlength_m = 0.009\naxial = \"periodic\"\nfroude = 0.05\n[[species]]\ndiameter_m = 0.004\n",
      "short.toml");
  try {
    drum::make_drum_engine(bad, 0.0);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("short.toml: drum.length_m"), std::string::npos) << e.what();
  }
}

// A small periodic drum (no end walls at all): every particle stays, positions stay in [0, L), and the bed
// rolls at Fr 0.02 with an angle near the material's, as the end-walled drum of test_drum.cpp. Four
// diameters of period: at three (L 12 mm) the bed sat on the rolling/cascading line (surface sagitta 0.11
// against 0.12, co-rotating 0.48 against slumping's 0.5) and a last-bit change flipped it; at 16 mm the
// sagitta is 0.05 and co-rotating 0.22–0.26 (N_c 11, 12, 13).
TEST(DrumPeriodic, SmallDrumKeepsItsParticlesAndRolls) {
  const auto s = spread::testing::small_test_drum({"drum.length_m=0.016", "drum.axial=periodic"});
  ASSERT_EQ(s.axial, drum::AxialBoundary::kPeriodic);
  const auto r = drum::run_drum(s);
  std::size_t active = 0;
  for (std::size_t i = 0; i < r.final_particles.size(); ++i) {
    if (!r.final_particles.active[i]) continue;
    ++active;
    EXPECT_GE(r.final_particles.z[i], 0.0);
    EXPECT_LT(r.final_particles.z[i], s.length_m);
  }
  EXPECT_EQ(active, r.particles);
  EXPECT_TRUE(r.settled);
  EXPECT_EQ(r.evidence.regime, drum::Regime::kRolling) << r.evidence.reason;
  EXPECT_GT(r.evidence.angle_of_repose_deg, 15.0) << r.evidence.reason;
  EXPECT_LT(r.evidence.angle_of_repose_deg, 40.0);
}
