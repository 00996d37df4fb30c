/* Predict the spread pattern of a twin-disc spreader from a launch-table file.
 * Build: cc -std=c99 example.c -Icapi/include -Lbuild/capi -lspreadc ... (see "Linking" above).
 * Run:   ./example tables.sqlite */
#include <stdio.h>
#include <stdlib.h>

#include "spread/spread.h"

int main(int argc, char** argv) {
  spread_tables* tables = NULL;
  spread_status status;
  spread_prediction_def def;
  spread_prediction result;
  const char* material = NULL;
  double min_rpm = 0.0, max_rpm = 0.0;
  double* trays = NULL;
  size_t capacity = 0;
  int32_t k;

  if (argc != 2) {
    fprintf(stderr, "usage: %s TABLES.sqlite\n", argv[0]);
    return 2;
  }
  if (spread_version() / 10000 != SPREAD_VERSION_MAJOR) {
    fprintf(stderr, "libspread %s does not match the header %s\n", spread_version_string(),
            SPREAD_VERSION_STRING);
    return 1;
  }

  /* Open (read-only); all workspace is allocated here, not during predictions. */
  status = spread_open(argv[1], &tables);
  if (status != SPREAD_OK) {
    fprintf(stderr, "%s: %s\n", argv[1], spread_status_str(status));
    return 1;
  }

  /* Pick the first material and the middle of its rpm range. */
  if (spread_material_name(tables, 0, &material) != SPREAD_OK ||
      spread_material_rpm_range(tables, 0, &min_rpm, &max_rpm) != SPREAD_OK) {
    spread_close(tables);
    return 1;
  }

  /* Caller-owned buffer for the transverse distribution, sized by the bounds query. */
  def = spread_prediction_def_default(); /* always start from the defaults */
  def.material = material;
  def.rpm = 0.5 * (min_rpm + max_rpm);
  def.cv_target_percent = 15.0;
  if (spread_transverse_bound(tables, def.tray_width_m, &capacity) != SPREAD_OK) {
    spread_close(tables);
    return 1;
  }
  trays = (double*)malloc(capacity * sizeof(double));
  if (trays == NULL) {
    spread_close(tables);
    return 1;
  }

  status = spread_predict(tables, &def, &result, trays, capacity);
  if (status != SPREAD_OK) {
    fprintf(stderr, "predict %s at %.0f rpm: %s\n", material, def.rpm, spread_status_str(status));
    free(trays);
    spread_close(tables);
    return 1;
  }

  printf("%s at %.0f rpm: throw width %.1f m, working width %.1f m (to-and-fro) / %.1f m (racetrack),"
         " CV %.1f %% at %.1f m\n",
         material, def.rpm, result.throw_width_m, result.working_width_to_and_fro_m,
         result.working_width_racetrack_m, result.cv_percent, result.bout_width_m);
  for (k = 0; k < result.tray_count; ++k) {
    printf("%7.2f m %6.3f %%\n", result.tray_left_edge_m + (k + 0.5) * result.tray_width_m, 100.0 * trays[k]);
  }

  free(trays);
  spread_close(tables);
  return 0;
}
