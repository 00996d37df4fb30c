#include "libspread/physics/dem/sphere_wall.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

namespace spread::dem {

namespace {
// Cells beyond this many per bead are wasted memory (a thin lining in a large box): the grid coarsens.
constexpr double kMaxCellsPerBead = 8.0;
constexpr double kMinCellBudget = 4096.0;
}  // namespace

SphereWall::SphereWall(const std::vector<Vec3>& centres_m, const std::vector<double>& radii_m) {
  if (centres_m.empty()) throw std::invalid_argument("sphere wall: no beads");
  if (centres_m.size() != radii_m.size())
    throw std::invalid_argument("sphere wall: " + std::to_string(centres_m.size()) + " centres but " +
                                std::to_string(radii_m.size()) + " radii");
  if (centres_m.size() > kMaxBeads)
    throw std::invalid_argument("sphere wall: " + std::to_string(centres_m.size()) + " beads, at most " +
                                std::to_string(kMaxBeads));
  Vec3 lo = centres_m.front(), hi = centres_m.front();
  min_inner_axis_distance_m_ = std::numeric_limits<double>::infinity();
  for (std::size_t b = 0; b < centres_m.size(); ++b) {
    if (!centres_m[b].allFinite()) throw std::invalid_argument("sphere wall: bead " + std::to_string(b) + ": centre is not finite");
    if (!(radii_m[b] > 0.0) || !std::isfinite(radii_m[b]))
      throw std::invalid_argument("sphere wall: bead " + std::to_string(b) + ": radius must be > 0");
    lo = lo.cwiseMin(centres_m[b]);
    hi = hi.cwiseMax(centres_m[b]);
    max_radius_m_ = std::max(max_radius_m_, radii_m[b]);
    const double rho = std::hypot(centres_m[b].x(), centres_m[b].y());
    min_inner_axis_distance_m_ = std::min(min_inner_axis_distance_m_, rho - radii_m[b]);
    max_axis_distance_m_ = std::max(max_axis_distance_m_, rho + radii_m[b]);
  }
  // Cell one bead diameter wide: a particle no larger than a bead searches 3 cells per axis.
  cell_m_ = 2.0 * max_radius_m_;
  const Vec3 extent = hi - lo;
  auto cells_along = [&](double e) { return std::max(1, static_cast<int>(std::floor(e / cell_m_)) + 1); };
  const double budget = std::max(kMinCellBudget, kMaxCellsPerBead * static_cast<double>(centres_m.size()));
  while (static_cast<double>(cells_along(extent.x())) * cells_along(extent.y()) * cells_along(extent.z()) > budget)
    cell_m_ *= 2.0;
  lo_m_ = lo;
  nx_ = cells_along(extent.x());
  ny_ = cells_along(extent.y());
  nz_ = cells_along(extent.z());
  auto cell_of = [&](const Vec3& c) {
    const int i = std::min(nx_ - 1, static_cast<int>((c.x() - lo_m_.x()) / cell_m_));
    const int j = std::min(ny_ - 1, static_cast<int>((c.y() - lo_m_.y()) / cell_m_));
    const int k = std::min(nz_ - 1, static_cast<int>((c.z() - lo_m_.z()) / cell_m_));
    return (static_cast<std::size_t>(k) * static_cast<std::size_t>(ny_) + static_cast<std::size_t>(j)) * static_cast<std::size_t>(nx_) +
           static_cast<std::size_t>(i);
  };
  const std::size_t ncell = static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_) * static_cast<std::size_t>(nz_);
  std::vector<std::size_t> cell(centres_m.size());
  for (std::size_t b = 0; b < centres_m.size(); ++b) cell[b] = cell_of(centres_m[b]);
  std::vector<std::uint32_t> order(centres_m.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return cell[a] < cell[b]; });
  cell_start_.assign(ncell + 1, 0);
  for (std::size_t b = 0; b < centres_m.size(); ++b) ++cell_start_[cell[b] + 1];
  std::partial_sum(cell_start_.begin(), cell_start_.end(), cell_start_.begin());
  for (std::uint32_t b : order) {
    x_m_.push_back(centres_m[b].x());
    y_m_.push_back(centres_m[b].y());
    z_m_.push_back(centres_m[b].z());
    radius_m_.push_back(radii_m[b]);
  }
}

