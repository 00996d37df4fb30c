#include "libspread/physics/drum/measurements.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <unordered_map>

namespace spread::drum {

namespace {

constexpr double kRadToDeg = 180.0 / kPi;
constexpr double kFreeFlightGap = 0.25;  // airborne: no particle or wall within this many diameters

// Particles within `gap_m` of another particle (surface to surface; 0: touching), found through a
// uniform grid of cells one largest diameter plus the gap wide.
std::vector<std::uint8_t> particles_near_another(const dem::ParticleArrays& p, double gap_m) {
  const std::size_t n = p.size();
  std::vector<std::uint8_t> near(n, 0);
  double rmax = 0.0;
  for (std::size_t i = 0; i < n; ++i) rmax = std::max(rmax, p.radius_m[i]);
  if (n == 0 || rmax <= 0.0) return near;
  const double cell = 2.0 * rmax + gap_m;
  auto key = [&](long long a, long long b, long long c) {
    return (static_cast<std::uint64_t>(a & 0x1FFFFF) << 42) | (static_cast<std::uint64_t>(b & 0x1FFFFF) << 21) |
           static_cast<std::uint64_t>(c & 0x1FFFFF);
  };
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> grid;
  auto idx = [&](double v) { return static_cast<long long>(std::floor(v / cell)); };
  for (std::size_t i = 0; i < n; ++i)
    if (p.active[i]) grid[key(idx(p.x[i]), idx(p.y[i]), idx(p.z[i]))].push_back(static_cast<std::uint32_t>(i));
  for (std::size_t i = 0; i < n; ++i) {
    if (!p.active[i] || near[i]) continue;
    const long long a = idx(p.x[i]), b = idx(p.y[i]), c = idx(p.z[i]);
    for (long long da = -1; da <= 1 && !near[i]; ++da)
      for (long long db = -1; db <= 1 && !near[i]; ++db)
        for (long long dc = -1; dc <= 1 && !near[i]; ++dc) {
          const auto it = grid.find(key(a + da, b + db, c + dc));
          if (it == grid.end()) continue;
          for (std::uint32_t j : it->second) {
            if (j == i) continue;
            const double dx = p.x[i] - p.x[j], dy = p.y[i] - p.y[j], dz = p.z[i] - p.z[j];
            const double cut = p.radius_m[i] + p.radius_m[j] + gap_m;
            if (dx * dx + dy * dy + dz * dz < cut * cut) {
              near[i] = near[j] = 1;
              break;
            }
          }
        }
  }
  return near;
}

}  // namespace

double lacey_index(const dem::ParticleArrays& p, double cell_m) {
  std::unordered_map<long long, std::pair<int, int>> cells;  // (count, species-1 count)
  int total = 0, ones = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!p.active[i]) continue;
    const long long cx = static_cast<long long>(std::floor(p.x[i] / cell_m));
    const long long cy = static_cast<long long>(std::floor(p.y[i] / cell_m));
    auto& c = cells[cx * 1000003LL + cy];
    ++c.first;
    ++total;
    if (p.material[i] == 1) {
      ++c.second;
      ++ones;
    }
  }
  if (total == 0 || ones == 0 || ones == total) return 0.0;
  const double frac = static_cast<double>(ones) / total;
  const double s0 = frac * (1.0 - frac);
  double var = 0.0;
  int counted = 0, used_cells = 0;
  for (const auto& [k, c] : cells) {
    if (c.first < 3) continue;
    const double f = static_cast<double>(c.second) / c.first;
    var += c.first * (f - frac) * (f - frac);
    counted += c.first;
    ++used_cells;
  }
  if (counted == 0) return 0.0;
  var /= counted;
  const double sr = s0 / (static_cast<double>(counted) / used_cells);
  return (s0 - var) / (s0 - sr);
}

