#include "libspread/physics/dem/vtk_writer.hpp"

#include <array>
#include <cmath>
#include <fstream>
#include <stdexcept>
#include <vector>

namespace spread::dem {

void write_particles_vtk(const ParticleArrays& p, const std::string& path) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write VTK file '" + path + "'");
  std::size_t n = 0;
  for (std::size_t i = 0; i < p.size(); ++i) n += p.active[i] ? 1 : 0;
  out << "# vtk DataFile Version 3.0\nlibspread particles\nASCII\nDATASET POLYDATA\nPOINTS " << n << " double\n";
  out.precision(9);
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.active[i]) out << p.x[i] << ' ' << p.y[i] << ' ' << p.z[i] << '\n';
  out << "POINT_DATA " << n << "\nSCALARS radius_m double 1\nLOOKUP_TABLE default\n";
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.active[i]) out << p.radius_m[i] << '\n';
  out << "VECTORS velocity_m_s double\n";
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.active[i]) out << p.vx[i] << ' ' << p.vy[i] << ' ' << p.vz[i] << '\n';
  if (!out) throw std::runtime_error("cannot write VTK file '" + path + "'");
}

namespace {

// Triangles in the inertial frame, collected before writing (the header needs the counts).
struct TriangleSoup {
  std::vector<Vec3> points;
  std::vector<int> group_of_triangle;

  void add(const Vec3& a, const Vec3& b, const Vec3& c, int group) {
    points.push_back(a);
    points.push_back(b);
    points.push_back(c);
    group_of_triangle.push_back(group);
  }
};

// The group frame turns about the vertical axis through centre_m (wall_set.hpp): inertial point =
// centre + Rz(θ) · local, θ = initial angle + ω t.
struct GroupPose {
  Vec3 centre_m;
  double cos_theta, sin_theta;
  Vec3 place(const Vec3& local) const {
    return centre_m + Vec3(cos_theta * local.x() - sin_theta * local.y(),
                           sin_theta * local.x() + cos_theta * local.y(), local.z());
  }
};

void add_piece(const AnalyticPiece& piece, const GroupPose& pose, int group, int segments,
               double plane_half_size_m, TriangleSoup& soup) {
  switch (piece.kind) {
    case PieceKind::kRevolution: {
      const double step_rad = 2.0 * M_PI / segments;
      for (int k = 0; k < segments; ++k) {
        const double a0 = k * step_rad, a1 = (k + 1) * step_rad;
        const auto at = [&](double rho, double z, double a) {
          return pose.place(Vec3(rho * std::cos(a), rho * std::sin(a), z));
        };
        const Vec3 p00 = at(piece.rho0_m, piece.z0_m, a0), p01 = at(piece.rho0_m, piece.z0_m, a1);
        const Vec3 p10 = at(piece.rho1_m, piece.z1_m, a0), p11 = at(piece.rho1_m, piece.z1_m, a1);
        if (piece.rho0_m > 0.0) soup.add(p00, p10, p01, group);  // at the apex (ρ0 = 0) that one is empty
        if (piece.rho1_m > 0.0) soup.add(p01, p10, p11, group);
      }
      break;
    }
    case PieceKind::kRectangle: {
      const Vec3 u = piece.axis_u * piece.length_u_m, v = piece.axis_v * piece.length_v_m;
      const Vec3 o = pose.place(piece.origin), ou = pose.place(piece.origin + u), ov = pose.place(piece.origin + v),
                 ouv = pose.place(piece.origin + u + v);
      soup.add(o, ou, ouv, group);
      soup.add(o, ouv, ov, group);
      break;
    }
    case PieceKind::kPlane: {
      // Any two unit tangents: cross the normal with the coordinate axis it is least aligned with.
      const Vec3 n = piece.normal.normalized();
      const Vec3 helper = std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
      const Vec3 t1 = n.cross(helper).normalized() * plane_half_size_m;
      const Vec3 t2 = n.cross(t1);
      const Vec3 c = piece.origin;
      soup.add(pose.place(c - t1 - t2), pose.place(c + t1 - t2), pose.place(c + t1 + t2), group);
      soup.add(pose.place(c - t1 - t2), pose.place(c + t1 + t2), pose.place(c - t1 + t2), group);
      break;
    }
  }
}

}  // namespace

void write_walls_vtk(const WallSet& walls, double t_s, const std::string& path, int segments,
                     double plane_half_size_m) {
  if (segments < 3) throw std::invalid_argument("write_walls_vtk: segments must be >= 3");
  TriangleSoup soup;
  for (std::size_t g = 0; g < walls.groups.size(); ++g) {
    const WallGroup& group = walls.groups[g];
    const double theta_rad = group.initial_angle_rad + group.angular_velocity_rad_s * t_s;
    const GroupPose pose{group.centre_m, std::cos(theta_rad), std::sin(theta_rad)};
    const int index = static_cast<int>(g);
    for (const AnalyticPiece& piece : group.pieces) add_piece(piece, pose, index, segments, plane_half_size_m, soup);
    for (const MeshCollider& mesh : group.meshes) {
      const auto& v = mesh.mesh().vertices;
      for (const auto& tri : mesh.mesh().triangles) {
        soup.add(pose.place(v[tri[0]]), pose.place(v[tri[1]]), pose.place(v[tri[2]]), index);
      }
    }
  }
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write VTK file '" + path + "'");
  const std::size_t triangles = soup.group_of_triangle.size();
  out << "# vtk DataFile Version 3.0\nlibspread walls at t = " << t_s << " s\nASCII\nDATASET POLYDATA\nPOINTS "
      << soup.points.size() << " double\n";
  out.precision(9);
  for (const Vec3& p : soup.points) out << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
  out << "POLYGONS " << triangles << ' ' << 4 * triangles << '\n';
  for (std::size_t k = 0; k < triangles; ++k) out << "3 " << 3 * k << ' ' << 3 * k + 1 << ' ' << 3 * k + 2 << '\n';
  out << "CELL_DATA " << triangles << "\nSCALARS group int 1\nLOOKUP_TABLE default\n";
  for (int g : soup.group_of_triangle) out << g << '\n';
  if (!out) throw std::runtime_error("cannot write VTK file '" + path + "'");
}

}  // namespace spread::dem
