#include "libspread/accuracy/accuracy.hpp"

namespace spread::accuracy {

// The source tree's scenes/default.toml (the Case-1 twin-disc machine the bundled tables describe).
std::string default_scene_path() { return SPREAD_ACCURACY_DEFAULT_SCENE; }

}  // namespace spread::accuracy
