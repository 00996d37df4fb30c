#include "libspread/physics/drum/drum_packing.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <tuple>

namespace spread::drum {

std::size_t particle_count(const DrumScene& s) {
  double v_mean = 0.0;
  for (const auto& x : s.species) v_mean += x.number_fraction * kPi / 6.0 * x.diameter_m * x.diameter_m * x.diameter_m;
  const double r_free = free_radius_m(s);  // inside a bead lining the bed fills the space within the bead tips
  const double bed = s.fill_fraction * kPi * r_free * r_free * s.length_m * s.bed_solid_fraction;
  return static_cast<std::size_t>(std::max(1.0, std::round(bed / v_mean)));
}

std::vector<PlacedParticle> grid_packing(const DrumScene& s, double spacing_factor) {
  double dmax = 0.0;
  for (const auto& x : s.species) dmax = std::max(dmax, x.diameter_m);
  const double h = spacing_factor * dmax;
  const double rmax = 0.5 * dmax;
  const double rho_max = free_radius_m(s) - 0.5 * h - 1e-3 * rmax;  // cell centre at least half a cell from the wall
  std::vector<std::tuple<double, double, double>> nodes;       // (y, x, z): sorted bottom first
  const int nxy = static_cast<int>(std::floor(rho_max / h));
  std::vector<double> zs;
  for (double z = 0.5 * h; z <= s.length_m - 0.5 * h + 1e-12; z += h) zs.push_back(z);
  if (zs.empty()) zs.push_back(0.5 * s.length_m);
  for (int i = -nxy; i <= nxy; ++i)
    for (int j = -nxy; j <= nxy; ++j) {
      const double x = i * h, y = j * h;
      if (std::hypot(x, y) > rho_max) continue;
      for (double z : zs) nodes.emplace_back(y, x, z);
    }
  std::sort(nodes.begin(), nodes.end());
  const std::size_t n = particle_count(s);
  if (n > nodes.size())
    throw std::invalid_argument(s.source_name + ": drum.fill_fraction: " + std::to_string(n) + " particles do not fit the " +
                                std::to_string(nodes.size()) + " grid cells of the drum; lower the fill fraction");
  std::vector<PlacedParticle> out(n);
  const std::size_t n0 = s.species.size() == 1 ? n : static_cast<std::size_t>(std::round(s.species[0].number_fraction * static_cast<double>(n)));
  for (std::size_t k = 0; k < n; ++k) {
    const auto& [y, x, z] = nodes[k];
    out[k].position_m = Vec3(x, y, z);
    out[k].species = k < n0 ? 0 : 1;
    out[k].radius_m = 0.5 * s.species[static_cast<std::size_t>(out[k].species)].diameter_m;
  }
  return out;
}

}  // namespace spread::drum
