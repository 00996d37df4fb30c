/* The C API from C99 (compiled with -std=c99 -Wall -Wextra -pedantic -Werror): every declaration of
 * spread.h must be C, the inline defaults must work in C, and the basic calls must behave. Exit code 0 =
 * pass; each failed check prints its line. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "spread/spread.h"

static int failures = 0;
#define CHECK(cond)                                              \
  do {                                                           \
    if (!(cond)) {                                               \
      fprintf(stderr, "%s:%d: CHECK(%s) failed\n", __FILE__, __LINE__, #cond); \
      ++failures;                                                \
    }                                                            \
  } while (0)

/* A caller's allocator in C: malloc with a count of live blocks (alignment <= 16 here). */
static long live_blocks = 0;
static void* counted_alloc(void* user, size_t size, size_t alignment) {
  (void)user;
  if (alignment > 16) return NULL;
  ++live_blocks;
  return malloc(size);
}
static void counted_free(void* user, void* pointer, size_t size) {
  (void)user;
  (void)size;
  --live_blocks;
  free(pointer);
}

int main(int argc, char** argv) {
  spread_tables* tables = NULL;
  spread_prediction_def def = spread_prediction_def_default();
  spread_trajectory_def traj = spread_trajectory_def_default();
  spread_prediction result;
  spread_landing landing;
  double trays[1000];
  size_t bound = 0;
  int32_t count = 0;
  const char* name = NULL;

  if (argc != 2) {
    fprintf(stderr, "usage: capi_c99 TABLES.sqlite\n");
    return 2;
  }
  CHECK(def.struct_size == sizeof(spread_prediction_def));
  CHECK(isnan(def.disc_height_m));
  CHECK(def.cv_target_percent == 15.0);
  CHECK(def.effects == SPREAD_EFFECTS_AS_TABLE);
  CHECK(isnan(def.kernel_half_width_m));
  /* The layouts a C compiler gives end in no padding either (docs/c-api.md "ABI rules"). */
  CHECK(traj.reserved == 0u);
  CHECK(sizeof(spread_trajectory_def) == offsetof(spread_trajectory_def, reserved) + sizeof traj.reserved);
  CHECK(sizeof(spread_landing) == offsetof(spread_landing, reserved) + sizeof landing.reserved);
  CHECK(sizeof(spread_prediction_def) == offsetof(spread_prediction_def, reserved2) + sizeof def.reserved2);
  CHECK(def.fly_outside_domain == 0u && def.reserved2 == 0u);
  CHECK(def.drop_point_turn_rad == 0.0);
  CHECK(isnan(def.disc_rpm[0]) && isnan(def.disc_rpm[1]));
  CHECK(isnan(def.disc_drop_point_turn_rad[0]) && isnan(def.disc_drop_point_turn_rad[1]));
  CHECK(def.result_size == sizeof(spread_prediction) && def.reserved == 0u);
  CHECK(sizeof(spread_band) == offsetof(spread_band, limited_by_layout) + sizeof(int32_t));
  CHECK(sizeof(spread_prediction) == offsetof(spread_prediction, disc_drop_point_turn_rad) + sizeof result.disc_drop_point_turn_rad);
  CHECK(spread_version() == SPREAD_VERSION_NUMBER);
  CHECK(strcmp(spread_version_string(), SPREAD_VERSION_STRING) == 0);
  CHECK(strncmp(spread_status_str(SPREAD_ERROR_FILE_CORRUPT), "SPREAD_ERROR_FILE_CORRUPT", 25) == 0);

  CHECK(spread_open("/nonexistent/tables.sqlite", &tables) == SPREAD_ERROR_FILE_MISSING);
  CHECK(tables == NULL);
  CHECK(spread_open(argv[1], &tables) == SPREAD_OK);
  if (tables == NULL) return 1;

  CHECK(spread_material_count(tables, &count) == SPREAD_OK && count == 2);
  CHECK(spread_material_name(tables, 0, &name) == SPREAD_OK && strcmp(name, "can") == 0);
  CHECK(spread_transverse_bound(tables, 0.5, &bound) == SPREAD_OK && bound <= 1000);

  def.material = "can";
  def.rpm = 640.0;
  CHECK(spread_predict(tables, &def, &result, trays, sizeof trays / sizeof trays[0]) == SPREAD_OK);
  CHECK(result.working_width_to_and_fro_m > 0.0);
  CHECK(result.tray_count > 0 && (size_t)result.tray_count <= bound);
  def.rpm = NAN;
  CHECK(spread_predict(tables, &def, &result, NULL, 0) == SPREAD_ERROR_NOT_FINITE);
  def.rpm = 1e4;
  CHECK(spread_predict(tables, &def, &result, NULL, 0) == SPREAD_ERROR_RPM_OUTSIDE_TABLE);
  def.rpm = 640.0;
  def.material = "sand";
  CHECK(spread_predict(tables, &def, &result, NULL, 0) == SPREAD_ERROR_UNKNOWN_MATERIAL);

  traj.position_m[2] = 1.0;
  traj.velocity_m_s[0] = 10.0;
  CHECK(spread_trajectory(&traj, &landing) == SPREAD_OK);
  CHECK(landing.position_m[0] > 1.0 && landing.position_m[0] < 10.0);
  CHECK(landing.reserved == 0);

  CHECK(strstr(spread_last_error_detail(), "sand") != NULL);

  spread_close(tables);

  {
    /* One shared handle from a caller's allocator, and a workspace for another thread. */
    spread_allocator allocator;
    spread_workspace* workspace = NULL;
    allocator.alloc = counted_alloc;
    allocator.free = counted_free;
    allocator.user = NULL;
    tables = NULL;
    CHECK(spread_open_with_allocator(argv[1], &allocator, &tables) == SPREAD_OK);
    if (tables == NULL) return 1;
    CHECK(live_blocks > 0);
    CHECK(spread_workspace_create(tables, &workspace) == SPREAD_OK);
    def.material = "can";
    def.rpm = 640.0;
    CHECK(spread_workspace_predict(workspace, &def, &result, NULL, 0) == SPREAD_OK);
    CHECK(result.working_width_to_and_fro_m > 0.0);
    spread_workspace_free(workspace);
    spread_close(tables);
    CHECK(live_blocks == 0);
  }
  if (failures == 0) printf("capi_c99: all checks passed\n");
  return failures == 0 ? 0 : 1;
}
