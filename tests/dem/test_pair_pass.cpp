// The particle–particle pass: one thread adds each pair straight into the sums, several threads
// store per-pair results and gather them; both must give bit-identical states. The block is large enough
// (> 4096 particles and pairs) for the threaded path to run.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>

#include "libspread/core/cpu_features.hpp"
#include "libspread/physics/dem/engine.hpp"
#include "libspread/physics/dem/neighbor_list.hpp"

using namespace spread;
using namespace spread::dem;

namespace {

// Linear springs (k_n 1000 N/m), velocity Verlet, particles of radii in [r_min, r_max] (m).
EngineParams linear_verlet(double r_min_m, double r_max_m) {
  EngineParams ep;
  ep.contact_law = kLinearSpringDashpotLaw;
  ep.linear.normal_stiffness_n_m = 1000.0;
  ep.integrator = Integrator::kVelocityVerlet;
  ep.min_particle_radius_m = r_min_m;
  ep.max_particle_radius_m = r_max_m;
  return ep;
}

// uniform: one radius for all (the material pair's coefficients tabulated, the law in lanes where the
// processor has them); else radii varied, every pair's coefficients its own.
// speed: scales the initial velocities (1: a gentle fall).
DemEngine dense_block(int threads, bool uniform = false, bool periodic = false, double speed = 1.0) {
  Material p;
  p.name = "bead";
  p.friction_particle = p.friction_wall = 0.5;
  p.restitution = 0.5;
  p.youngs_modulus_pa = 5e7;
  Material w = p;
  w.rigid = true;
  WallGroup floor;
  floor.pieces.push_back(make_plane(Vec3::Zero(), Vec3::UnitZ()));
  floor.material = 1;
  WallSet walls;
  walls.groups.push_back(floor);
  EngineParams ep = linear_verlet(1.8e-3, 2.0e-3);
  ep.impact_speed_m_s = 1.0;
  ep.threads = threads;
  if (periodic) ep.periodic_z = {true, 0.0, 8 * 3.99e-3};  // the 8 layers, the top one touching the bottom one
  DemEngine e({p, w}, {}, walls, ep);
  // 24 × 24 × 8 grid, neighbours just touching (spacing 3.99 mm for radii up to 2 mm), sizes and
  // velocities varied deterministically so that every pair differs.
  int k = 0;
  for (int ix = 0; ix < 24; ++ix)
    for (int iy = 0; iy < 24; ++iy)
      for (int iz = 0; iz < 8; ++iz, ++k)
        e.add_particle(Vec3(ix * 3.99e-3, iy * 3.99e-3, 2.0e-3 + iz * 3.99e-3),
                       speed * Vec3(0.01 * ((k * 7) % 5 - 2), 0.01 * ((k * 3) % 5 - 2), -0.05),
                       uniform ? 1.995e-3 : 1.8e-3 + 0.2e-3 * ((k * 11) % 10) / 9.0, 0,
                       Vec3(0.0, 0.0, 0.5 * ((k * 5) % 3 - 1)));
  return e;
}

// Limits the registers for its lifetime and gives the widest back at its end, also when an assertion returns
// early, so that a failing test leaves the rest of the binary on the widest registers.
class RegistersLimited {
 public:
  explicit RegistersLimited(Registers limit) { limit_registers(limit); }
  ~RegistersLimited() { limit_registers(Registers::kAvx512); }
  RegistersLimited(const RegistersLimited&) = delete;
  RegistersLimited& operator=(const RegistersLimited&) = delete;
};

// The threaded passes run from 4,096 particles and 4,096 listed pairs on (DemEngine::threads_share_pairs);
// below that, two threads would be compared with one.
void expect_threads_share_pairs(const DemEngine& e) {
  ASSERT_GE(e.active_count(), 4096u);
  ASSERT_GE(e.pair_count(), 4096u);
}

// Positions, velocities, spins and the last forces of two engines' particles, bit for bit; returns how
// many particles were pushed sideways (only contacts push sideways).
std::size_t expect_identical_states(const DemEngine& first, const DemEngine& second) {
  const auto& a = first.particles();
  const auto& b = second.particles();
  EXPECT_EQ(a.size(), b.size());
  std::size_t pushed = 0;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
    for (const auto field : {&ParticleArrays::x, &ParticleArrays::y, &ParticleArrays::z, &ParticleArrays::vx, &ParticleArrays::vy, &ParticleArrays::vz,
                             &ParticleArrays::wx, &ParticleArrays::wy, &ParticleArrays::wz, &ParticleArrays::fx, &ParticleArrays::fy, &ParticleArrays::fz}) {
      if ((a.*field)[i] != (b.*field)[i]) {
        ADD_FAILURE() << "particle " << i << " differs";
        return pushed;
      }
    }
    pushed += a.fx[i] != 0.0 ? 1 : 0;
  }
  return pushed;
}

