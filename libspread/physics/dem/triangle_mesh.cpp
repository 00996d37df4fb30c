#include "libspread/physics/dem/triangle_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <tuple>

namespace spread::dem {

TriangleMesh weld_triangle_soup(const std::vector<std::array<Vec3, 3>>& soup, double weld_tolerance_m,
                                MeshLoadReport* report) {
  TriangleMesh mesh;
  // Quantise to the weld tolerance and merge equal keys; deterministic (ordered map).
  const double q = weld_tolerance_m > 0.0 ? weld_tolerance_m : 1e-9;
  std::map<std::tuple<long long, long long, long long>, std::uint32_t> index;
  auto vertex_id = [&](const Vec3& v) {
    const auto key = std::make_tuple(std::llround(v.x() / q), std::llround(v.y() / q), std::llround(v.z() / q));
    auto [it, inserted] = index.emplace(key, static_cast<std::uint32_t>(mesh.vertices.size()));
    if (inserted) mesh.vertices.push_back(v);
    return it->second;
  };
  std::size_t dropped = 0;
  for (const auto& t : soup) {
    const double longest2 = std::max({(t[1] - t[0]).squaredNorm(), (t[2] - t[1]).squaredNorm(), (t[0] - t[2]).squaredNorm()});
    const double area2x = (t[1] - t[0]).cross(t[2] - t[0]).norm();
    if (!(longest2 > 0.0) || !(area2x > 1e-12 * longest2) || !std::isfinite(area2x)) {
      ++dropped;
      continue;
    }
    const std::uint32_t a = vertex_id(t[0]), b = vertex_id(t[1]), c = vertex_id(t[2]);
    if (a == b || b == c || c == a) {
      ++dropped;
      continue;
    }
    mesh.triangles.push_back({a, b, c});
  }
  if (report) {
    report->triangles_read = soup.size();
    report->degenerate_dropped = dropped;
  }
  return mesh;
}

namespace {
float read_f32(const unsigned char* p) {
  float f;
  std::memcpy(&f, p, 4);  // STL is little-endian, as is every platform we build for
  return f;
}
}  // namespace

TriangleMesh read_stl(const std::string& path, double scale, MeshLoadReport* report) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("STL file '" + path + "': cannot open");
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::vector<std::array<Vec3, 3>> soup;
  bool binary = false;
  if (bytes.size() >= 84) {
    std::uint32_t n = 0;
    std::memcpy(&n, bytes.data() + 80, 4);
    binary = bytes.size() == 84 + 50ull * n;
    if (binary) {
      soup.reserve(n);
      for (std::uint32_t t = 0; t < n; ++t) {
        const unsigned char* rec = bytes.data() + 84 + 50ull * t + 12;  // skip the stored normal
        std::array<Vec3, 3> tri;
        for (int v = 0; v < 3; ++v)
          tri[static_cast<std::size_t>(v)] = scale * Vec3(read_f32(rec + 12 * v), read_f32(rec + 12 * v + 4), read_f32(rec + 12 * v + 8));
        soup.push_back(tri);
      }
    }
  }
  if (!binary) {
    std::string text(bytes.begin(), bytes.end());
    std::istringstream is(text);
    std::string word;
    if (!(is >> word) || word != "solid")
      throw std::runtime_error("STL file '" + path + "': neither binary (size != 84 + 50n) nor ASCII ('solid' expected)");
    std::array<Vec3, 3> tri;
    int nv = 0;
    while (is >> word) {
      if (word == "vertex") {
        double x, y, z;
        if (!(is >> x >> y >> z)) throw std::runtime_error("STL file '" + path + "': malformed vertex line");
        if (nv >= 3) throw std::runtime_error("STL file '" + path + "': facet with more than 3 vertices");
        tri[static_cast<std::size_t>(nv++)] = scale * Vec3(x, y, z);
      } else if (word == "endfacet") {
        if (nv != 3) throw std::runtime_error("STL file '" + path + "': facet without 3 vertices");
        soup.push_back(tri);
        nv = 0;
      }
    }
  }
  double extent = 0.0;
  for (const auto& t : soup)
    for (const auto& v : t) extent = std::max(extent, v.cwiseAbs().maxCoeff());
  MeshLoadReport local;
  TriangleMesh mesh = weld_triangle_soup(soup, std::max(extent, 1e-9) * 1e-9, &local);
  std::ostringstream msg;
  msg << "STL file '" << path << "': " << local.triangles_read << " triangles read ("
      << (binary ? "binary" : "ASCII") << "), " << local.degenerate_dropped << " degenerate dropped";
  local.message = msg.str();
  if (report) *report = local;
  if (mesh.triangles.empty()) throw std::runtime_error("STL file '" + path + "': no valid triangle");
  return mesh;
}

