// Batches of independent flights over std::thread workers. Each flight depends only on its own inputs and
// lands in its own output slot, so the results are bit-identical for any thread count; contiguous chunks
// keep each worker's output writes on its own cache lines.
#include <algorithm>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "libspread/physics/flight/fly_unchecked.hpp"
#include "libspread/physics/flight/validation.hpp"

namespace spread::flight {

void fly_batch(std::span<const Granule> granules, std::span<const State> launches, double ground_z_m,
               const Air& air, EffectSet effects, const Settings& settings, std::span<Landing> out,
               int threads) {
  const std::size_t count = launches.size();
  if (granules.size() != count && granules.size() != 1) {
    throw std::invalid_argument("fly_batch: granules.size() (" + std::to_string(granules.size()) +
                                ") must be 1 or launches.size() (" + std::to_string(count) + ")");
  }
  if (out.size() != count) {
    throw std::invalid_argument("fly_batch: out.size() (" + std::to_string(out.size()) +
                                ") must equal launches.size() (" + std::to_string(count) + ")");
  }
  // Validate everything here so no exception has to cross a worker thread.
  detail::validate_shared_inputs(ground_z_m, air, effects, settings);
  for (std::size_t i = 0; i < count; ++i) {
    const Granule& granule = granules.size() == 1 ? granules[0] : granules[i];
    detail::validate_flight_inputs(granule, launches[i], ground_z_m, static_cast<long>(i));
    detail::validate_rk4_step(granule, launches[i], ground_z_m, air, effects, settings, static_cast<long>(i));
  }
  if (count == 0) return;

  const auto fly_range = [&](std::size_t begin, std::size_t end) {
    const StepObserver no_observer{};
    for (std::size_t i = begin; i < end; ++i) {
      const Granule& granule = granules.size() == 1 ? granules[0] : granules[i];
      out[i] = detail::fly_unchecked(granule, launches[i], ground_z_m, air, effects, settings, no_observer);
    }
  };

  std::size_t workers = threads > 0 ? static_cast<std::size_t>(threads)
                                    : std::max<std::size_t>(1, std::thread::hardware_concurrency());
  workers = std::min(workers, count);
  if (workers <= 1) {
    fly_range(0, count);
    return;
  }
  std::vector<std::thread> pool;  // allocation per batch, not per flight
  pool.reserve(workers - 1);
  const std::size_t chunk = (count + workers - 1) / workers;
  for (std::size_t w = 1; w < workers; ++w) {
    const std::size_t begin = std::min(count, w * chunk);
    const std::size_t end = std::min(count, begin + chunk);
    if (begin < end) pool.emplace_back(fly_range, begin, end);
  }
  fly_range(0, std::min(count, chunk));  // the calling thread takes the first chunk
  for (auto& thread : pool) thread.join();
}

}  // namespace spread::flight