// Two engines from `make`, one stepped with the registers limited to the baseline, one with the widest the
// processor has (AVX-512's passes where it has them), compared state for state.
template <class Make>
void expect_widest_gives_the_portable_bits(const Make& make, int steps) {
  limit_registers(Registers::kAvx512);
  DemEngine widest = make();
  limit_registers(Registers::kBaseline);
  DemEngine portable = make();
  for (int s = 0; s < steps; ++s) portable.step();
  limit_registers(Registers::kAvx512);
  for (int s = 0; s < steps; ++s) widest.step();
  EXPECT_GT(expect_identical_states(widest, portable), 100u);
}

}  // namespace

// Where the processor has AVX-512 two threads run the batched pass, each its own range of particles, the
// sums range after range; elsewhere they store each pair's results and gather them. Either gives the bits of
// one thread, with radii varied (each pair alone) and with one radius (eight pairs in lanes).
TEST(DemPairPass, OneThreadAndTwoThreadsGiveIdenticalStates) {
  for (const bool uniform : {false, true}) {
    SCOPED_TRACE(testing::Message() << "uniform " << uniform);
    DemEngine one = dense_block(1, uniform), two = dense_block(2, uniform);
    for (int s = 0; s < 60; ++s) {
      one.step();
      two.step();
    }
    expect_threads_share_pairs(two);
    EXPECT_GT(expect_identical_states(one, two), 100u);
  }
}

// Two threads storing each pair's results (the form without AVX-512, and with an energy monitor) against
// one thread on the same registers.
TEST(DemPairPass, TwoThreadsStoringThePairsGiveTheBitsOfOne) {
  const RegistersLimited baseline(Registers::kBaseline);
  DemEngine one = dense_block(1), two = dense_block(2);
  for (int s = 0; s < 60; ++s) {
    one.step();
    two.step();
  }
  expect_threads_share_pairs(two);
  EXPECT_GT(expect_identical_states(one, two), 100u);
}

// The pair pass chosen at run time (AVX-512's encoding where the processor has it) gives the bits of the
// portable one: 60 steps of a dense block, every state compared.
// Both with radii varied (each pair alone) and with one radius (eight pairs in lanes), along a periodic axis
// too (the minimum image in lanes).
TEST(DemPairPass, WidestRegistersGiveIdenticalStates) {
  for (const bool uniform : {false, true})
    for (const bool periodic : {false, true}) {
      SCOPED_TRACE(testing::Message() << "uniform " << uniform << ", periodic " << periodic);
      expect_widest_gives_the_portable_bits([&] { return dense_block(1, uniform, periodic); }, 60);
    }
  if (!cpu_has_avx512f()) GTEST_SKIP() << "no AVX-512 here: the portable pass was compared with itself";
}

