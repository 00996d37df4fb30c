#include "libspread/analysis/calibration/scene_of_run.hpp"

#include <sstream>
#include <string>
#include <vector>

namespace spread::calibration {

scene::Scene scene_of_run(const tables::Run& run) {
  // Split off the override block that provenance_text() appends, and apply it again: as comments the
  // overrides would otherwise be lost.
  static const std::string kMarker = "# overrides applied after the text above:\n";
  std::string text = run.scene_text;
  std::vector<std::string> overrides;
  const auto marker = text.rfind(kMarker);
  if (marker != std::string::npos) {
    std::istringstream tail(text.substr(marker + kMarker.size()));
    std::string line;
    bool all_overrides = true;
    std::vector<std::string> found;
    while (std::getline(tail, line)) {
      if (line.rfind("# --set ", 0) == 0) found.push_back(line.substr(8));
      else if (!line.empty()) all_overrides = false;
    }
    if (all_overrides) {
      overrides = std::move(found);
      text.erase(marker);
    }
  }
  std::ostringstream label;
  label << "table run '" << run.material << "' @ " << run.rpm << " rpm (stored scene)";
  return scene::parse_scene(text, label.str(), overrides);
}

}  // namespace spread::calibration