void write_stl_binary(const TriangleMesh& mesh, const std::string& path) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw std::runtime_error("cannot write STL file '" + path + "'");
  char header[80] = "libspread binary STL";
  out.write(header, 80);
  const auto n = static_cast<std::uint32_t>(mesh.triangles.size());
  out.write(reinterpret_cast<const char*>(&n), 4);
  for (const auto& t : mesh.triangles) {
    const Vec3& a = mesh.vertices[t[0]];
    const Vec3& b = mesh.vertices[t[1]];
    const Vec3& c = mesh.vertices[t[2]];
    const Vec3 nrm = (b - a).cross(c - a).normalized();
    float rec[12];
    const Vec3* vs[4] = {&nrm, &a, &b, &c};
    for (int k = 0; k < 4; ++k)
      for (int d = 0; d < 3; ++d) rec[3 * k + d] = static_cast<float>((*vs[k])[d]);
    out.write(reinterpret_cast<const char*>(rec), sizeof rec);
    const std::uint16_t attr = 0;
    out.write(reinterpret_cast<const char*>(&attr), 2);
  }
}

void write_stl_ascii(const TriangleMesh& mesh, const std::string& path) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write STL file '" + path + "'");
  out.precision(17);
  out << "solid libspread\n";
  for (const auto& t : mesh.triangles) {
    const Vec3& a = mesh.vertices[t[0]];
    const Vec3& b = mesh.vertices[t[1]];
    const Vec3& c = mesh.vertices[t[2]];
    const Vec3 n = (b - a).cross(c - a).normalized();
    out << " facet normal " << n.x() << ' ' << n.y() << ' ' << n.z() << "\n  outer loop\n";
    for (const Vec3* v : {&a, &b, &c}) out << "   vertex " << v->x() << ' ' << v->y() << ' ' << v->z() << "\n";
    out << "  endloop\n endfacet\n";
  }
  out << "endsolid libspread\n";
}

Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, Feature& feature,
                               int fv[2]) {
  // Voronoi regions of the vertices, edges and face, in Ericson's order.
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) { feature = Feature::kVertex; fv[0] = 0; return a; }
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) { feature = Feature::kVertex; fv[0] = 1; return b; }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    feature = Feature::kEdge; fv[0] = 0; fv[1] = 1;
    return a + (d1 / (d1 - d3)) * ab;
  }
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) { feature = Feature::kVertex; fv[0] = 2; return c; }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    feature = Feature::kEdge; fv[0] = 0; fv[1] = 2;
    return a + (d2 / (d2 - d6)) * ac;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    feature = Feature::kEdge; fv[0] = 1; fv[1] = 2;
    return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  }
  const double denom = 1.0 / (va + vb + vc);
  feature = Feature::kFace;
  return a + ab * (vb * denom) + ac * (vc * denom);
}

