// Recorded tracks (track_csv.hpp): columns by name, checks that name the line.
#include "libspread/analysis/field/track_csv.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>

#include "libspread/analysis/field/projection.hpp"
#include "libspread/core/error.hpp"

namespace spread::field {
namespace {

[[noreturn]] void refuse_track(const std::string& where, int line, const std::string& what) {
  const std::string at = where + ":" + std::to_string(line);
  throw Error(ErrorKind::kArgument, at, at + ": " + what);
}

struct Fix {
  int line = 0;
  double time_s = 0.0, x = 0.0, y = 0.0, speed_m_s = 0.0, heading_deg = 0.0;
  bool spreading = true;
};

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream in(line);
  std::string cell;
  while (std::getline(in, cell, ',')) {
    cell.erase(0, cell.find_first_not_of(" \t\r"));
    cell.erase(cell.find_last_not_of(" \t\r") + 1);
    cells.push_back(cell);
  }
  return cells;
}

double number(const std::string& text, const std::string& column, const std::string& where, int line) {
  try {
    std::size_t used = 0;
    const double v = std::stod(text, &used);
    if (used == text.size() && std::isfinite(v)) return v;
  } catch (const std::exception&) {
  }
  refuse_track(where, line, column + " is '" + text + "', not a number");
}

struct Columns {
  std::map<std::string, std::size_t> index;
  bool lon_lat = false;
};
Columns header(const std::string& line, const std::string& where, int line_number) {
  Columns c;
  const auto cells = split(line);
  for (std::size_t i = 0; i < cells.size(); ++i) c.index[cells[i]] = i;
  c.lon_lat = c.index.count("lon_deg") && c.index.count("lat_deg");
  const bool metres = c.index.count("x_m") && c.index.count("y_m");
  for (const char* need : {"time_s", "speed_m_s", "heading_deg"}) {
    if (!c.index.count(need)) refuse_track(where, line_number, std::string("the header has no column ") + need);
  }
  if (!c.lon_lat && !metres) refuse_track(where, line_number, "the header has neither x_m, y_m nor lon_deg, lat_deg");
  return c;
}

std::vector<Fix> read_fixes(const std::string& text, const std::string& where, Columns& columns) {
  std::vector<Fix> fixes;
  std::stringstream in(text);
  std::string line;
  int line_number = 0;
  bool have_header = false;
  while (std::getline(in, line)) {
    ++line_number;
    if (line.find_first_not_of(" \t\r") == std::string::npos || line[0] == '#') continue;
    if (!have_header) {
      columns = header(line, where, line_number);
      have_header = true;
      continue;
    }
    const auto cells = split(line);
    const auto cell = [&](const std::string& name) {
      const std::size_t i = columns.index.at(name);
      if (i >= cells.size()) refuse_track(where, line_number, "no value for " + name);
      return number(cells[i], name, where, line_number);
    };
    Fix f;
    f.line = line_number;
    f.time_s = cell("time_s");
    f.x = cell(columns.lon_lat ? "lon_deg" : "x_m");
    f.y = cell(columns.lon_lat ? "lat_deg" : "y_m");
    f.speed_m_s = cell("speed_m_s");
    f.heading_deg = cell("heading_deg");
    if (columns.index.count("spreading")) f.spreading = cell("spreading") != 0.0;
    if (f.speed_m_s < 0.0) refuse_track(where, line_number, "speed_m_s is negative");
    fixes.push_back(f);
  }
  if (fixes.size() < 2) refuse_track(where, line_number, "the track has fewer than 2 fixes");
  return fixes;
}

void check_motion(const std::vector<Fix>& fixes, const std::string& where) {
  for (std::size_t i = 1; i < fixes.size(); ++i) {
    const Fix &a = fixes[i - 1], &b = fixes[i];
    const double dt = b.time_s - a.time_s;
    if (!(dt > 0.0)) refuse_track(where, b.line, "time_s does not increase (" + std::to_string(a.time_s) + " s, then " +
                                               std::to_string(b.time_s) + " s)");
    const double moved_m = std::hypot(b.x - a.x, b.y - a.y);
    const double allowed_m = 1.5 * std::max(a.speed_m_s, b.speed_m_s) * dt + kJumpSlack_m;
    if (moved_m > allowed_m) {
      std::ostringstream out;
      out.precision(4);
      out << "the track jumps " << moved_m << " m in " << dt << " s at a recorded " << std::max(a.speed_m_s, b.speed_m_s)
          << " m/s (at most " << allowed_m << " m): a lost fix or two logs joined";
      refuse_track(where, b.line, out.str());
    }
    if (moved_m > kJumpSlack_m && b.speed_m_s > 0.5) {
      // Heading clockwise from north: the forward vector is (sin h, cos h).
      const double h = b.heading_deg * std::numbers::pi / 180.0;
      const double along = ((b.x - a.x) * std::sin(h) + (b.y - a.y) * std::cos(h)) / moved_m;
      if (along < 0.0) {
        refuse_track(where, b.line, "heading_deg " + std::to_string(b.heading_deg) +
                                  " points away from the direction the track moves (reversing, or another heading convention: "
                                  "clockwise from north is expected)");
      }
    }
  }
}

std::vector<Pass> passes_of(const std::vector<Fix>& fixes) {
  std::vector<Pass> passes;
  Pass current;
  current.kind = PassKind::kTrack;
  for (const Fix& f : fixes) {
    if (f.spreading) {
      current.path.push_back({f.x, f.y});
      continue;
    }
    if (current.path.size() >= 2) passes.push_back(current);
    current.path.clear();
  }
  if (current.path.size() >= 2) passes.push_back(current);
  return passes;
}

}  // namespace

std::vector<Pass> parse_track_csv(const std::string& text, const std::string& where, const Boundary& boundary) {
  Columns columns;
  std::vector<Fix> fixes = read_fixes(text, where, columns);
  if (columns.lon_lat) {
    Ring points;
    for (const Fix& f : fixes) points.push_back({f.x, f.y});
    const Ring projected = lon_lat_to(points, boundary.crs, where);
    for (std::size_t i = 0; i < fixes.size(); ++i) {
      fixes[i].x = projected[i].x_m;
      fixes[i].y = projected[i].y_m;
    }
  }
  check_motion(fixes, where);
  return passes_of(fixes);
}

std::vector<Pass> read_track_csv(const std::string& path, const Boundary& boundary) {
  std::ifstream in(path);
  if (!in) throw Error(ErrorKind::kMissing, path, path + ": no such file (the recorded track, CSV)");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_track_csv(text.str(), path, boundary);
}

}  // namespace spread::field
