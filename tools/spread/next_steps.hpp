#pragma once
// What to do next, at the end of every calibration command: in the technician's terms — re-test at this
// gate, drive this bout width, this result needs a table and how to make one — each step a plain sentence
// (the report page's "Next steps", words a farmer reads) and, on the terminal, the command that does it.
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tools/spread/verdicts.hpp"

namespace spread::cli {

struct NextStep {
  std::string what;     // the sentence: no option names, no paths
  std::string command;  // the command that does it ("" when it is work in the field)
};

// Printed last on the terminal: "next: <what>" and, indented below it, the command.
void print_next_steps(const std::vector<NextStep>& steps);
// --json's "next_steps": [{"what", "command"}].
nlohmann::json next_steps_json(const std::vector<NextStep>& steps);
// The page's notes: "Next: <what>".
std::vector<std::string> next_steps_notes(const std::vector<NextStep>& steps);

// How a table is made, for the steps that need one (lookup_builder on the machine's scene; the DEM
// takes minutes).
NextStep make_a_table_step();

// After a catch test: set the gate, then check the spread across the bout with a tray test at it.
std::vector<NextStep> rate_next_steps(double required_gate, double current_gate, double width_m);

// After a tray test or quick check, by its verdicts (the CV's first, then the rate's): what the
// technician does at the bout `bout_width_m` judged, given the working width found (0: a quick check).
std::vector<NextStep> tray_next_steps(const std::vector<Verdict>& verdicts, double bout_width_m, double working_width_m,
                                      bool width_given, int passes, bool quick_check, const std::string& tray_file);

// After a pattern calibration written as `material` into `table` (nothing written: refused).
std::vector<NextStep> pattern_next_steps(bool written, const std::string& table, const std::string& material,
                                         double width_m);

// After a prediction at `width_m` (0: none given) from `table`, by its verdicts.
std::vector<NextStep> predict_next_steps(const std::vector<Verdict>& verdicts, const std::string& table,
                                         const std::string& material, double width_m);

// After a setting chart: set the discs for the width, keep the rate right at that width, confirm.
std::vector<NextStep> chart_next_steps();

// A bout width changed from `from_m` to `to_m` at the same rate and speed moves the gate: on a metering
// line through zero its opening scales with the width ("the gate meters 4.2 % less for the same rate: ...").
std::string gate_follows_width(double from_m, double to_m);

}  // namespace spread::cli
