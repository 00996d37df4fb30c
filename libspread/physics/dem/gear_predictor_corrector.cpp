#include "libspread/physics/dem/gear_predictor_corrector.hpp"

#include <stdexcept>
#include <string>
#include <unordered_map>

namespace spread::dem {

namespace {
void check_values(int values) {
  if (values < 4 || values > 6)
    throw std::invalid_argument("gear integrator: " + std::to_string(values) + " values requested; use 4, 5 or 6");
}
}  // namespace

GearCoefficients gear_second_order_coefficients(int values) {
  check_values(values);
  GearCoefficients g;
  g.values = values;
  if (values == 4) g.c = {1.0 / 6.0, 5.0 / 6.0, 1.0, 1.0 / 3.0, 0.0, 0.0};
  if (values == 5) g.c = {19.0 / 120.0, 3.0 / 4.0, 1.0, 1.0 / 2.0, 1.0 / 12.0, 0.0};
  if (values == 6) g.c = {3.0 / 16.0, 251.0 / 360.0, 1.0, 11.0 / 18.0, 1.0 / 6.0, 1.0 / 60.0};
  return g;
}

GearCoefficients gear_first_order_coefficients(int values) {
  check_values(values);
  GearCoefficients g;
  g.values = values;
  if (values == 4) g.c = {3.0 / 8.0, 1.0, 3.0 / 4.0, 1.0 / 6.0, 0.0, 0.0};
  if (values == 5) g.c = {251.0 / 720.0, 1.0, 11.0 / 12.0, 1.0 / 3.0, 1.0 / 24.0, 0.0};
  if (values == 6) g.c = {95.0 / 288.0, 1.0, 25.0 / 24.0, 35.0 / 72.0, 5.0 / 48.0, 1.0 / 120.0};
  return g;
}

GearPredictorCorrector::GearPredictorCorrector(int values)
    : second_(gear_second_order_coefficients(values)),
      first_(gear_first_order_coefficients(values)),
      hi_t_(values - 2),
      hi_w_(values - 1) {}

void GearPredictorCorrector::sync(const ParticleArrays& p) {
  const std::size_t n = p.size();
  if (ids_.size() == n && (n == 0 || (ids_.front() == p.id.front() && ids_.back() == p.id.back()))) {
    // Slots keep their particle unless compaction or an addition happened; ids are unique and both
    // operations keep the order, so equal ends and equal size mean equal sequences.
    return;
  }
  std::unordered_map<std::uint32_t, std::size_t> old_slot;
  old_slot.reserve(ids_.size());
  for (std::size_t s = 0; s < ids_.size(); ++s) old_slot.emplace(ids_[s], s);
  const auto ht = static_cast<std::size_t>(hi_t_), hw = static_cast<std::size_t>(hi_w_);
  std::vector<double> trans(n * 3 * ht, 0.0), spin(p.with_spin ? n * 3 * hw : 0, 0.0);
  std::vector<std::uint8_t> fresh(n, 1);
  for (std::size_t i = 0; i < n; ++i) {
    const auto it = old_slot.find(p.id[i]);
    if (it == old_slot.end()) continue;  // new particle: derivatives from start()
    const std::size_t s = it->second;
    fresh[i] = fresh_[s];
    for (std::size_t k = 0; k < 3 * ht; ++k) trans[i * 3 * ht + k] = trans_[s * 3 * ht + k];
    if (p.with_spin && !spin_.empty())
      for (std::size_t k = 0; k < 3 * hw; ++k) spin[i * 3 * hw + k] = spin_[s * 3 * hw + k];
  }
  ids_ = p.id;
  fresh_.swap(fresh);
  trans_.swap(trans);
  spin_.swap(spin);
}

bool GearPredictorCorrector::needs_start(const ParticleArrays& p) {
  sync(p);
  for (std::uint8_t f : fresh_)
    if (f) return true;
  return false;
}

void GearPredictorCorrector::start(const ParticleArrays& p, const Vec3& g, double dt) {
  sync(p);
  const auto ht = static_cast<std::size_t>(hi_t_), hw = static_cast<std::size_t>(hi_w_);
  const double* force[3] = {p.fx.data(), p.fy.data(), p.fz.data()};
  const double* torque[3] = {p.tx.data(), p.ty.data(), p.tz.data()};
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!fresh_[i]) continue;
    fresh_[i] = 0;
    for (std::size_t c = 0; c < 3; ++c) {
      trans_[(i * 3 + c) * ht] = 0.5 * dt * dt * (force[c][i] / p.mass_kg[i] + g[static_cast<Eigen::Index>(c)]);
      if (p.with_spin) spin_[(i * 3 + c) * hw] = dt * torque[c][i] / p.inertia_kg_m2[i];
    }
  }
}