// The batched pass at every register width — four lanes in pairs of SSE2 registers (the portable pass), four
// in AVX2 registers, eight in AVX-512 registers — gives the bits of the particle-by-particle pass (two threads
// storing the pairs' results on the baseline registers): 60 steps of a dense block, every state compared, with
// radii varied (each pair alone) and one radius (pairs in lanes), along a periodic axis too.
TEST(DemPairPass, EveryRegisterWidthGivesTheSameBits) {
  for (const bool uniform : {false, true})
    for (const bool periodic : {false, true}) {
      SCOPED_TRACE(testing::Message() << "uniform " << uniform << ", periodic " << periodic);
      DemEngine by_particle = dense_block(2, uniform, periodic);
      {
        const RegistersLimited baseline(Registers::kBaseline);
        for (int s = 0; s < 60; ++s) by_particle.step();
      }
      expect_threads_share_pairs(by_particle);
      for (const Registers registers : {Registers::kBaseline, Registers::kAvx2, Registers::kAvx512}) {
        SCOPED_TRACE(testing::Message() << "registers " << static_cast<int>(registers));
        const RegistersLimited limit(registers);
        DemEngine batched = dense_block(1, uniform, periodic);
        for (int s = 0; s < 60; ++s) batched.step();
        EXPECT_GT(expect_identical_states(batched, by_particle), 100u);
      }
    }
  if (!cpu_has_avx2() || !cpu_has_avx512f()) GTEST_SKIP() << "no AVX2 or no AVX-512 here: a width was compared with the portable pass";
}

// SPREAD_REGISTERS limits the registers for the whole program (ctest dem.registers.environment_limits_the_width
// runs this with SPREAD_REGISTERS=avx2; unset, nothing is limited).
TEST(DemRegisters, TheEnvironmentLimitsTheWidth) {
  const char* env = std::getenv("SPREAD_REGISTERS");
  if (env != nullptr && std::string(env) == "avx2") {
    EXPECT_TRUE(registers_allowed(Registers::kAvx2));
    EXPECT_FALSE(registers_allowed(Registers::kAvx512));
    EXPECT_FALSE(cpu_has_avx512f());
  } else {
    EXPECT_TRUE(env == nullptr || std::string(env).empty()) << "run with SPREAD_REGISTERS unset or avx2";
    EXPECT_TRUE(registers_allowed(Registers::kAvx512));
  }
}

// steps(n) gives each step's opening kick and drift to the previous step's pair pass (velocity Verlet): the
// bits of n calls of step(), on one thread (the kick leaves the sums at zero) and two (the wall pass zeroes
// them), on both passes, with a block thrown fast enough to rebuild the near and pair lists at the same steps,
// and with a list longer than a batch (the particle-by-particle pass called from the batched one).
TEST(DemPairPass, StepsGiveTheBitsOfSteppingOneByOne) {
  for (const Registers registers : {Registers::kAvx512, Registers::kBaseline})
    for (const int threads : {1, 2})
      for (const double speed : {1.0, 10.0}) {
        SCOPED_TRACE(testing::Message() << "baseline " << (registers == Registers::kBaseline) << ", threads " << threads
                                        << ", speed " << speed);
        const RegistersLimited limit(registers);
        DemEngine one_by_one = dense_block(threads, true, false, speed), fused = dense_block(threads, true, false, speed);
        for (int s = 0; s < 80; ++s) one_by_one.step();
        fused.steps(80);
        EXPECT_EQ(fused.stats().steps, 80u);
        EXPECT_EQ(fused.stats().pair_list_builds, one_by_one.stats().pair_list_builds);
        EXPECT_EQ(fused.stats().near_list_builds, one_by_one.stats().near_list_builds);
        if (speed > 1.0) {
          EXPECT_GT(fused.stats().near_list_builds, 0u);
        }
        EXPECT_GT(expect_identical_states(fused, one_by_one), 100u);
        EXPECT_EQ(fused.time_s(), one_by_one.time_s());
      }
}