MeshCollider::MeshCollider(TriangleMesh mesh, double max_particle_radius_m, double cell_m) : mesh_(std::move(mesh)) {
  if (mesh_.triangles.empty()) return;
  Vec3 lo = mesh_.vertices[0], hi = lo;
  double edge_sum = 0.0;
  for (const auto& v : mesh_.vertices) { lo = lo.cwiseMin(v); hi = hi.cwiseMax(v); }
  for (const auto& t : mesh_.triangles) edge_sum += (mesh_.vertices[t[1]] - mesh_.vertices[t[0]]).norm();
  const double mean_edge = edge_sum / static_cast<double>(mesh_.triangles.size());
  if (cell_m <= 0.0) cell_m = std::max(mean_edge, 4.0 * max_particle_radius_m);
  // Keep the grid to a few million cells.
  const Vec3 ext = hi - lo;
  while ((ext.x() / cell_m + 1) * (ext.y() / cell_m + 1) * (ext.z() / cell_m + 1) > 4e6) cell_m *= 1.5;
  // And the cell lists to a few million entries: a few huge triangles among many small ones (small
  // cells) would each be listed in every cell of their bounding box — a crafted STL could exhaust memory.
  const double max_items = 8e6 + 8.0 * static_cast<double>(mesh_.triangles.size());
  const auto items_at = [&](double cell) {
    double items = 0.0;
    for (const auto& t : mesh_.triangles) {
      const Vec3& a = mesh_.vertices[t[0]];
      const Vec3 box = a.cwiseMax(mesh_.vertices[t[1]]).cwiseMax(mesh_.vertices[t[2]]) -
                       a.cwiseMin(mesh_.vertices[t[1]]).cwiseMin(mesh_.vertices[t[2]]);
      items += (std::floor(box.x() / cell) + 2.0) * (std::floor(box.y() / cell) + 2.0) * (std::floor(box.z() / cell) + 2.0);
    }
    return items;
  };
  while (items_at(cell_m) > max_items) cell_m *= 2.0;
  cell_m_ = cell_m;
  lo_ = lo - Vec3::Constant(1e-9);
  nx_ = static_cast<int>(ext.x() / cell_m) + 1;
  ny_ = static_cast<int>(ext.y() / cell_m) + 1;
  nz_ = static_cast<int>(ext.z() / cell_m) + 1;
  const std::size_t ncell = static_cast<std::size_t>(nx_) * ny_ * nz_;
  std::vector<std::uint32_t> count(ncell + 1, 0);
  auto cell_range = [&](const std::array<std::uint32_t, 3>& t, int lo_i[3], int hi_i[3]) {
    Vec3 a = mesh_.vertices[t[0]], b = a;
    for (int k = 1; k < 3; ++k) { a = a.cwiseMin(mesh_.vertices[t[k]]); b = b.cwiseMax(mesh_.vertices[t[k]]); }
    const int n[3] = {nx_, ny_, nz_};
    for (int d = 0; d < 3; ++d) {
      lo_i[d] = std::clamp(static_cast<int>(std::floor((a[d] - lo_[d]) / cell_m_)), 0, n[d] - 1);
      hi_i[d] = std::clamp(static_cast<int>(std::floor((b[d] - lo_[d]) / cell_m_)), 0, n[d] - 1);
    }
  };
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<std::uint32_t> fill;
    if (pass == 1) {
      for (std::size_t k = 1; k <= ncell; ++k) count[k] += count[k - 1];
      cell_start_ = count;
      cell_items_.assign(count[ncell], 0);
      fill.assign(count.begin(), count.end() - 1);
    }
    for (std::uint32_t ti = 0; ti < mesh_.triangles.size(); ++ti) {
      int l[3], h[3];
      cell_range(mesh_.triangles[ti], l, h);
      for (int iz = l[2]; iz <= h[2]; ++iz)
        for (int iy = l[1]; iy <= h[1]; ++iy)
          for (int ix = l[0]; ix <= h[0]; ++ix) {
            const std::size_t cell = (static_cast<std::size_t>(iz) * ny_ + iy) * nx_ + ix;
            if (pass == 0) ++count[cell + 1];
            else cell_items_[fill[cell]++] = ti;
          }
    }
  }
  bounds_.reserve(mesh_.triangles.size());
  for (const auto& t : mesh_.triangles)
    bounds_.push_back(triangle_bound(mesh_.vertices[t[0]], mesh_.vertices[t[1]], mesh_.vertices[t[2]]));
}