void GearPredictorCorrector::predict(ParticleArrays& p, double dt) {
  sync(p);
  const int nv = second_.values;
  const auto ht = static_cast<std::size_t>(hi_t_), hw = static_cast<std::size_t>(hi_w_);
  double* pos[3] = {p.x.data(), p.y.data(), p.z.data()};
  double* vel[3] = {p.vx.data(), p.vy.data(), p.vz.data()};
  double* spin[3] = {p.wx.data(), p.wy.data(), p.wz.data()};
  double r[kGearMaxValues];
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!p.active[i]) continue;
    for (std::size_t c = 0; c < 3; ++c) {
      double* hi = &trans_[(i * 3 + c) * ht];
      r[0] = pos[c][i];
      r[1] = vel[c][i] * dt;
      for (std::size_t k = 0; k < ht; ++k) r[k + 2] = hi[k];
      gear_predict_scaled(r, nv);
      pos[c][i] = r[0];
      vel[c][i] = r[1] / dt;
      for (std::size_t k = 0; k < ht; ++k) hi[k] = r[k + 2];
    }
    if (!p.with_spin) continue;
    for (std::size_t c = 0; c < 3; ++c) {
      double* hi = &spin_[(i * 3 + c) * hw];
      r[0] = spin[c][i];
      for (std::size_t k = 0; k < hw; ++k) r[k + 1] = hi[k];
      gear_predict_scaled(r, nv);
      spin[c][i] = r[0];
      for (std::size_t k = 0; k < hw; ++k) hi[k] = r[k + 1];
    }
  }
}

void GearPredictorCorrector::correct(ParticleArrays& p, const Vec3& g, double dt) {
  sync(p);  // the force pass may have compacted the arrays
  const auto ht = static_cast<std::size_t>(hi_t_), hw = static_cast<std::size_t>(hi_w_);
  double* pos[3] = {p.x.data(), p.y.data(), p.z.data()};
  double* vel[3] = {p.vx.data(), p.vy.data(), p.vz.data()};
  double* force[3] = {p.fx.data(), p.fy.data(), p.fz.data()};
  double* spin[3] = {p.wx.data(), p.wy.data(), p.wz.data()};
  double* torque[3] = {p.tx.data(), p.ty.data(), p.tz.data()};
  const double half_dt2 = 0.5 * dt * dt;
  const auto& c2 = second_.c;
  const auto& c1 = first_.c;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!p.active[i]) continue;
    const double inv_m = 1.0 / p.mass_kg[i];
    for (std::size_t c = 0; c < 3; ++c) {
      double* hi = &trans_[(i * 3 + c) * ht];
      // Δ = Δt²/2 · a(predicted) − r_2(predicted)
      const double delta = half_dt2 * (force[c][i] * inv_m + g[static_cast<Eigen::Index>(c)]) - hi[0];
      pos[c][i] += c2[0] * delta;
      vel[c][i] += c2[1] * delta / dt;
      for (std::size_t k = 0; k < ht; ++k) hi[k] += c2[k + 2] * delta;
    }
    if (!p.with_spin) continue;
    const double inv_i = 1.0 / p.inertia_kg_m2[i];
    for (std::size_t c = 0; c < 3; ++c) {
      double* hi = &spin_[(i * 3 + c) * hw];
      const double delta = dt * torque[c][i] * inv_i - hi[0];  // Δ = Δt α − w_1
      spin[c][i] += c1[0] * delta;
      for (std::size_t k = 0; k < hw; ++k) hi[k] += c1[k + 1] * delta;
    }
  }
}

}  // namespace spread::dem
