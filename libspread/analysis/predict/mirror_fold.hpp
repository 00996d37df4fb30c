#pragma once
// The right disc as the left one's mirror image on a tray layout symmetric about the centre line: tray k's
// kernel mass goes to tray T − 1 − k, so a quantity binned from the left disc's landings alone becomes the
// machine's by folding (and a gradient over trays becomes the left landing's alone: Σ_k g_k K_k(x) +
// Σ_k g_k K_k(−x) = Σ_k (g_k + g_{T−1−k}) K_k(x)).
#include <cstddef>
#include <span>

namespace spread::predict {

// values[k] and values[T − 1 − k] both become their sum (T even).
inline void fold_mirror(std::span<double> values) {
  const std::size_t count = values.size();
  for (std::size_t k = 0; k < count / 2; ++k) {
    const double sum = values[k] + values[count - 1 - k];
    values[k] = sum;
    values[count - 1 - k] = sum;
  }
}

}  // namespace spread::predict