Snapshot measure(const dem::ParticleArrays& p, const DrumGeometry& g, double time_s) {
  Snapshot s;
  s.time_s = time_s;
  const std::size_t n = p.size();
  const double w = g.angular_velocity_rad_s, R = g.radius_m;
  double dmax = 0.0;
  for (std::size_t i = 0; i < n; ++i) dmax = std::max(dmax, 2.0 * p.radius_m[i]);
  const auto touch = particles_near_another(p, 0.0);
  // Free flight: farther than a quarter diameter from any particle and wall. Touching alone is not enough:
  // in a soft, collisional surface layer many particles are momentarily apart by a small fraction of a
  // diameter, which counted 5–15 % of a rolling or cascading bed as "airborne".
  const double flight_gap = kFreeFlightGap * dmax;
  const auto near = particles_near_another(p, flight_gap);
  int active = 0, airborne = 0, co_rot = 0, outer = 0;
  double outer_speed = 0.0, cx = 0.0, cy = 0.0;
  constexpr int kSectors = 36;
  bool covered[kSectors] = {};
  for (std::size_t i = 0; i < n; ++i) {
    if (!p.active[i]) continue;
    ++active;
    const double x = p.x[i], y = p.y[i], r = p.radius_m[i];
    const double rho = std::hypot(x, y);
    // The end walls do not count: they are planes parallel to the cross-section (frictionless stand-ins
    // for a periodic axis), so a particle gliding along one still flies freely in the x–y plane. In a
    // drum 2.25 d long, a quarter-diameter clearance from both ends left a window of 0.75 d of the 1.25 d
    // the centres can occupy, and dropped ~80 % of the particles in flight (rough wall, Fr 0.6: 0.003
    // counted against 0.017). An end wall with friction that drags a particle shows as an in-plane force.
    const bool near_mantle = rho > R - r - flight_gap;
    const bool in_plane_force = i < p.fx.size() && i < p.fy.size() && (p.fx[i] != 0.0 || p.fy[i] != 0.0);
    if (!near[i] && !near_mantle && !in_plane_force) ++airborne;
    // Rigid rotation with the wall: v = ω ẑ × r = (−ω y, ω x).
    const double ux = p.vx[i] + w * y, uy = p.vy[i] - w * x;
    if (w > 0.0 && std::hypot(ux, uy) < 0.2 * w * rho) ++co_rot;
    if (rho > R - 1.5 * dmax) {
      double a = std::atan2(y, x);
      if (a < 0.0) a += 2.0 * kPi;
      covered[std::min(kSectors - 1, static_cast<int>(a / (2.0 * kPi) * kSectors))] = true;
    }
    // Slip at the wall: the layer in contact with the mantle (10 % of a radius of tolerance: on a bead
    // lining a particle resting on a bead tip sits at R − r), within 45° of straight down — under the
    // bed, away from its two ends where the surface flow meets the wall and runs against its motion (in
    // a thin bed those ends held a third of the wall layer and pulled a rolling bed's ratio to ~0.6).
    if (rho > R - 1.1 * r && -y > std::abs(x)) {
      ++outer;
      outer_speed += (-p.vx[i] * y + p.vy[i] * x) / rho;  // counter-clockwise tangential speed
    }
    cx += x;
    cy += y;
  }
  if (active == 0) return s;
  s.airborne_fraction = static_cast<double>(airborne) / active;
  s.co_rotating_fraction = static_cast<double>(co_rot) / active;
  s.wall_coverage = static_cast<double>(std::count(covered, covered + kSectors, true)) / kSectors;
  s.wall_speed_ratio = outer > 0 && w > 0.0 ? outer_speed / outer / (w * R) : 0.0;
  s.centroid_angle_deg = std::atan2(cx / active, -cy / active) * kRadToDeg;

  // Free surface: in columns one diameter wide along x, the highest touching particle; the central
  // 70 % of the surface chord is fitted by a line y = a + b x (the seed's plane free surface, Sect. 4).
  std::unordered_map<long long, std::pair<double, double>> top;  // column → (x, y) of the highest
  for (std::size_t i = 0; i < n; ++i) {
    if (!p.active[i] || !touch[i]) continue;
    const long long c = static_cast<long long>(std::floor(p.x[i] / dmax));
    auto it = top.find(c);
    if (it == top.end() || p.y[i] > it->second.second) top[c] = {p.x[i], p.y[i]};
  }
  std::vector<std::pair<double, double>> pts;
  for (const auto& [c, xy] : top) pts.push_back(xy);
  std::sort(pts.begin(), pts.end());
  if (pts.size() >= 5) {
    const double x0 = pts.front().first, x1 = pts.back().first, span = x1 - x0;
    std::vector<std::pair<double, double>> mid;
    for (const auto& q : pts)
      if (q.first >= x0 + 0.15 * span && q.first <= x1 - 0.15 * span) mid.push_back(q);
    if (mid.size() >= 3) {
      double sx = 0, sy = 0, sxx = 0, sxy = 0;
      for (const auto& q : mid) { sx += q.first; sy += q.second; sxx += q.first * q.first; sxy += q.first * q.second; }
      const double m = static_cast<double>(mid.size());
      const double den = m * sxx - sx * sx;
      if (den > 0.0) {
        const double b = (m * sxy - sx * sy) / den, a = (sy - b * sx) / m;
        s.angle_of_repose_deg = std::atan(b) * kRadToDeg;
        double dev = 0.0;
        for (const auto& q : mid) dev = std::max(dev, std::abs(q.second - (a + b * q.first)) / std::sqrt(1.0 + b * b));
        const double chord = (mid.back().first - mid.front().first) * std::sqrt(1.0 + b * b);
        s.surface_sagitta = chord > 0.0 ? dev / chord : 0.0;
        s.surface_points = static_cast<int>(mid.size());
      }
    }
  }
  bool two = false;
  for (std::size_t i = 0; i < n && !two; ++i) two = p.material[i] == 1;
  if (two) s.lacey_index = lacey_index(p, 3.0 * dmax);
  return s;
}