int SphereWall::query(const Vec3& c, double radius_m, BeadContact* out, int max_out) const {
  if (radius_m_.empty() || max_out <= 0) return 0;
  // Exact early-out: |x − x_b| ≥ ρ_b − ρ, so ρ + r ≤ ρ_b − R_b for every bead means no overlap.
  if (std::hypot(c.x(), c.y()) + radius_m <= min_inner_axis_distance_m_) return 0;
  const double reach = radius_m + max_radius_m_;
  auto range = [&](double v, double lo, int n, int& a, int& b) {
    a = static_cast<int>(std::floor((v - reach - lo) / cell_m_));
    b = static_cast<int>(std::floor((v + reach - lo) / cell_m_));
    a = std::max(a, 0);
    b = std::min(b, n - 1);
    return a <= b;
  };
  int i0, i1, j0, j1, k0, k1;
  if (!range(c.x(), lo_m_.x(), nx_, i0, i1) || !range(c.y(), lo_m_.y(), ny_, j0, j1) || !range(c.z(), lo_m_.z(), nz_, k0, k1))
    return 0;
  int n = 0;
  for (int k = k0; k <= k1; ++k)
    for (int j = j0; j <= j1; ++j) {
      const std::size_t row = (static_cast<std::size_t>(k) * static_cast<std::size_t>(ny_) + static_cast<std::size_t>(j)) *
                              static_cast<std::size_t>(nx_);
      for (std::uint32_t q = cell_start_[row + static_cast<std::size_t>(i0)]; q < cell_start_[row + static_cast<std::size_t>(i1) + 1]; ++q) {
        const double dx = c.x() - x_m_[q], dy = c.y() - y_m_[q], dz = c.z() - z_m_[q];
        const double cut = radius_m + radius_m_[q];
        const double d2 = dx * dx + dy * dy + dz * dz;
        if (d2 >= cut * cut || d2 == 0.0) continue;
        const double d = std::sqrt(d2);
        BeadContact bc;
        bc.normal = Vec3(dx, dy, dz) / d;
        bc.distance_m = d - radius_m_[q];
        // Each body takes half the overlap δ (seed 001): the contact point is R_b − δ/2 from the bead centre.
        const double overlap = cut - d;
        bc.point = Vec3(x_m_[q], y_m_[q], z_m_[q]) + (radius_m_[q] - 0.5 * overlap) * bc.normal;
        bc.bead = q;
        // Keep the max_out closest (insertion into a short sorted list).
        int at = n < max_out ? n : max_out;
        if (n < max_out) ++n;
        else if (bc.distance_m >= out[max_out - 1].distance_m) continue;
        else at = max_out - 1;
        while (at > 0 && out[at - 1].distance_m > bc.distance_m) {
          out[at] = out[at - 1];
          --at;
        }
        out[at] = bc;
      }
    }
  return n;
}

int SphereWall::material_for(double particle_radius_m, int fallback) const {
  int best = fallback;
  double gap = std::numeric_limits<double>::infinity();
  for (const auto& m : materials_by_radius) {
    const double g = std::abs(m.particle_radius_m - particle_radius_m);
    if (g < gap) {
      gap = g;
      best = m.material;
    }
  }
  return best;
}

SphereWall make_cylinder_bead_lining(double cylinder_radius_m, double length_m, double bead_diameter_m) {
  if (!(bead_diameter_m > 0.0) || !(bead_diameter_m <= 0.5 * cylinder_radius_m))
    throw std::invalid_argument("bead lining: bead diameter " + std::to_string(bead_diameter_m) +
                                " m must be in (0, cylinder radius / 2]");
  if (!(bead_diameter_m <= length_m))
    throw std::invalid_argument("bead lining: bead diameter " + std::to_string(bead_diameter_m) +
                                " m must not exceed the cylinder length " + std::to_string(length_m) + " m");
  const double rb = 0.5 * bead_diameter_m;
  const double ring_radius = cylinder_radius_m - rb;
  // Largest n with chord 2 ρ_c sin(π/n) ≥ d_b: neighbouring beads in a ring do not overlap.
  const int per_ring = static_cast<int>(std::floor(kPi / std::asin(rb / ring_radius)));
  const int rings = std::max(1, static_cast<int>(std::floor(length_m / bead_diameter_m)));
  const double pitch = 2.0 * kPi / per_ring;
  std::vector<Vec3> centres;
  std::vector<double> radii;
  for (int k = 0; k < rings; ++k) {
    const double z = (k + 0.5) * length_m / rings;
    const double offset = (k % 2) ? 0.5 * pitch : 0.0;
    for (int i = 0; i < per_ring; ++i) {
      const double a = offset + i * pitch;
      centres.emplace_back(ring_radius * std::cos(a), ring_radius * std::sin(a), z);
      radii.push_back(rb);
    }
  }
  return SphereWall(centres, radii);
}

Material bead_contact_material(const Material& particle, double particle_radius_m, double bead_radius_m) {
  if (!(particle_radius_m > 0.0) || !(bead_radius_m > 0.0))
    throw std::invalid_argument("bead contact material: particle and bead radii must be > 0");
  validate_material(particle);
  const double f = 0.5 * std::sqrt(bead_radius_m / (particle_radius_m + bead_radius_m));
  Material bead = particle;
  bead.name = particle.name + " bead contact";
  bead.rigid = false;
  bead.youngs_modulus_pa = particle.youngs_modulus_pa * f / (1.0 - f);
  return bead;
}

double bead_rolling_friction(double rolling_friction, double particle_radius_m, double bead_radius_m) {
  return rolling_friction * bead_radius_m / (particle_radius_m + bead_radius_m);
}

}  // namespace spread::dem
