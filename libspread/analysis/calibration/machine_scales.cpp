#include "libspread/analysis/calibration/machine_scales.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>

#include "libspread/io/scene/scene.hpp"
#include "libspread/io/scene/toml_document.hpp"

namespace spread::calibration {
namespace {

std::string degrees(double turn_deg) {
  char text[32];
  std::snprintf(text, sizeof text, "%+.1f deg", turn_deg);
  return text;
}

}  // namespace

MachineScales parse_machine_scales(const std::string& text, const std::string& source) {
  scene::TomlDocument document(text, source, {});
  document.check_top_level_keys({"drop_point_scale"});
  scene::TomlSection section = document.section("drop_point_scale");
  MachineScales scales;
  scales.source = source;
  const auto marks = section.strings("marks");
  const auto turns = section.numbers("turn_deg");
  if (!marks) section.fail("marks", "missing: the marks of the drop-point scale as printed on the machine");
  if (!turns) section.fail("turn_deg", "missing: the drop point each mark sets, turned from the table's (degrees)");
  if (marks->size() != turns->size()) {
    section.fail("turn_deg", std::to_string(turns->size()) + " turns for " + std::to_string(marks->size()) + " marks");
  }
  if (marks->size() < 2) section.fail("marks", "a scale needs at least two marks");
  std::set<std::string> seen;
  for (std::size_t i = 0; i < marks->size(); ++i) {
    if ((*marks)[i].empty() || !seen.insert((*marks)[i]).second) {
      section.fail("marks", "mark " + std::to_string(i + 1) + " is empty or repeated");
    }
    if (!(std::abs((*turns)[i]) <= 180.0)) section.fail("turn_deg", "a turn beyond ±180 degrees");
    if (i > 0 && !((*turns)[i] > (*turns)[i - 1])) {
      section.fail("turn_deg", "the turns must rise from mark to mark (" + (*marks)[i - 1] + " then " + (*marks)[i] + ")");
    }
  }
  section.finish();
  scales.drop_point = {*marks, *turns};
  return scales;
}

MachineScales read_machine_scales(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw scene::SceneError(path + ": cannot open the scales file");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_machine_scales(text.str(), path);
}

std::string drop_point_mark(const DropPointScale& scale, double turn_deg) {
  const auto& m = scale.marks;
  const auto& t = scale.turn_deg;
  if (m.size() < 2 || m.size() != t.size() || !std::isfinite(turn_deg)) return "?";
  const double first_step = t[1] - t[0], last_step = t.back() - t[t.size() - 2];
  if (turn_deg < t.front() - 0.05 * first_step) {
    return "beyond " + m.front() + ", which is " + degrees(t.front());
  }
  if (turn_deg > t.back() + 0.05 * last_step) {
    return "beyond " + m.back() + ", which is " + degrees(t.back());
  }
  std::size_t i = 0;
  while (i + 2 < t.size() && turn_deg > t[i + 1]) ++i;
  const double fraction = (turn_deg - t[i]) / (t[i + 1] - t[i]);
  if (fraction < 0.05) return m[i];
  if (fraction > 0.95) return m[i + 1];
  char text[96];
  std::snprintf(text, sizeof text, "%s+%.1f towards %s", m[i].c_str(), fraction, m[i + 1].c_str());
  return text;
}

}  // namespace spread::calibration
