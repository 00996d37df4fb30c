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
  if (predictor.predict(request, prediction) != predict::PredictStatus::kOk || prediction.band_count_to_and_fro == 0) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  return predict::kConfidence95 * prediction.bands_to_and_fro[0].upper_se_m;
}

}  // namespace spread::lookup
