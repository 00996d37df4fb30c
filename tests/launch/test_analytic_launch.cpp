// Launch samples from the analytic model: determinism, pairing across rpm, distributions, frames.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "libspread/physics/launch/analytic_launch.hpp"
#include "libspread/physics/launch/launch_statistics.hpp"
#include "libspread/physics/launch/patterson_reece.hpp"

namespace spread::launch {
namespace {

scene::Machine flat_machine() {
  scene::Machine m;
  m.disc_radius_m = 0.3;
  m.vane_end_radius_m = 0.3;
  m.cone_angle_rad = 0.0;
  m.vane_count = 4;
  return m;
}

tables::Material material(double mu) {
  tables::Material m;
  m.name = "test";
  m.density_kg_m3 = 1800.0;
  m.diameter_mean_m = 3.2e-3;
  m.diameter_sd_m = 0.6e-3;
  m.friction_wall = mu;
  return m;
}

scene::Inlet inlet() {
  scene::Inlet in;
  in.radius_m = 0.015;
  in.offset_m = 0.08;
  in.angle_rad = 0.5;
  return in;
}

bool same_bits(const std::vector<tables::LaunchSample>& a, const std::vector<tables::LaunchSample>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(tables::LaunchSample)) == 0;
}

TEST(AnalyticLaunch, SameSeedSameSamplesOtherSeedOtherSamples) {
  const auto a = analytic_launch_samples(flat_machine(), material(0.4), 600.0, inlet(), 300, 7);
  const auto b = analytic_launch_samples(flat_machine(), material(0.4), 600.0, inlet(), 300, 7);
  const auto c = analytic_launch_samples(flat_machine(), material(0.4), 600.0, inlet(), 300, 8);
  EXPECT_TRUE(same_bits(a, b));
  EXPECT_FALSE(same_bits(a, c));
}

TEST(AnalyticLaunch, SampleKOfTwoRowsHasTheSameDiameterAndMass) {
  const auto slow = analytic_launch_samples(flat_machine(), material(0.4), 450.0, inlet(), 200, 3);
  const auto fast = analytic_launch_samples(flat_machine(), material(0.4), 750.0, inlet(), 200, 3);
  ASSERT_EQ(slow.size(), fast.size());
  int moved = 0;
  for (std::size_t k = 0; k < slow.size(); ++k) {
    EXPECT_EQ(slow[k].diameter_m, fast[k].diameter_m);
    EXPECT_EQ(slow[k].mass_kg, fast[k].mass_kg);
    moved += slow[k].x_m != fast[k].x_m ? 1 : 0;
  }
  EXPECT_GT(moved, 0);  // the rows differ where they should (launch angle changes with rpm)
}

TEST(AnalyticLaunch, DiametersFollowTheLognormalMeanAndSd) {
  const auto samples = analytic_launch_samples(flat_machine(), material(0.4), 600.0, inlet(), 4000, 1);
  double sum = 0.0, sum2 = 0.0;
  for (const auto& s : samples) {
    sum += s.diameter_m;
    sum2 += static_cast<double>(s.diameter_m) * s.diameter_m;
    EXPECT_NEAR(s.mass_kg, 1800.0 * kPi * std::pow(static_cast<double>(s.diameter_m), 3) / 6.0, 1e-6 * s.mass_kg);
  }
  const double n = static_cast<double>(samples.size());
  const double mean = sum / n;
  const double sd = std::sqrt((sum2 - n * mean * mean) / (n - 1.0));
  EXPECT_NEAR(mean, 3.2e-3, 0.01 * 3.2e-3);
  EXPECT_NEAR(sd, 0.6e-3, 0.03 * 0.6e-3);
}

TEST(AnalyticLaunch, SamplesSitOnTheRimWithTheVaneExitVelocity) {
  const double rpm = 600.0;
  AnalyticLaunchOptions sliding;
  sliding.spin = scene::SpinModel::kSliding;
  const auto samples = analytic_launch_samples(flat_machine(), material(0.4), rpm, inlet(), 100, 2, sliding);
  const double omega = rpm * 2.0 * kPi / 60.0;
  for (const auto& s : samples) {
    EXPECT_NEAR(std::hypot(s.x_m, s.y_m), 0.3, 1e-6);
    // Tangential component of the normalised velocity is exactly the rim speed (ωR / ωR = 1), ccw.
    const double rho = std::hypot(s.x_m, s.y_m);
    const double v_t = (-s.vx_norm * s.y_m + s.vy_norm * s.x_m) / rho;
    const double v_r = (s.vx_norm * s.x_m + s.vy_norm * s.y_m) / rho;
    EXPECT_NEAR(v_t, 1.0, 1e-6);
    EXPECT_GT(v_r, 0.3);
    EXPECT_LT(v_r, 1.0);
    EXPECT_EQ(s.vz_norm, 0.0f);
    EXPECT_NEAR(s.wz_norm, 1.0, 1e-7);  // sliding: turns with the disc
    EXPECT_GT(s.t_s, 0.0f);
  }
  const LaunchStatistics st = launch_statistics(samples, omega * 0.3);
  EXPECT_EQ(st.count, 100);
  EXPECT_GT(st.angle_from_tangent_deg_mean, 20.0);
  EXPECT_LT(st.angle_from_tangent_deg_mean, 45.0);
}

TEST(AnalyticLaunch, ClockwiseDiscMirrorsTheTangentialVelocity) {
  scene::Machine cw = flat_machine();
  cw.rotation_sense = -1;
  AnalyticLaunchOptions sliding;
  sliding.spin = scene::SpinModel::kSliding;  // turns with the disc: ω = sense·Ω ẑ
  const auto samples = analytic_launch_samples(cw, material(0.4), 600.0, inlet(), 50, 2, sliding);
  for (const auto& s : samples) {
    const double rho = std::hypot(s.x_m, s.y_m);
    EXPECT_NEAR((-s.vx_norm * s.y_m + s.vy_norm * s.x_m) / rho, -1.0, 1e-6);
    EXPECT_NEAR(s.wz_norm, -1.0, 1e-7);
  }
}

TEST(AnalyticLaunch, RollingSpinIsAboutTheDiscAxisAlongTheVaneFace) {
  // On a flat disc a granule rolling along the vane face spins about the disc axis, against the disc's
  // sense: ω_z = sense·(Ω − v_r/(d/2)) (thousands of rad/s, as the DEM's launches show).
  for (int sense : {1, -1}) {
    scene::Machine machine = flat_machine();
    machine.rotation_sense = sense;
    const double rpm = 600.0, omega = rpm * 2.0 * kPi / 60.0;
    const auto samples = analytic_launch_samples(machine, material(0.4), rpm, inlet(), 50, 2);  // default model
    for (const auto& s : samples) {
      const double rho = std::hypot(s.x_m, s.y_m);
      const double v_r = (s.vx_norm * s.x_m + s.vy_norm * s.y_m) / rho * omega * 0.3;  // m/s relative, radial
      EXPECT_NEAR(s.wx_norm, 0.0, 1e-9);
      EXPECT_NEAR(s.wy_norm, 0.0, 1e-9);
      const double expected = sense * (omega - v_r / (0.5 * s.diameter_m));
      EXPECT_NEAR(s.wz_norm * omega, expected, 1e-4 * std::abs(expected));
      EXPECT_LT(static_cast<double>(sense) * s.wz_norm * omega, -1000.0);
    }
  }
}

TEST(AnalyticLaunch, RollingSpinOnAConeTiltsWithTheGeneratrix) {
  // ω_rel ⟂ the vane face normal e_θ and ⟂ the motion along the generatrix (cos α e_r + sin α e_z).
  scene::Machine cone = flat_machine();
  cone.cone_angle_rad = 0.157;
  const double rpm = 600.0;
  const auto samples = analytic_launch_samples(cone, material(0.4), rpm, inlet(), 20, 2);
  for (const auto& s : samples) {
    const double rho = std::hypot(s.x_m, s.y_m);
    const double er_x = s.x_m / rho, er_y = s.y_m / rho;
    const double rel_x = s.wx_norm, rel_y = s.wy_norm, rel_z = s.wz_norm - 1.0;  // minus the disc's turn
    const double along = (rel_x * er_x + rel_y * er_y) * std::cos(0.157) + rel_z * std::sin(0.157);
    EXPECT_NEAR(along, 0.0, 1e-5 * std::hypot(rel_z, rel_x, rel_y));
    EXPECT_NEAR(-rel_x * er_y + rel_y * er_x, 0.0, 1e-5 * std::abs(rel_z));  // no e_θ component
  }
}

TEST(AnalyticLaunch, BadInputIsRefused) {
  scene::Machine no_vanes = flat_machine();
  no_vanes.vane_count = 0;
  EXPECT_THROW(analytic_launch_samples(no_vanes, material(0.4), 600.0, inlet(), 10, 1), std::invalid_argument);
  scene::Machine pitched = flat_machine();
  pitched.vane_pitch_rad = 0.2;
  EXPECT_THROW(analytic_launch_samples(pitched, material(0.4), 600.0, inlet(), 10, 1), std::invalid_argument);
  EXPECT_THROW(analytic_launch_samples(flat_machine(), material(0.4), -1.0, inlet(), 10, 1), std::invalid_argument);
  EXPECT_THROW(analytic_launch_samples(flat_machine(), material(0.4), 600.0, inlet(), 0, 1), std::invalid_argument);
}

TEST(InverseNormalCdf, MatchesKnownQuantiles) {
  EXPECT_NEAR(inverse_normal_cdf(0.5), 0.0, 1e-12);
  EXPECT_NEAR(inverse_normal_cdf(0.975), 1.959963984540054, 1e-9);
  EXPECT_NEAR(inverse_normal_cdf(0.001), -3.090232306167814, 1e-9);
}

}  // namespace
}  // namespace spread::launch