namespace {

// v / |v|, scaled by its largest component first: with tiny coordinates d² or a face's cross product
// underflows and d/|d| is not a unit vector (fuzz_stl_reader regression). False for a zero or non-finite v.
bool unit_vector(const Vec3& v, Vec3& unit_v) {
  const double m = v.cwiseAbs().maxCoeff();
  if (!(m > 0.0) || !std::isfinite(m)) return false;
  unit_v = v / m;
  unit_v /= unit_v.norm();
  return true;
}

// The contact of the sphere (centre, radius_m) with triangle ti, if it touches: closest point, feature,
// distance and normal (the face's when the centre lies on the surface), and the feature's vertices (an edge's
// two, a vertex's one twice). False when it does not touch or has no defined normal (collinear vertices).
bool triangle_contact(const TriangleMesh& mesh, std::uint32_t ti, const Vec3& centre, double radius_m, MeshContact& mc,
                      std::uint32_t (&feature_vertices)[2]) {
  const auto& t = mesh.triangles[ti];
  Feature f;
  int fv[2] = {0, 0};
  const Vec3 q = closest_point_on_triangle(centre, mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]], f, fv);
  const Vec3 d = centre - q;
  const double dist2 = d.squaredNorm();
  if (dist2 >= radius_m * radius_m) return false;
  mc.triangle = ti;
  mc.feature = f;
  mc.point = q;
  mc.distance_m = std::sqrt(dist2);
  const bool centre_off_surface = mc.distance_m > 1e-12 * radius_m && unit_vector(d, mc.normal);
  if (!centre_off_surface) {
    const Vec3 fn = (mesh.vertices[t[1]] - mesh.vertices[t[0]]).cross(mesh.vertices[t[2]] - mesh.vertices[t[0]]);
    if (!unit_vector(fn, mc.normal)) return false;
  }
  feature_vertices[0] = t[static_cast<std::size_t>(fv[0])];
  feature_vertices[1] = f == Feature::kEdge ? t[static_cast<std::size_t>(fv[1])] : feature_vertices[0];
  return true;
}

// The candidates that are local minima of the distance, closest first, into out (at most max_out). Ties are
// broken by feature rank (face before edge before vertex) then triangle id, so the outcome never depends on
// the grid's traversal order.
int local_minima(const TriangleMesh& mesh, const MeshContact* cand, const std::uint32_t (*cand_v)[2], int ncand,
                 MeshContact* out, int max_out) {
  constexpr int kMaxCandidates = 48;
  int order[kMaxCandidates];
  for (int c = 0; c < ncand; ++c) order[c] = c;
  std::sort(order, order + ncand, [&](int x, int y) {
    if (cand[x].distance_m != cand[y].distance_m) return cand[x].distance_m < cand[y].distance_m;
    if (cand[x].feature != cand[y].feature) return cand[x].feature < cand[y].feature;
    return cand[x].triangle < cand[y].triangle;
  });
  int nout = 0;
  constexpr double kSameNormal = 0.99999;    // cos 0.26°: the same patch seen through another triangle
  constexpr double kSharedVertexCos = 0.7;   // cos 45°
  for (int oi = 0; oi < ncand; ++oi) {
    const MeshContact& c = cand[order[oi]];
    bool keep = true;
    for (int a = 0; a < nout && keep; ++a) {
      if (c.normal.dot(out[a].normal) > kSameNormal) keep = false;
      if (keep && c.feature != Feature::kFace) {
        const auto& at = mesh.triangles[out[a].triangle];
        auto contains = [&](std::uint32_t v) { return at[0] == v || at[1] == v || at[2] == v; };
        const bool has0 = contains(cand_v[order[oi]][0]), has1 = contains(cand_v[order[oi]][1]);
        // Contains the whole feature: not a local minimum. Shares one vertex with a nearly parallel
        // normal: the same flat patch seen across a fan of triangles around that vertex.
        if ((has0 && has1) || ((has0 || has1) && c.normal.dot(out[a].normal) > kSharedVertexCos)) keep = false;
      }
    }
    if (keep && nout < max_out) out[nout++] = c;
  }
  return nout;
}

// The cheap test lets a triangle through when its bound is below r² and a hair more: the bound and the
// exact distance round differently, and the hair (10⁻⁶ r²) is far above either's rounding.
double cull_distance2_m2(double radius_m) { return radius_m * radius_m * (1.0 + 1e-6); }

}  // namespace

bool MeshCollider::cell_range(const Vec3& centre, double reach_m, int l[3], int h[3]) const {
  const int n[3] = {nx_, ny_, nz_};
  for (int d = 0; d < 3; ++d) {
    l[d] = static_cast<int>(std::floor((centre[d] - reach_m - lo_[d]) / cell_m_));
    h[d] = static_cast<int>(std::floor((centre[d] + reach_m - lo_[d]) / cell_m_));
    if (h[d] < 0 || l[d] >= n[d]) return false;
    l[d] = std::max(l[d], 0);
    h[d] = std::min(h[d], n[d] - 1);
  }
  return true;
}