// Particles removed below a loss plane stay in the lists, inactive, until the next pair-list build; the
// batched pass's touch rows give them a NaN radius instead of testing the active flags. The bottom layer of
// the block removed after the first step, the bits of the portable pass, which tests the flags.
TEST(DemPairPass, RemovedParticlesTouchNothingOnEitherPass) {
  auto block = [] {
    DemEngine e = dense_block(1, true);
    Collector loss;
    loss.lost_below_z_m = 2.5e-3;  // the bottom layer's centres are at 2.0 mm
    e.set_collector(loss);
    return e;
  };
  limit_registers(Registers::kAvx512);
  DemEngine widest = block();
  const RegistersLimited baseline(Registers::kBaseline);
  DemEngine portable = block();
  for (int s = 0; s < 40; ++s) portable.step();
  limit_registers(Registers::kAvx512);
  for (int s = 0; s < 40; ++s) widest.step();
  EXPECT_EQ(widest.stats().lost, 24u * 24u);
  EXPECT_EQ(widest.stats().pair_list_builds, 1u);  // no build since: the removed ones are still listed
  EXPECT_LT(widest.active_count(), widest.particles().size());
  EXPECT_GT(expect_identical_states(widest, portable), 100u);
  if (!cpu_has_avx512f()) GTEST_SKIP() << "no AVX-512 here: the portable pass was compared with itself";
}

// One thread looks at the near list only (the pairs within half the skin, rebuilt as particles move),
// two threads storing the pairs' results at every listed pair: a block thrown ten times as fast, so that
// the near list is rebuilt between pair-list builds and leaves pairs out that touch later, gives the same
// bits either way.
TEST(DemPairPass, NearListGivesTheBitsOfTheWholeList) {
  DemEngine one = dense_block(1, true, false, 10.0), two = dense_block(2, true, false, 10.0);
  for (int s = 0; s < 150; ++s) one.step();
  {
    const RegistersLimited baseline(Registers::kBaseline);  // two threads store the pairs' results there
    for (int s = 0; s < 150; ++s) two.step();
  }
  expect_threads_share_pairs(two);
  EXPECT_GT(one.stats().near_list_builds, 0u);
  EXPECT_GT(expect_identical_states(one, two), 100u);
}

// A particle whose list outgrows the batched pass's batch (256 pairs) goes through the particle-by-particle
// pass: a 6 mm sphere first, in a block of 1 mm ones, gives the bits of the portable pass.
TEST(DemPairPass, AListLongerThanABatchGivesThePortableBits) {
  auto block = [] {
    Material p;
    p.name = "bead";
    p.friction_particle = p.friction_wall = 0.5;
    p.restitution = 0.5;
    EngineParams ep = linear_verlet(1e-3, 6e-3);
    ep.gravity_m_s2 = Vec3::Zero();
    DemEngine e({p}, {}, WallSet{}, ep);
    e.add_particle(Vec3(0.0, 0.0, 0.0), Vec3(0.02, 0.0, 0.0), 6e-3, 0, Vec3(0.0, 0.0, 1.0));
    int k = 0;
    for (int ix = -7; ix <= 7; ++ix)
      for (int iy = -7; iy <= 7; ++iy)
        for (int iz = -7; iz <= 7; ++iz, ++k) {
          const Vec3 c(ix * 1.99e-3, iy * 1.99e-3, iz * 1.99e-3);
          if (c.norm() < 6.9e-3) continue;  // room for the large one
          e.add_particle(c, Vec3(0.0, 0.01 * (k % 3 - 1), 0.0), 1e-3, 0);
        }
    return e;
  };
  expect_widest_gives_the_portable_bits(block, 40);
  {
    DemEngine one_by_one = block(), fused = block();
    for (int s = 0; s < 40; ++s) one_by_one.step();
    fused.steps(40);
    EXPECT_GT(expect_identical_states(fused, one_by_one), 100u);
  }
  if (!cpu_has_avx512f()) GTEST_SKIP() << "no AVX-512 here: the portable pass was compared with itself";
}

