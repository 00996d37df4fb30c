#include "lookup_builder/row_uncertainty.hpp"

#include <limits>

#include "libspread/analysis/predict/predictor.hpp"

namespace spread::lookup {

double row_working_width_ci_m(const tables::Machine& machine, const tables::Material& material, const tables::Run& run) {
  tables::TableContents contents;
  contents.machine = machine;
  contents.materials = {material};
  contents.runs = {run};
  predict::Predictor predictor(std::move(contents));
  predict::PredictionRequest request;
  request.material = material.name;
  request.rpm = run.rpm;
  predict::Prediction prediction;
  if (predictor.predict(request, prediction) != predict::PredictStatus::kOk ||
      !(prediction.working_width_to_and_fro_m > 0.0)) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  constexpr double kZ95 = 1.96;  // two-sided 95 % of the normal distribution
  return kZ95 * prediction.working_width_to_and_fro_se_m;
}

}  // namespace spread::lookup