int MeshCollider::query(const Vec3& centre, double radius_m, MeshContact* out, int max_out) const {
  if (mesh_.triangles.empty()) return 0;
  constexpr int kMaxCandidates = 48;
  MeshContact cand[kMaxCandidates];
  std::uint32_t cand_v[kMaxCandidates][2];
  int ncand = 0;
  int l[3], h[3];
  if (!cell_range(centre, radius_m, l, h)) return 0;
  const double cull_m2 = cull_distance2_m2(radius_m);
  for (int iz = l[2]; iz <= h[2]; ++iz)
    for (int iy = l[1]; iy <= h[1]; ++iy)
      for (int ix = l[0]; ix <= h[0]; ++ix) {
        const std::size_t cell = (static_cast<std::size_t>(iz) * ny_ + iy) * nx_ + ix;
        for (std::uint32_t k = cell_start_[cell]; k < cell_start_[cell + 1]; ++k) {
          const std::uint32_t ti = cell_items_[k];
          bool seen = false;
          for (int c = 0; c < ncand && !seen; ++c) seen = cand[c].triangle == ti;
          if (seen || ncand == kMaxCandidates || distance2_lower_bound_m2(bounds_[ti], centre) > cull_m2) continue;
          if (triangle_contact(mesh_, ti, centre, radius_m, cand[ncand], cand_v[ncand])) ++ncand;
        }
      }
  return local_minima(mesh_, cand, cand_v, ncand, out, max_out);
}

namespace {

// query_listed with room for kRoom candidates; −1 when more touch.
template <int kRoom>
int listed_contacts(const TriangleMesh& mesh, const std::vector<TriangleBound>& bounds, const Vec3& centre, double radius_m,
                    const std::uint32_t* triangles, int count, MeshContact* out, int max_out) {
  MeshContact cand[kRoom];
  std::uint32_t cand_v[kRoom][2];
  int ncand = 0;
  const double cull_m2 = cull_distance2_m2(radius_m);
  for (int k = 0; k < count; ++k) {
    const std::uint32_t ti = triangles[k];
    if (distance2_lower_bound_m2(bounds[ti], centre) > cull_m2) continue;
    if (ncand == kRoom) return -1;
    if (triangle_contact(mesh, ti, centre, radius_m, cand[ncand], cand_v[ncand])) ++ncand;
  }
  if (ncand == 1 && max_out >= 1) {  // the usual case on a face: local_minima would keep it as it is
    out[0] = cand[0];
    return 1;
  }
  return local_minima(mesh, cand, cand_v, ncand, out, max_out);
}

}  // namespace

int MeshCollider::query_listed(const Vec3& centre, double radius_m, const std::uint32_t* triangles, int count,
                               MeshContact* out, int max_out) const {
  // Room for four candidates covers a granule on a face, an edge or a vane's foot; its scratch is built on
  // every call. More (up to query()'s 48, which a list of MeshNear::kCapacity cannot exceed): again.
  const int n = listed_contacts<4>(mesh_, bounds_, centre, radius_m, triangles, count, out, max_out);
  return n >= 0 ? n : listed_contacts<48>(mesh_, bounds_, centre, radius_m, triangles, count, out, max_out);
}

int MeshCollider::triangles_within(const Vec3& centre, double reach_m, std::uint32_t* triangles, int capacity) const {
  if (mesh_.triangles.empty()) return 0;
  int l[3], h[3];
  if (!cell_range(centre, reach_m, l, h)) return 0;
  const double reach2 = reach_m * reach_m;
  int count = 0;
  for (int iz = l[2]; iz <= h[2]; ++iz)
    for (int iy = l[1]; iy <= h[1]; ++iy)
      for (int ix = l[0]; ix <= h[0]; ++ix) {
        const std::size_t cell = (static_cast<std::size_t>(iz) * ny_ + iy) * nx_ + ix;
        for (std::uint32_t k = cell_start_[cell]; k < cell_start_[cell + 1]; ++k) {
          const std::uint32_t ti = cell_items_[k];
          if (std::find(triangles, triangles + count, ti) != triangles + count) continue;
          const auto& t = mesh_.triangles[ti];
          Feature f;
          int fv[2];
          const Vec3 q = closest_point_on_triangle(centre, mesh_.vertices[t[0]], mesh_.vertices[t[1]], mesh_.vertices[t[2]], f, fv);
          if ((centre - q).squaredNorm() >= reach2) continue;
          if (count == capacity) return capacity + 1;
          triangles[count++] = ti;
        }
      }
  std::sort(triangles, triangles + count);
  return count;
}

}  // namespace spread::dem
