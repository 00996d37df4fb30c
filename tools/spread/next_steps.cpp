#include "tools/spread/next_steps.hpp"

#include <cmath>
#include <cstdio>

#include "tools/spread/number_format.hpp"

namespace spread::cli {
namespace {

std::string quoted(const std::string& text) {
  return text.find_first_of(" '\"()") == std::string::npos ? text : "'" + text + "'";
}

}  // namespace

void print_next_steps(const std::vector<NextStep>& steps) {
  for (const NextStep& s : steps) {
    std::printf("next: %s\n", s.what.c_str());
    if (!s.command.empty()) std::printf("      %s\n", s.command.c_str());
  }
}

nlohmann::json next_steps_json(const std::vector<NextStep>& steps) {
  nlohmann::json list = nlohmann::json::array();
  for (const NextStep& s : steps) {
    list.push_back({{"what", s.what}, {"command", s.command.empty() ? nlohmann::json(nullptr) : nlohmann::json(s.command)}});
  }
  return list;
}

std::vector<std::string> next_steps_notes(const std::vector<NextStep>& steps) {
  std::vector<std::string> notes;
  for (const NextStep& s : steps) notes.push_back("Next: " + s.what);
  return notes;
}

NextStep make_a_table_step() {
  return {"a setting for this spreader needs a launch table of the machine, made once from its scene (a "
          "simulation of the discs, some minutes)",
          "lookup_builder scenes/default.toml --output table.sqlite"};
}

std::vector<NextStep> rate_next_steps(double required_gate, double current_gate, double width_m) {
  std::vector<NextStep> steps;
  if (std::abs(required_gate - current_gate) > 1e-9) {
    steps.push_back({"set the gate to " + format("%.2f", required_gate) + " (it is at " + format("%.2f", current_gate) +
                         ")",
                     ""});
  }
  steps.push_back({"lay a row of trays across the whole throw, drive " + format("%.0f m", width_m) +
                       " bouts over it at this gate (three passes), weigh each tray and check the spread",
                   "spread calibrate tray TRAYS.csv --width " + format("%g", width_m)});
  return steps;
}

std::vector<NextStep> tray_next_steps(const std::vector<Verdict>& verdicts, double bout_width_m, double working_width_m,
                                      bool width_given, int passes, bool quick_check, const std::string& tray_file) {
  std::vector<NextStep> steps;
  const std::string bout = format("%.2f m", bout_width_m);
  const std::string file = quoted(tray_file);
  for (const Verdict& v : verdicts) {
    if (v.kind == "rate" && v.shown.level == plot::ReportVerdict::Level::kFail) {
      steps.push_back({"the trays did not catch the rate set: weigh a catch at the gate again and set it anew",
                       "spread calibrate rate --mass KG --time S --gate G --target-rate KG_HA --width " +
                           format("%g", bout_width_m) + " --speed KM_H"});
    }
    if (v.kind != "cv") continue;
    switch (v.shown.level) {
      case plot::ReportVerdict::Level::kPass:
        steps.push_back({"the spread is even at " + bout + ": keep this setting" +
                             (width_given ? std::string() : " and drive bouts of " + bout) +
                             "; check the rate with a catch test when the material or its batch changes",
                         ""});
        break;
      case plot::ReportVerdict::Level::kMarginal:
        if (quick_check) {
          steps.push_back({"these few trays cannot tell: lay a row of trays across the whole throw and drive "
                           "three passes over it",
                           "spread calibrate tray TRAYS.csv --width " + format("%g", bout_width_m)});
        } else {
          // Below the bout the working width is a width to drive; at or above it, only a margin is gained.
          const bool narrower = working_width_m > 0.0 && working_width_m < bout_width_m;
          steps.push_back({std::string(passes < 3 ? "drive more passes over the trays" : "repeat the tray test") +
                               " to narrow the interval, or " +
                               (narrower ? "drive bouts of at most " + format("%.2f m", working_width_m) +
                                               " (within the target)"
                                         : "drive a bout narrower than " + bout + " for a margin below the target"),
                           ""});
        }
        break;
      case plot::ReportVerdict::Level::kFail:
        if (quick_check) {
          steps.push_back({"the spread across this bout is uneven: lay a row of trays across the whole throw to "
                           "find the working width and what to change",
                           "spread calibrate tray TRAYS.csv --width " + format("%g", bout_width_m)});
          break;
        }
        steps.push_back({"the spread is uneven at " + bout + ": drive bouts of at most " +
                             format("%.2f m", working_width_m) +
                             ", or change the setting — fit the machine's table to this tray test and take the "
                             "setting for your bout width from its chart",
                         "spread calibrate pattern --tables TABLE.sqlite --material MATERIAL --rpm RPM --trays " + file +
                             " --output CALIBRATED.sqlite --width " + format("%g", bout_width_m)});
        steps.push_back(make_a_table_step());
        break;
      case plot::ReportVerdict::Level::kNone:
        steps.push_back({"too few trays of the bout were weighed: weigh the missing trays, or lay them again and "
                         "repeat the pass",
                         ""});
        break;
    }
  }
  return steps;
}

std::vector<NextStep> pattern_next_steps(bool written, const std::string& table, const std::string& material,
                                         double width_m) {
  if (!written) {
    return {{"the fit was refused (above): check the tray test and the disc speed it was driven at, then fit again",
             ""}};
  }
  const std::string widths = width_m > 0.0 ? format("%g", width_m) : std::string("12,15,18,21,24");
  return {{"take the disc speed and drop point for your bout width from the calibrated material's chart",
           "spread chart --tables " + quoted(table) + " --material " + quoted(material) + " --widths " + widths},
          {"set them, then lay the trays again and confirm the spread with a second tray test", ""}};
}

std::vector<NextStep> predict_next_steps(const std::vector<Verdict>& verdicts, const std::string& table,
                                         const std::string& material, double width_m) {
  const std::string chart = "spread chart --tables " + quoted(table) + " --material " + quoted(material) + " --widths ";
  if (verdicts.empty() || !(width_m > 0.0)) {
    return {{"give your bout width: the CV there, and what to change when it is above the target",
             "spread predict --tables " + quoted(table) + " --material " + quoted(material) + " --rpm RPM --width W"}};
  }
  if (verdicts.front().shown.level == plot::ReportVerdict::Level::kPass) {
    return {{"the table predicts an even spread at " + format("%.2f m", width_m) +
                 ": confirm it with a tray test across the whole throw at this setting",
             "spread calibrate tray TRAYS.csv --width " + format("%g", width_m)}};
  }
  return {{"change one setting as listed above, or take the disc speed and drop point for your bout width from "
           "the chart",
           chart + format("%g", width_m)},
          {"confirm the new setting with a tray test across the whole throw",
           "spread calibrate tray TRAYS.csv --width " + format("%g", width_m)}};
}

std::vector<NextStep> chart_next_steps() {
  return {{"set both discs to the speed and drop point of your bout width", ""},
          {"the gate meters for a width: at another bout width than your catch test's, set the gate for this one",
           "spread calibrate rate --mass KG --time S --gate G --target-rate KG_HA --width W --speed KM_H"},
          {"confirm the spread at the new setting with a tray test across the whole throw",
           "spread calibrate tray TRAYS.csv --width W"}};
}

std::string gate_follows_width(double from_m, double to_m) {
  const double change = 100.0 * (to_m / from_m - 1.0);
  return "the gate meters " + format("%.1f %%", std::abs(change)) + (change < 0.0 ? " less" : " more") +
         " for the same rate: its opening × " + format("%.2f", to_m) + "/" + format("%.2f", from_m) +
         " on a metering line through zero";
}

}  // namespace spread::cli