std::string regime_name(Regime r) {
  switch (r) {
    case Regime::kSlipping: return "slipping";
    case Regime::kSlumping: return "slumping";
    case Regime::kRolling: return "rolling";
    case Regime::kCascading: return "cascading";
    case Regime::kCataracting: return "cataracting";
    case Regime::kCentrifuging: return "centrifuging";
  }
  return "unknown";
}

RegimeEvidence classify(const std::vector<Snapshot>& window, double froude) {
  RegimeEvidence e;
  e.froude = froude;
  e.samples = static_cast<int>(window.size());
  if (window.empty()) {
    e.reason = "no samples in the measurement window";
    return e;
  }
  double a2 = 0.0;
  for (const auto& s : window) {
    e.angle_of_repose_deg += s.angle_of_repose_deg;
    a2 += s.angle_of_repose_deg * s.angle_of_repose_deg;
    e.surface_sagitta += s.surface_sagitta;
    e.airborne_fraction += s.airborne_fraction;
    e.co_rotating_fraction += s.co_rotating_fraction;
    e.wall_coverage += s.wall_coverage;
    e.wall_speed_ratio += s.wall_speed_ratio;
    e.centroid_angle_deg += s.centroid_angle_deg;
    e.lacey_index += s.lacey_index;
  }
  const double m = static_cast<double>(window.size());
  e.angle_of_repose_deg /= m;
  e.angle_of_repose_sd_deg = std::sqrt(std::max(0.0, a2 / m - e.angle_of_repose_deg * e.angle_of_repose_deg));
  e.surface_sagitta /= m;
  e.airborne_fraction /= m;
  e.co_rotating_fraction /= m;
  e.wall_coverage /= m;
  e.wall_speed_ratio /= m;
  e.centroid_angle_deg /= m;
  e.lacey_index /= m;
  std::ostringstream os;
  os.precision(3);
  // Rules in order (docs/drum.md): a ring held all round the wall; particles in free flight; a bed that
  // does not follow the wall; intermittent avalanches; a curved surface; otherwise a flat rolling layer.
  if (e.wall_coverage >= 0.9 && e.co_rotating_fraction >= 0.8) {
    e.regime = Regime::kCentrifuging;
    os << "wall coverage " << e.wall_coverage << " >= 0.9 and co-rotating fraction " << e.co_rotating_fraction << " >= 0.8";
  } else if (e.airborne_fraction >= 0.01) {
    // Free flight (a quarter diameter clear of everything) stays below 0.002 in rolling and cascading
    // beds; particles thrown off a lifted shoulder give 0.014 and more (docs/drum.md).
    e.regime = Regime::kCataracting;
    os << "airborne fraction " << e.airborne_fraction << " >= 0.01 (particles in free flight)";
  } else if (e.wall_speed_ratio < 0.5 && e.co_rotating_fraction < 0.25) {
    e.regime = Regime::kSlipping;
    os << "outer layer moves at " << e.wall_speed_ratio << " of the wall speed (< 0.5), co-rotating " << e.co_rotating_fraction;
  } else if (e.angle_of_repose_sd_deg >= 4.0 && e.co_rotating_fraction >= 0.5 && e.wall_coverage < 0.6) {
    // Slumping: a compact heap (less than 60 % of the wall covered) turns with the wall between
    // avalanches (mostly co-rotating) and the angle jumps. Without the heap condition a bed forming a
    // ring near Fr 1 (coverage 0.88, a surface fit that jumps by 25°) was labelled slumping.
    e.regime = Regime::kSlumping;
    os << "angle of repose varies by sd " << e.angle_of_repose_sd_deg << " deg >= 4 (avalanches) while co-rotating "
       << e.co_rotating_fraction << " >= 0.5";
  } else if (e.surface_sagitta >= 0.12) {
    e.regime = Regime::kCascading;
    os << "surface sagitta/chord " << e.surface_sagitta << " >= 0.12 (curved surface)";
  } else {
    e.regime = Regime::kRolling;
    os << "flat surface (sagitta/chord " << e.surface_sagitta << "), steady angle " << e.angle_of_repose_deg << " ± "
       << e.angle_of_repose_sd_deg << " deg, airborne " << e.airborne_fraction;
  }
  e.reason = os.str();
  return e;
}

}  // namespace spread::drum
