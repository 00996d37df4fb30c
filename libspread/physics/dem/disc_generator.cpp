#include "libspread/physics/dem/disc_generator.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace spread::dem {

namespace {
void validate(const DiscGeometry& g) {
  auto bad = [](const char* what) { throw std::invalid_argument(std::string("disc geometry: ") + what); };
  if (!(g.radius_m > 0.0)) bad("radius_m must be > 0");
  if (!(std::abs(g.cone_angle_rad) < 1.3)) bad("cone_angle_rad must be within (-1.3, 1.3)");
  if (g.vane_count < 0) bad("vane_count must be >= 0");
  if (g.vane_count > 0) {
    const double end = g.vane_end_radius_m > 0.0 ? g.vane_end_radius_m : g.radius_m;
    if (!(g.vane_start_radius_m >= 0.0) || !(end > g.vane_start_radius_m)) bad("vanes need 0 <= start radius < end radius");
    if (end > g.radius_m * (1.0 + 1e-9)) bad("vane_end_radius_m must not exceed the disc radius");
    if (!(g.vane_height_m > 0.0)) bad("vane_height_m must be > 0");
    if (!(std::abs(g.vane_pitch_rad) < 1.4)) bad("vane_pitch_rad must be within (-1.4, 1.4)");
  }
  if (g.mesh_size_m < 0.0) bad("mesh_size_m must be >= 0");
  if (g.mesh && g.mesh->triangles.empty()) bad("the given disc mesh has no triangle");
}

struct VaneLine { Vec3 start, end; };
// Straight vane from radius r_s at the given polar angle, leaning by the pitch, ending at radius r_e:
// |P_s + L d| = r_e  →  L = −r_s cos ψ + sqrt(r_e² − r_s² sin² ψ).
VaneLine vane_line(const DiscGeometry& g, int k) {
  const double r_s = g.vane_start_radius_m;
  const double r_e = g.vane_end_radius_m > 0.0 ? g.vane_end_radius_m : g.radius_m;
  const double phi = g.first_vane_angle_rad + 2.0 * kPi * k / g.vane_count;
  const Vec3 er(std::cos(phi), std::sin(phi), 0.0), et(-std::sin(phi), std::cos(phi), 0.0);
  const double psi = g.vane_pitch_rad;
  const Vec3 d = std::cos(psi) * er + std::sin(psi) * et;
  const double len = -r_s * std::cos(psi) + std::sqrt(r_e * r_e - r_s * r_s * std::sin(psi) * std::sin(psi));
  Vec3 a = r_s * er, b = a + len * d;
  const double t = std::tan(g.cone_angle_rad);
  a.z() = g.z_apex_m + t * std::hypot(a.x(), a.y());
  b.z() = g.z_apex_m + t * std::hypot(b.x(), b.y());
  return {a, b};
}
}  // namespace

TriangleMesh mesh_cone_disc(double radius_m, double cone_angle_rad, double z_apex_m, double xi) {
  if (!(xi > 0.0)) throw std::invalid_argument("disc mesh: mesh_size_m must be > 0");
  std::vector<std::array<Vec3, 3>> soup;
  const int rings = std::max(1, static_cast<int>(std::ceil(radius_m / xi)));
  const double t = std::tan(cone_angle_rad);
  auto ring = [&](int k) {
    std::vector<Vec3> pts;
    const double rho = radius_m * k / rings;
    const int n = k == 0 ? 1 : std::max(6, static_cast<int>(std::ceil(2.0 * kPi * rho / xi)));
    for (int j = 0; j < n; ++j) {
      const double a = 2.0 * kPi * j / n;
      pts.emplace_back(rho * std::cos(a), rho * std::sin(a), z_apex_m + t * rho);
    }
    return pts;
  };
  std::vector<Vec3> inner = ring(0);
  for (int k = 1; k <= rings; ++k) {
    std::vector<Vec3> outer = ring(k);
    const std::size_t ni = inner.size(), no = outer.size();
    if (ni == 1) {
      for (std::size_t j = 0; j < no; ++j) soup.push_back({inner[0], outer[j], outer[(j + 1) % no]});
    } else {
      // Zipper between two rings by angle: always advance the ring whose next node comes first.
      std::size_t i = 0, o = 0;
      while (i < ni || o < no) {
        const double ai = static_cast<double>(i + 1) / static_cast<double>(ni);
        const double ao = static_cast<double>(o + 1) / static_cast<double>(no);
        if (o < no && (i >= ni || ao <= ai)) {
          soup.push_back({inner[i % ni], outer[o % no], outer[(o + 1) % no]});
          ++o;
        } else {
          soup.push_back({inner[i % ni], outer[o % no], inner[(i + 1) % ni]});
          ++i;
        }
      }
    }
    inner = std::move(outer);
  }
  return weld_triangle_soup(soup, xi * 1e-6);
}

TriangleMesh mesh_disc_with_vanes(const DiscGeometry& g) {
  validate(g);
  if (g.mesh) return *g.mesh;
  TriangleMesh disc = mesh_cone_disc(g.radius_m, g.cone_angle_rad, g.z_apex_m, g.mesh_size_m);
  std::vector<std::array<Vec3, 3>> soup;
  for (const auto& tri : disc.triangles) soup.push_back({disc.vertices[tri[0]], disc.vertices[tri[1]], disc.vertices[tri[2]]});
  for (int k = 0; k < g.vane_count; ++k) {
    const VaneLine line = vane_line(g, k);
    const Vec3 u = line.end - line.start;
    const int nu = std::max(1, static_cast<int>(std::ceil(u.norm() / g.mesh_size_m)));
    const int nv = std::max(1, static_cast<int>(std::ceil(g.vane_height_m / g.mesh_size_m)));
    for (int a = 0; a < nu; ++a)
      for (int b = 0; b < nv; ++b) {
        auto node = [&](int i, int j) {
          return Vec3(line.start + u * (static_cast<double>(i) / nu) + Vec3(0, 0, g.vane_height_m * j / nv));
        };
        soup.push_back({node(a, b), node(a + 1, b), node(a + 1, b + 1)});
        soup.push_back({node(a, b), node(a + 1, b + 1), node(a, b + 1)});
      }
  }
  return weld_triangle_soup(soup, g.mesh_size_m * 1e-6);
}

WallGroup make_disc(const DiscGeometry& g, double rpm, int material, double max_particle_radius_m) {
  validate(g);
  WallGroup group;
  group.name = "disc";
  group.material = material;
  group.angular_velocity_rad_s = rpm * 2.0 * kPi / 60.0;
  if (g.mesh) {
    group.meshes.emplace_back(*g.mesh, max_particle_radius_m);
    return group;
  }
  if (g.mesh_size_m > 0.0) {
    group.meshes.emplace_back(mesh_disc_with_vanes(g), max_particle_radius_m);
    return group;
  }
  group.pieces.push_back(make_cone_disc(g.radius_m, g.cone_angle_rad, g.z_apex_m));
  for (int k = 0; k < g.vane_count; ++k) {
    const VaneLine line = vane_line(g, k);
    const Vec3 u = line.end - line.start;
    group.pieces.push_back(make_rectangle(line.start, u, u.norm(), Vec3::UnitZ(), g.vane_height_m));
  }
  return group;
}

}  // namespace spread::dem
