#include "libspread/analysis/predict/run_flight_effects.hpp"

#include <optional>
#include <string>

namespace spread::predict {

flight::EffectSet run_flight_effects(const tables::Run& run) {
  const std::optional<std::string> recorded = tables::recorded_flight_effects(run);
  return recorded ? flight::parse_effects(*recorded) : kUnrecordedRunEffects;
}

}  // namespace spread::predict
