#pragma once
// The scene a table run was built from, recovered from the run's provenance text (Run::scene_text =
// Scene::provenance_text(): the TOML text, then the --set overrides as "# --set key=value" comment lines).
// The analytic launch model needs the full machine geometry (vane radii) and the inlet, which only the
// scene holds; the table's machine row has the rest.
#include "libspread/io/scene/scene.hpp"
#include "libspread/io/tables/table_format.hpp"

namespace spread::calibration {

// Throws scene::SceneError when the stored text is not a valid scene (message names the run).
scene::Scene scene_of_run(const tables::Run& run);

}  // namespace spread::calibration
