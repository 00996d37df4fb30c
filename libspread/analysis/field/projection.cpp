// PROJ's C API (proj.h): a context, the source and target CRS, one transformation for the ring.
#include "libspread/analysis/field/projection.hpp"

#include <proj.h>

#include <cmath>
#include <memory>
#include <sstream>

#include "libspread/core/error.hpp"

namespace spread::field {
namespace {

[[noreturn]] void refuse_projection(const std::string& where, const std::string& what) {
  throw Error(ErrorKind::kArgument, where, where + ": " + what);
}

struct ContextDeleter {
  void operator()(PJ_CONTEXT* c) const { proj_context_destroy(c); }
};
struct PjDeleter {
  void operator()(PJ* p) const { proj_destroy(p); }
};
using Context = std::unique_ptr<PJ_CONTEXT, ContextDeleter>;
using Pj = std::unique_ptr<PJ, PjDeleter>;

// A transformation whose axes are in the order x = easting or longitude, y = northing or latitude,
// whatever the CRS definitions' own axis order (EPSG:4326 is latitude first).
Pj transformation(PJ_CONTEXT* ctx, const std::string& from, const std::string& to, const std::string& where) {
  Pj raw(proj_create_crs_to_crs(ctx, from.c_str(), to.c_str(), nullptr));
  if (!raw) refuse_projection(where, "PROJ cannot transform from " + from + " to " + to + " (unknown CRS?)");
  Pj normalised(proj_normalize_for_visualization(ctx, raw.get()));
  if (!normalised) refuse_projection(where, "PROJ cannot order the axes of " + from + " → " + to);
  return normalised;
}

Point transform(PJ* pj, Point p) {
  const PJ_COORD out = proj_trans(pj, PJ_FWD, proj_coord(p.x_m, p.y_m, 0.0, 0.0));
  return {out.xy.x, out.xy.y};
}

void require_lon_lat(const Ring& ring, const std::string& where) {
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Point p = ring[i];
    if (std::abs(p.x_m) > 180.0 || std::abs(p.y_m) > 90.0) {
      std::ostringstream out;
      out.precision(10);
      out << "position " << i << " (" << p.x_m << ", " << p.y_m
          << ") is not longitude/latitude (beyond ±180°/±90°): wrong units — a file in metres needs its CRS "
             "(a crs member, or the field's crs, e.g. \"EPSG:25832\", or \"local\")";
      refuse_projection(where, out.str());
    }
    if (std::abs(p.y_m) > 84.0) {
      refuse_projection(where, "position " + std::to_string(i) + " lies at latitude " + std::to_string(p.y_m) +
                        "°, beyond UTM's ±84° (longitude and latitude swapped?)");
    }
  }
}

ProjectedRing from_lon_lat(const SourceRing& source) {
  require_lon_lat(source.ring, source.where);
  double lon = 0.0, lat = 0.0;
  for (const Point& p : source.ring) {
    lon += p.x_m;
    lat += p.y_m;
  }
  lon /= static_cast<double>(source.ring.size());
  lat /= static_cast<double>(source.ring.size());
  ProjectedRing out;
  out.crs = utm_crs_for(lon, lat);
  Context ctx(proj_context_create());
  const Pj pj = transformation(ctx.get(), "OGC:CRS84", out.crs, source.where);
  for (const Point& p : source.ring) out.ring.push_back(transform(pj.get(), p));
  return out;
}

void require_metres(PJ_CONTEXT* ctx, PJ* crs, const std::string& name, const std::string& where) {
  const PJ_TYPE type = proj_get_type(crs);
  if (type != PJ_TYPE_PROJECTED_CRS) {
    refuse_projection(where, name + " is not a projected CRS (a field in metres needs one, e.g. a UTM zone; "
                         "longitude/latitude files need no crs)");
  }
  Pj cs(proj_crs_get_coordinate_system(ctx, crs));
  const char* unit = nullptr;
  double to_metre = 0.0;
  if (!cs || !proj_cs_get_axis_info(ctx, cs.get(), 0, nullptr, nullptr, nullptr, &to_metre, &unit, nullptr, nullptr) ||
      std::abs(to_metre - 1.0) > 1e-12) {
    refuse_projection(where, name + " is not in metres (unit " + std::string(unit ? unit : "?") + ")");
  }
}

void require_area_of_use(PJ_CONTEXT* ctx, PJ* crs, const SourceRing& source) {
  double west = 0.0, south = 0.0, east = 0.0, north = 0.0;
  const char* area = nullptr;
  if (!proj_get_area_of_use(ctx, crs, &west, &south, &east, &north, &area) || west == -1000.0) return;
  const Pj to_lon_lat = transformation(ctx, source.crs, "OGC:CRS84", source.where);
  for (std::size_t i = 0; i < source.ring.size(); ++i) {
    const Point ll = transform(to_lon_lat.get(), source.ring[i]);
    const bool inside_lon = west <= east ? (ll.x_m >= west - 0.5 && ll.x_m <= east + 0.5)
                                         : (ll.x_m >= west - 0.5 || ll.x_m <= east + 0.5);  // across 180°
    if (std::isfinite(ll.x_m) && std::isfinite(ll.y_m) && inside_lon && ll.y_m >= south - 0.5 && ll.y_m <= north + 0.5) {
      continue;
    }
    std::ostringstream out;
    out.precision(6);
    out << "position " << i << " lies at " << ll.y_m << "° latitude, " << ll.x_m << "° longitude in " << source.crs
        << ", outside its area of use (" << (area ? area : "") << ": " << south << "° to " << north << "° latitude, "
        << west << "° to " << east << "° longitude)"
        << ((ll.y_m < 0.0) != (south + north < 0.0) ? ": wrong hemisphere (a UTM zone north is EPSG:326NN, south 327NN)"
                                                     : ": wrong zone or CRS");
    refuse_projection(source.where, out.str());
  }
}

ProjectedRing from_projected(const SourceRing& source) {
  Context ctx(proj_context_create());
  Pj crs(proj_create(ctx.get(), source.crs.c_str()));
  if (!crs) refuse_projection(source.where, "unknown CRS '" + source.crs + "' (PROJ does not know it)");
  require_metres(ctx.get(), crs.get(), source.crs, source.where);
  require_area_of_use(ctx.get(), crs.get(), source);
  return {source.ring, source.crs};
}

}  // namespace

std::string utm_crs_for(double longitude_deg, double latitude_deg) {
  // Zones are 6° wide from 180° W (zone 1); longitude 180° itself belongs to zone 60.
  int zone = static_cast<int>(std::floor((longitude_deg + 180.0) / 6.0)) + 1;
  if (zone > 60) zone = 60;
  return "EPSG:" + std::to_string((latitude_deg >= 0.0 ? 32600 : 32700) + zone);
}

Ring lon_lat_to(const Ring& lon_lat, const std::string& crs, const std::string& where) {
  if (crs == "local") refuse_projection(where, "longitude/latitude points for a field in local metres: give x_m, y_m");
  require_lon_lat(lon_lat, where);
  Context ctx(proj_context_create());
  const Pj pj = transformation(ctx.get(), "OGC:CRS84", crs, where);
  Ring out;
  out.reserve(lon_lat.size());
  for (const Point& p : lon_lat) out.push_back(transform(pj.get(), p));
  return out;
}

ProjectedRing project_to_metres(const SourceRing& source) {
  if (source.crs.empty()) return from_lon_lat(source);
  if (source.crs == "local") return {source.ring, "local"};
  return from_projected(source);
}

}  // namespace spread::field
