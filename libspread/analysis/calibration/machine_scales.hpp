#pragma once
// The spreader's own scales. The tools compute a drop point as a turn from the table's, in degrees; the
// technician sets it on the machine's drop-point scale — letters or numbers on the disc's feed system.
// A scales file (docs/field-calibration.md, "The machine's scales") gives each mark the turn it sets, so
// every drop point printed reads on that scale as well: "+9.5 deg" is "D+0.6 towards E" beside it.
//
//   [drop_point_scale]
//   marks = ["A", "B", "C", "D", "E"]
//   turn_deg = [-30, -15, 0, 15, 30]   # each mark's drop point, turned from the table's (ascending)
#include <string>
#include <vector>

namespace spread::calibration {

struct DropPointScale {
  std::vector<std::string> marks;  // as printed on the machine
  std::vector<double> turn_deg;    // strictly ascending, one per mark
};

struct MachineScales {
  std::string source;  // the file, for messages
  DropPointScale drop_point;
};

// Reads a scales file; a scene::SceneError names the file and key of a problem (or "cannot open the scales
// file") (a missing or unknown key,
// marks and turns of different lengths, fewer than two marks, turns not ascending, a turn beyond ±180°).
MachineScales read_machine_scales(const std::string& path);
MachineScales parse_machine_scales(const std::string& text, const std::string& source);

// The drop point `turn_deg` on the scale: "D" on a mark (within a twentieth of the step), "D+0.6 towards E"
// between two (six tenths of the way), and beyond the scale's ends "beyond H, which is +60.0 deg" (the
// caller prints the turn itself beside it).
std::string drop_point_mark(const DropPointScale& scale, double turn_deg);

}  // namespace spread::calibration