// A listed pair farther apart than r_i + r_j + inner skin is left out of the near list, and the spring it
// still held is released; nearer pairs stay, in pair order.
TEST(NearList, LeavesOutOnlyPairsBeyondTheInnerSkin) {
  ParticleArrays p;
  const double r = 1e-3;
  const double mass = 1e-5, inertia = 4e-12;
  // 0–1 touching, 0–2 within the inner skin (0.5 mm) but apart, 1–3 beyond it yet within the skin (1 mm).
  p.push_back(Vec3(0.0, 0.0, 0.0), Vec3::Zero(), Vec3::Zero(), r, mass, inertia, 0, 1, 0.0);
  p.push_back(Vec3(1.9e-3, 0.0, 0.0), Vec3::Zero(), Vec3::Zero(), r, mass, inertia, 0, 2, 0.0);
  p.push_back(Vec3(0.0, 2.4e-3, 0.0), Vec3::Zero(), Vec3::Zero(), r, mass, inertia, 0, 3, 0.0);
  p.push_back(Vec3(1.9e-3 + 2.8e-3, 0.0, 0.0), Vec3::Zero(), Vec3::Zero(), r, mass, inertia, 0, 4, 0.0);
  PairList list;
  build_pair_list(p, 1e-3, list);
  ASSERT_EQ(list.size(), 3u);  // 0–1, 0–2, 1–3
  std::uint32_t far = 0;
  for (std::uint32_t k = 0; k < list.size(); ++k) {
    if (list.first[k] == 1 && list.second[k] == 3) far = k;
    list.held[k] = 1;
    for (int h = 0; h < kHistoryDoubles; ++h) list.history[k * kHistoryDoubles + h] = 0.25;
  }
  NearList near;
  build_near_list(p, 0.5e-3, list, near);
  ASSERT_EQ(near.start.size(), 5u);
  ASSERT_EQ(near.pairs.size(), 2u);
  EXPECT_LT(near.pairs[0], near.pairs[1]);
  for (const std::uint32_t k : near.pairs) {
    EXPECT_NE(k, far);
    EXPECT_EQ(list.held[k], 1);
    EXPECT_EQ(list.history[k * kHistoryDoubles], 0.25);
  }
  EXPECT_EQ(list.held[far], 0);
  for (int h = 0; h < kHistoryDoubles; ++h) EXPECT_EQ(list.history[far * kHistoryDoubles + h], 0.0);
}

TEST(DemPairPass, NewtonsThirdLawHoldsWithoutWallsOrGravity) {
  // Without walls and gravity the pair forces are the only forces: they sum to zero (to rounding).
  Material p;
  p.name = "bead";
  EngineParams ep;
  ep.contact_law = kLinearSpringDashpotLaw;
  ep.linear.normal_stiffness_n_m = 1000.0;
  ep.integrator = Integrator::kVelocityVerlet;
  ep.min_particle_radius_m = 2e-3;
  ep.gravity_m_s2 = Vec3::Zero();
  DemEngine e({p}, {}, WallSet{}, ep);
  int k = 0;
  for (int ix = 0; ix < 6; ++ix)
    for (int iy = 0; iy < 6; ++iy, ++k)
      e.add_particle(Vec3(ix * 3.9e-3, iy * 3.9e-3, 0.0), Vec3(0.02 * (k % 3 - 1), 0.0, 0.01 * (k % 2)), 2e-3, 0);
  e.step();
  double fx = 0.0, fy = 0.0, fz = 0.0, fmax = 0.0;
  const auto& q = e.particles();
  for (std::size_t i = 0; i < q.size(); ++i) {
    fx += q.fx[i];
    fy += q.fy[i];
    fz += q.fz[i];
    fmax = std::max(fmax, std::abs(q.fx[i]));
  }
  ASSERT_GT(fmax, 0.05);  // overlaps of 0.1 mm at k_n 1000 N/m: 0.1 N
  EXPECT_NEAR(fx, 0.0, 1e-12 * fmax);
  EXPECT_NEAR(fy, 0.0, 1e-12 * fmax);
  EXPECT_NEAR(fz, 0.0, 1e-12 * fmax);
}
