#pragma once
// Maps a scene (libspread/io/scene) to the engine's own plain configuration, so the engine never depends
// on the scene parser. The only file of the DEM that knows the scene format.
#include <string>

#include "libspread/physics/dem/simulate.hpp"
#include "libspread/io/scene/scene.hpp"

namespace spread::dem {

// `material_name` empty: the scene's [simulate] material. Throws std::invalid_argument naming the
// scene key when a value cannot be used by the DEM.
SimulationConfig config_from_scene(const scene::Scene& scene, const std::string& material_name = "");

}  // namespace spread::dem
