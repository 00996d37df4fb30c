#pragma once
// The `spread drum` run (cmd_drum.cpp), also taken by `spread simulate` for a scene with a [drum] table.
#include <string>
#include <vector>

namespace spread::drum {

// Loads the drum scene with its --set overrides and runs it, or one run per Froude number of `sweep`
// (comma-separated; empty: one run) with the regime map PNG at `map_path` (empty: none). Prints text, or
// JSON with `json_out`. Returns the exit code.
int run_drum_command(const std::string& scene_path, const std::vector<std::string>& overrides, bool json_out,
                     const std::string& sweep, const std::string& map_path);

}  // namespace spread::drum
