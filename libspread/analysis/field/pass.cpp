// Pass kinds and lengths.
#include "libspread/analysis/field/pass.hpp"

namespace spread::field {

const char* to_string(PassKind kind) {
  switch (kind) {
    case PassKind::kHeadland: return "headland";
    case PassKind::kTramline: return "tramline";
    case PassKind::kTrack: return "track";
  }
  return "?";
}

double path_length_m(const std::vector<Point>& path) {
  double total = 0.0;
  for (std::size_t i = 1; i < path.size(); ++i) total += length(path[i] - path[i - 1]);
  return total;
}

}  // namespace spread::field
