/*
 * spread.h — C API of libspread: predict where a centrifugal fertiliser spreader throws its granules,
 * from a launch-table file (docs/design.md §4) and a ballistic flight model (seed 000, Sect. 2.4).
 *
 * C99, no dependencies beyond the C standard library. Guide and a complete example: docs/c-api.md.
 *
 * Conventions
 * - Every function that can fail returns a spread_status; SPREAD_OK (0) is success. Outputs are written
 *   only on success unless a function says otherwise. spread_status_str() names every code.
 * - Units are SI and appear in every field name (_m, _s, _m_s, _kg_m3, _rpm, _percent).
 * - Frame: x lateral (positive to the machine's right), y along the driving direction (forward), z up;
 *   the ground is z = 0 for predictions.
 * - Ownership (as sqlite3): a spread_tables handle is created by spread_open() and destroyed by
 *   spread_close(). Strings returned by the library belong to the handle and stay valid until
 *   spread_close(). Strings passed in (path, material name) are only read during the call. Result structs
 *   and buffers belong to the caller.
 * - No allocation during spread_predict() or spread_trajectory(): all workspace is allocated by
 *   spread_open() (or spread_workspace_create()). Memory of handles and workspaces can come from the
 *   caller's allocator (spread_open_with_allocator()).
 * - Worst case, stack: docs/c-api.md states the worst-case time of every call and the stack a call
 *   needs (spread_predict: under 8 KiB of the caller's stack).
 * - No C++ exception ever crosses this interface; an unexpected failure is SPREAD_ERROR_INTERNAL.
 *
 * Thread-safety
 *   A spread_tables handle holds the table (read-only after spread_open) and one prediction workspace.
 *   spread_predict(tables, ...) uses that workspace: one thread at a time per handle. To predict on
 *   several threads, open the table once and give each thread a spread_workspace
 *   (spread_workspace_create, cheap: no file access, no table copy); spread_workspace_predict only reads
 *   the handle, so workspaces of one handle may predict concurrently, also with the query functions
 *   (spread_material_*, spread_default_disc_height, spread_transverse_bound, which only read). Opening
 *   the same file once per thread also still works. Functions without a handle (spread_trajectory,
 *   spread_status_str, spread_version*, spread_last_error_detail) are thread-safe.
 *
 * ABI stability
 *   Definition structs carry struct_size, filled in by the static inline *_default() functions below with
 *   the sizeof() the caller was compiled with. The library reads struct_size to learn which header version
 *   the caller used, and reads/writes only the fields that version has (the definition and its result).
 *   New fields are only ever appended; existing fields, enum values and function signatures never change
 *   within a major version. Always start from *_default() and then set the fields you need.
 *   No published struct ends in padding: where alignment would leave some, a `reserved` field fills it
 *   (zeroed by *_default() and by the library, never read), so a field appended later always makes
 *   sizeof() larger and an older caller's struct_size can never cover it (docs/c-api.md "ABI rules").
 */
#ifndef SPREAD_SPREAD_H
#define SPREAD_SPREAD_H

#include <math.h>   /* NAN for the defaults */
#include <stddef.h> /* size_t */
#include <stdint.h> /* int32_t, uint32_t */

/* Compile-time version. spread_version() returns the run-time one: compare them to detect a mismatch
 * between the header you compiled with and the library you linked. */
#define SPREAD_VERSION_MAJOR 0
#define SPREAD_VERSION_MINOR 6
#define SPREAD_VERSION_PATCH 0
#define SPREAD_VERSION_NUMBER (SPREAD_VERSION_MAJOR * 10000 + SPREAD_VERSION_MINOR * 100 + SPREAD_VERSION_PATCH)
#define SPREAD_VERSION_STRING "0.6.0"

#if defined(__GNUC__) || defined(__clang__)
#define SPREAD_API __attribute__((visibility("default")))
#else
#define SPREAD_API
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* ---------------------------------------------------------------------------------------------------
 * Status codes. Values are stable: new codes are appended, existing ones never renumbered.
 * ------------------------------------------------------------------------------------------------- */
typedef enum spread_status {
  SPREAD_OK = 0,
  SPREAD_ERROR_NULL_POINTER = 1,       /* a required pointer argument is NULL */
  SPREAD_ERROR_NOT_FINITE = 2,         /* a floating-point argument is NaN or infinite */
  SPREAD_ERROR_OUT_OF_RANGE = 3,       /* a value outside its domain (negative height, CV target <= 0,
                                          tray width <= 0, index >= count, struct_size too small, ...) */
  SPREAD_ERROR_RPM_OUTSIDE_TABLE = 4,  /* rpm outside [min, max] of the material's table rows */
  SPREAD_ERROR_UNKNOWN_MATERIAL = 5,   /* no material of that name in the file */
  SPREAD_ERROR_UNKNOWN_EFFECT = 6,     /* effect bits outside SPREAD_EFFECT_ALL | SPREAD_EFFECTS_AS_TABLE */
  SPREAD_ERROR_BUFFER_TOO_SMALL = 7,   /* caller buffer smaller than needed; see spread_transverse_bound */
  SPREAD_ERROR_FILE_MISSING = 8,       /* no such file */
  SPREAD_ERROR_FILE_NOT_OURS = 9,      /* not SQLite, or not a libspread launch-table file */
  SPREAD_ERROR_FILE_CORRUPT = 10,      /* integrity check failed or a record is malformed */
  SPREAD_ERROR_FILE_WRONG_VERSION = 11,/* a launch-table file of another format version */
  SPREAD_ERROR_FILE_EMPTY = 12,        /* a launch-table file without runs */
  SPREAD_ERROR_IO = 13,                /* any other failure reading the file (locked, unreadable) */
  SPREAD_ERROR_OUT_OF_MEMORY = 14,     /* spread_open could not allocate */
  SPREAD_ERROR_NOT_LANDED = 15,        /* a trajectory did not reach the ground within the time limit */
  SPREAD_ERROR_INTERNAL = 16,          /* unexpected failure inside the library (a bug: please report) */
  SPREAD_ERROR_BAD_HANDLE = 17,        /* not a live handle: already closed/freed, or not made by this
                                          library (best-effort detection, see spread_close) */
  SPREAD_ERROR_OUTSIDE_DOMAIN = 18     /* (appended in 0.5) a request the table's landing grid does not
                                          cover: a disc height or wind outside spread_landing_domain, or
                                          effects beyond the table's; see fly_outside_domain */
} spread_status;

/* Name of a status code, e.g. "SPREAD_ERROR_UNKNOWN_MATERIAL: unknown material". Never NULL; static
 * storage. Unknown values give "unknown status". */
SPREAD_API const char* spread_status_str(spread_status status);

/* Run-time version: SPREAD_VERSION_NUMBER and SPREAD_VERSION_STRING of the library you linked. */
SPREAD_API uint32_t spread_version(void);
SPREAD_API const char* spread_version_string(void);

/* ---------------------------------------------------------------------------------------------------
 * In-flight effects: SPREAD_EFFECT_<NAME> for each flight effect of docs/scene-format.md, the bit of its
 * effect registry row (checked by the library's build and tests); SPREAD_EFFECT_ALL is all of them.
 * Bits are never renumbered. Gravity always acts.
 * ------------------------------------------------------------------------------------------------- */
#define SPREAD_EFFECT_DRAG 0x1u       /* air drag, seed Eq. 27 with the Haider–Levenspiel C_D, Eq. 32 */
#define SPREAD_EFFECT_MAGNUS 0x2u     /* Magnus lift, Eq. 28 (smoothly vanishing lift model) */
#define SPREAD_EFFECT_SPIN_DECAY 0x4u /* spin decay in flight, Eqs. 34–36 */
#define SPREAD_EFFECT_WIND 0x8u       /* wind: the relative air velocity replaces the granule velocity */
#define SPREAD_EFFECT_ALL (SPREAD_EFFECT_DRAG | SPREAD_EFFECT_MAGNUS | SPREAD_EFFECT_SPIN_DECAY | SPREAD_EFFECT_WIND)
/* The flight effects the table file was built with (each run records them; files that do not record
 * them mean drag, Magnus, spin decay and wind), plus any SPREAD_EFFECT_* bits given beside it, plus
 * SPREAD_EFFECT_WIND whenever the wind is not zero (the wind is a condition of the day, not of the
 * machine). The default. */
#define SPREAD_EFFECTS_AS_TABLE 0x80000000u

/* ---------------------------------------------------------------------------------------------------
 * Launch-table handle
 * ------------------------------------------------------------------------------------------------- */
typedef struct spread_tables spread_tables; /* opaque */

/* Opens a launch-table file read-only, checks it (application id, format version, integrity, records),
 * reads it into memory and allocates all prediction workspace. On success *out_tables is a new handle;
 * on failure *out_tables is set to NULL (when out_tables is not NULL) and the status says why:
 * SPREAD_ERROR_FILE_MISSING / _NOT_OURS / _CORRUPT / _WRONG_VERSION (also a legacy table, whose runs carry
 * no checked list: see SPREAD_OPEN_LEGACY_FILES) / _EMPTY / _IO / _OUT_OF_MEMORY. */
SPREAD_API spread_status spread_open(const char* path, spread_tables** out_tables);

/* Destroys a handle. NULL is a no-op. Its workspaces must not be used afterwards (they may still be
 * freed, before or after). A handle that
 * is not live (closed already) is left alone: the handle carries a tag that spread_open sets and
 * spread_close clears, and every function checks it (SPREAD_ERROR_BAD_HANDLE). After the memory is
 * freed that check reads freed memory, so it catches a double close or a use after close only as long as
 * the memory has not been reused: best effort, not a guarantee. */
SPREAD_API void spread_close(spread_tables* tables);

/* Materials, sorted by name, indexed 0 .. count-1. The name string belongs to the handle. */
SPREAD_API spread_status spread_material_count(const spread_tables* tables, int32_t* out_count);
SPREAD_API spread_status spread_material_name(const spread_tables* tables, int32_t index,
                                              const char** out_name);
/* The rpm range [min, max] of the material's table rows; predictions outside it are refused. */
SPREAD_API spread_status spread_material_rpm_range(const spread_tables* tables, int32_t index,
                                                   double* out_min_rpm, double* out_max_rpm);
/* Height of the disc above the ground stored with the machine (used when the definition says NaN). */
SPREAD_API spread_status spread_default_disc_height(const spread_tables* tables, double* out_height_m);
/* (appended in 0.5) The conditions the table's landing grid answers from every launch sample at the
 * grid's cost: disc heights [*out_min_height_m, *out_max_height_m] (m) and horizontal winds up to
 * *out_max_wind_m_s (m/s), with the table's own flight effects. Outside them spread_predict refuses with
 * SPREAD_ERROR_OUTSIDE_DOMAIN unless the definition sets fly_outside_domain. SPREAD_ERROR_OUTSIDE_DOMAIN
 * here: the material (index as spread_material_name) has no grid, because its runs fly more than drag;
 * every request then flies every sample. */
SPREAD_API spread_status spread_landing_domain(const spread_tables* tables, int32_t index, double* out_min_height_m,
                                               double* out_max_height_m, double* out_max_wind_m_s);

/* ---------------------------------------------------------------------------------------------------
 * Prediction
 * ------------------------------------------------------------------------------------------------- */
typedef struct spread_prediction_def {
  uint32_t struct_size;        /* sizeof(spread_prediction_def) of the caller's header; set by _default() */
  const char* material;        /* material name (NUL-terminated), read during the call only. Required. */
  double rpm;                  /* disc speed, revolutions per minute; within the material's table range */
  double disc_height_m;        /* disc above the ground (m), 0..100; NaN = the machine's stored height */
  double wind_m_s[2];          /* wind (x lateral, y forward), m/s, each within [-100, 100]; used when
                                  SPREAD_EFFECT_WIND is set */
  double cv_target_percent;    /* CV target for the effective working widths, percent, in (0, 1000]
                                  (default 15) */
  uint32_t effects;            /* SPREAD_EFFECT_* bits, or SPREAD_EFFECTS_AS_TABLE (the default) */
  double bout_width_m;         /* bout width at which cv_percent is evaluated, m, 0..1000;
                                  0 = at the to-and-fro effective working width */
  double tray_width_m;         /* width of the collecting trays, m, 0.1..100 (default 0.5, ISO 5690) */
  /* --- appended in 0.2 --- */
  double kernel_half_width_m;  /* half-width of the kernel each landing's mass is spread over, m, 0..10;
                                  NaN (default) = automatic (docs/metrics.md), 0 = point masses */
  /* --- appended in 0.3 --- */
  uint32_t result_size;        /* sizeof(spread_prediction) of the caller's header; set by _default().
                                  The library writes the result fields of every version it covers whole
                                  (from 0.3 on the result grows without the definition growing); below
                                  0.2's result (every field up to kernel_half_width_m) it is refused */
  uint32_t reserved;           /* fills the padding before the next double; 0 from _default(), never read */
  double drop_point_turn_rad;  /* the drop point (feed position on the disc) turned from the table's, rad,
                                  within [-pi, pi]: counter-clockwise seen from above for the left disc,
                                  mirrored for the right (both discs alike). A disc the same all round
                                  turns its fan of launches by the same angle (docs/c-api.md). Default 0 */
  /* --- appended in 0.4 --- */
  double disc_rpm[2];          /* each disc's own speed, r/min: [0] the left disc, [1] the right (as the
                                  driver sees them); NaN (default) = rpm above. Within the material's
                                  table range. With both given, rpm must be 0 (it would be unused) */
  double disc_drop_point_turn_rad[2]; /* each disc's own drop-point turn, rad, within [-pi, pi], as
                                  drop_point_turn_rad for that disc; NaN (default) = drop_point_turn_rad.
                                  With both given, drop_point_turn_rad must be 0. A one-disc machine has
                                  only [0]: a value in [1] is refused */
  /* --- appended in 0.5 --- */
  uint32_t fly_outside_domain; /* 0 (default): a request outside the landing grid's domain is refused with
                                  SPREAD_ERROR_OUTSIDE_DOMAIN, so every answered request costs the
                                  grid's time; 1: it flies every launch sample instead (tens of
                                  milliseconds, docs/c-api.md "Landing grid"). Any other value is
                                  refused (SPREAD_ERROR_OUT_OF_RANGE). A definition older than 0.5 has 0 */
  uint32_t reserved2;          /* fills the struct to a whole double; 0 from _default(), never read */
} spread_prediction_def;

/* One band of bout widths whose CV meets the target (appended in 0.3). */
#define SPREAD_MAX_BANDS 4
typedef struct spread_band {
  double lower_m;                     /* narrowest bout width of the band */
  double upper_m;                     /* widest bout width, interpolated between whole trays */
  double upper_se_m;                  /* its standard error; NaN when the band reaches the layout's edge */
  double bout_width_m;                /* the widest whole-tray bout inside the band */
  double cv_percent;                  /* CV there */
  double cv_se_percent;
  double lowest_cv_percent;           /* the band's lowest CV */
  double lowest_cv_se_percent;
  double lowest_cv_bout_width_m;      /* and where */
  int32_t established;                /* 1: lowest_cv + 1.96 SE <= target (the headline rule's test) */
  int32_t limited_by_layout;          /* 1: CV stays within the target to the widest layout */
} spread_band;

/* Result of one prediction (whole machine: one disc or two counter-rotating discs). Caller-owned. */
typedef struct spread_prediction {
  double throw_width_m;               /* lateral extent holding 99 % of the mass */
  double working_width_to_and_fro_m;  /* the headline working width, to-and-fro (docs/metrics.md "Effective
                                         working width"): the upper end of the widest band of bout widths
                                         with CV <= target whose lowest CV meets the target at 95 %
                                         confidence, or that is joined to such a band by gaps the samples
                                         do not show above the target (the first band when none is); 0 =
                                         none. Before 0.3 this was the first band's upper end
                                         (first_band_width_*_m) */
  double working_width_racetrack_m;   /* the same for racetrack driving */
  double bout_width_m;                /* bout width cv_percent refers to (the requested one, or the
                                         to-and-fro working width); 0 when that width is 0 */
  double cv_percent;                  /* CV at bout_width_m, to-and-fro, percent; NaN when bout_width_m
                                         is 0 */
  double cv_racetrack_percent;        /* CV at bout_width_m, racetrack, percent; NaN when bout_width_m
                                         is 0 */
  double mean_radius_m;               /* R̄ of one disc's landings about its centre, seed Eq. 51 */
  double radial_width_m;              /* ξ, seed Eq. 52 */
  double disc_height_m;               /* the height used */
  double lost_mass_fraction;          /* mass that fell outside the tray range or did not land, 0..1 */
  int32_t tray_count;                 /* trays of the transverse distribution (needed buffer size) */
  double tray_width_m;                /* as requested */
  double tray_left_edge_m;            /* left edge of tray 0; tray k is centred at
                                         tray_left_edge_m + (k + 0.5) * tray_width_m */
  int32_t flights;                    /* trajectories integrated for this prediction (0: every landing
                                         came from the landing grid, docs/c-api.md) */
  /* --- appended in 0.2: written only for a definition of at least this version's struct_size ---
   * Monte Carlo standard errors over the table's launch samples (delta method, docs/metrics.md
   * "Uncertainty"); a 95 % interval is about ±2 standard errors. Between two DEM rows the throw width's,
   * the working widths' and the CVs' (not the bands') also hold the interpolation's own error as the
   * rows' disagreement shows it, in quadrature (docs/metrics.md "Between rows"). NaN where undefined (no
   * width meets the target, the crossing is the layout's edge, an infinite CV). */
  int32_t sample_count;               /* independent launch samples behind the estimate */
  double throw_width_se_m;
  double working_width_to_and_fro_se_m;
  double working_width_racetrack_se_m;
  double cv_se_percent;               /* of cv_percent */
  double cv_racetrack_se_percent;     /* of cv_racetrack_percent */
  int32_t cv_crossings_to_and_fro;    /* times CV(W) crosses the target; > 1: more than one band of bout
                                         widths meets it (see the bands below) */
  int32_t cv_crossings_racetrack;
  uint32_t effects;                   /* the SPREAD_EFFECT_* bits that ran */
  double kernel_half_width_m;         /* as used */
  /* --- appended in 0.3: written when def->result_size covers them ---
   * Every band of bout widths whose CV meets the target, narrowest first: the first
   * SPREAD_MAX_BANDS - 1 bands and the widest are kept (a spreader pattern has one to three). */
  int32_t band_count_to_and_fro;      /* bands found (may exceed SPREAD_MAX_BANDS) */
  int32_t band_count_racetrack;
  int32_t headline_band_to_and_fro;   /* index into bands_to_and_fro of the working width's band; -1 none */
  int32_t headline_band_racetrack;
  double first_band_width_to_and_fro_m;  /* the first band's upper end (the first rise of CV(W) above the
                                            target) */
  double first_band_width_racetrack_m;
  spread_band bands_to_and_fro[SPREAD_MAX_BANDS];
  spread_band bands_racetrack[SPREAD_MAX_BANDS];
  /* --- appended in 0.4: written when def->result_size covers them --- */
  double disc_rpm[2];                 /* each disc's speed as used, r/min ([1]: NaN on a one-disc machine) */
  double disc_drop_point_turn_rad[2]; /* each disc's drop-point turn as used, rad */
} spread_prediction;

/* Defaults. Static inline on purpose: the struct is built with the caller's sizeof, so a newer library
 * with a larger struct never writes past the caller's memory. */
static inline spread_prediction_def spread_prediction_def_default(void) {
  spread_prediction_def def;
  def.struct_size = (uint32_t)sizeof(spread_prediction_def);
  def.material = NULL;
  def.rpm = 0.0;
  def.disc_height_m = NAN;
  def.wind_m_s[0] = 0.0;
  def.wind_m_s[1] = 0.0;
  def.cv_target_percent = 15.0;
  def.effects = SPREAD_EFFECTS_AS_TABLE;
  def.bout_width_m = 0.0;
  def.tray_width_m = 0.5;
  def.kernel_half_width_m = NAN;
  def.result_size = (uint32_t)sizeof(struct spread_prediction);
  def.reserved = 0u;
  def.drop_point_turn_rad = 0.0;
  def.disc_rpm[0] = NAN;
  def.disc_rpm[1] = NAN;
  def.disc_drop_point_turn_rad[0] = NAN;
  def.disc_drop_point_turn_rad[1] = NAN;
  def.fly_outside_domain = 0u;
  def.reserved2 = 0u;
  return def;
}

/* Upper bound of spread_prediction.tray_count for any prediction on this handle with this tray width
 * (zstd-style bounds query): a transverse buffer of this many doubles is always large enough. */
SPREAD_API spread_status spread_transverse_bound(const spread_tables* tables, double tray_width_m,
                                                 size_t* out_tray_count);

/* Predicts the spread pattern. `transverse_mass_fraction` may be NULL (not wanted); otherwise it receives
 * result->tray_count values: the fraction of the machine's discharged mass caught by each tray (the sum
 * over trays is 1 - lost_mass_fraction). If transverse_capacity < result->tray_count the call returns
 * SPREAD_ERROR_BUFFER_TOO_SMALL, writes nothing to the buffer, but fills *result (so tray_count says how
 * many are needed). Input errors: SPREAD_ERROR_NULL_POINTER, _NOT_FINITE, _OUT_OF_RANGE, _UNKNOWN_MATERIAL,
 * _RPM_OUTSIDE_TABLE, _UNKNOWN_EFFECT. Does not allocate. Not re-entrant on one handle (see top).
 * Time (docs/c-api.md "Worst-case time", bench_capi DomainSweep over every material, speed, height, wind,
 * kernel and tray width the grid answers): the median request 1.6-2.5 ms on one core of a 2-core AMD EPYC
 * (Zen 4); the slowest about 3.5 ms with AVX or AVX-512 registers and 4.3 ms on the portable path, set by
 * each disc at its own speed between rows (whose standard errors hold the interpolation's own error). */
SPREAD_API spread_status spread_predict(spread_tables* tables, const spread_prediction_def* def,
                                        spread_prediction* result, double* transverse_mass_fraction,
                                        size_t transverse_capacity);

/* Wind compensation (0.4): the setting of each disc that brings the to-and-fro CV at def->bout_width_m
 * (> 0, required) back towards def->cv_target_percent in the wind def->wind_m_s, from the present setting
 * in def (rpm and drop point, or each disc's own). The discs' speeds move apart by ±d (the left disc +d)
 * within the table's rows and at most 150 rpm, and their drop points turn by ±t (the left +t, the right
 * -t in its mirrored frame: both fans turn the same way seen from above) within 45 degrees: a 5 x 5 grid,
 * then golden-section search along d (to 4 rpm) and t (to 0.5 degrees), at most 48 predictions without
 * standard errors and one with them (docs/c-api.md "Wind compensation" gives the cost). *result is the
 * prediction at the setting found; result->disc_rpm and result->disc_drop_point_turn_rad say the setting,
 * so def->result_size must cover 0.4's result (spread_prediction_def_default() sets it). Whether the CV
 * now meets the target: result->cv_percent. The same errors as spread_predict, and SPREAD_ERROR_OUT_OF_RANGE
 * without a bout width, on a one-disc machine or for a definition or result older than 0.4. Does not
 * allocate. Not re-entrant on one handle. */
SPREAD_API spread_status spread_compensate_wind(spread_tables* tables, const spread_prediction_def* def,
                                                spread_prediction* result, double* transverse_mass_fraction,
                                                size_t transverse_capacity);

/* (appended in 0.6) spread_compensate_wind within a budget a control loop can schedule: at most
 * max_predictions predictions (0: no limit; otherwise at least 3: the present setting's, the answer's and
 * the present setting's again should the answer come out higher). A setting of the search the budget
 * leaves no prediction for is not flown (the search goes on with the settings it has), the answer is the
 * best of those flown, never above the present setting's CV, and *out_finished is 1 when the whole search
 * ran (the answer then spread_compensate_wind's, bit for bit), 0 when the budget cut it. Each prediction
 * costs about what spread_predict's does without standard errors, so the budget sets the call's time
 * (docs/c-api.md "Wind compensation"). The errors of spread_compensate_wind, and SPREAD_ERROR_OUT_OF_RANGE
 * for a budget of 1 or 2 or below 0. */
SPREAD_API spread_status spread_compensate_wind_within(spread_tables* tables, const spread_prediction_def* def,
                                                       int32_t max_predictions, spread_prediction* result,
                                                       double* transverse_mass_fraction, size_t transverse_capacity,
                                                       int32_t* out_finished);

/* ---------------------------------------------------------------------------------------------------
 * Border and edge spreading (0.4): the last bout along a field edge (docs/c-api.md "Border and edge")
 * ------------------------------------------------------------------------------------------------- */
#define SPREAD_EDGE_BORDER 0u /* road, path, water: at most max_beyond_percent over the edge line */
#define SPREAD_EDGE_FIELD 1u  /* next to another field: the rate at the edge line at least min_edge_rate */
typedef struct spread_edge_def {
  uint32_t struct_size;         /* sizeof(spread_edge_def) of the caller's header; set by _default() */
  uint32_t kind;                /* SPREAD_EDGE_BORDER (default) or SPREAD_EDGE_FIELD */
  int32_t side;                 /* the edge's side as the driver sees it: 0 left, 1 right (default) */
  uint32_t reserved;            /* 0 from _default(), never read */
  double gap_m;                 /* the edge line this far inside the field edge, m, in [0, bout width / 2):
                                   water 1 with a border spreading device, 3 without (default 0) */
  double flow_fraction;         /* the edge-side disc's flow on the last pass, of the field's, [0, 1.2]
                                   (default 1; 0: that disc off) */
  double max_beyond_percent;    /* border: the most of the pass's mass over the line, (0, 100] (default 0.1) */
  double tolerance_percent;     /* over-applied above 100 + this (or the field interior's peak, where
                                   higher), under-applied below 100 - this, (0, 100] (default 10) */
  double min_edge_rate_percent; /* field edge: the rate at the edge line at least this, (0, 100] (default 80) */
} spread_edge_def;

static inline spread_edge_def spread_edge_def_default(void) {
  spread_edge_def edge;
  edge.struct_size = (uint32_t)sizeof(spread_edge_def);
  edge.kind = SPREAD_EDGE_BORDER;
  edge.side = 1;
  edge.reserved = 0u;
  edge.gap_m = 0.0;
  edge.flow_fraction = 1.0;
  edge.max_beyond_percent = 0.1;
  edge.tolerance_percent = 10.0;
  edge.min_edge_rate_percent = 80.0;
  return edge;
}

/* The profile of the last bout: x from the last tramline, towards the edge positive; rates as a percent
 * of the field's rate inside (one pass's landed mass per bout width). */
typedef struct spread_edge_result {
  double edge_line_m;              /* bout width / 2 - gap */
  double mass_beyond_percent;      /* of this pass's mass, over the edge line */
  double max_rate_inside_percent;  /* the highest rate of the last bout, [-W/2, edge line] */
  double rate_at_edge_percent;     /* over the tray width that ends at the line */
  double over_limit_percent;       /* 100 + tolerance: above it, and above what the field's interior gets
                                      there, a tray is over-applied (judged over every bout this pass
                                      reaches; `meets` says whether any bout is) */
  double under_limit_percent;      /* 100 - tolerance: below it, and below the interior there, under-applied */
  double missing_inside_m;         /* fertiliser missing in the last bout against the field's interior,
                                      in metres of field rate */
  int32_t meets;                   /* 1: the kind's thresholds hold */
  int32_t tray_count;              /* trays of the profile (needed buffer size) */
  double tray_width_m;
  double tray_left_edge_m;         /* tray k is centred at tray_left_edge_m + (k + 0.5) * tray_width_m */
} spread_edge_result;

/* The last bout along a field edge with the edge-side disc set apart. def: the field's setting (rpm, drop
 * point, wind, height, bout_width_m > 0 required — the last tramline lies half of it from the field edge)
 * and, in disc_rpm[side] / disc_drop_point_turn_rad[side], the edge-side disc's own setting on the last
 * pass (NaN: as the field); in disc_drop_point_turn_rad[1 - side] the other disc's drop point on that pass
 * (NaN: as the field; its disc_rpm must be NaN). `rate` may be NULL; otherwise it
 * receives result->tray_count rates (percent), or SPREAD_ERROR_BUFFER_TOO_SMALL as spread_predict. The
 * errors of spread_predict, and SPREAD_ERROR_OUT_OF_RANGE for an edge definition out of its domain (named
 * in spread_last_error_detail), a one-disc machine or a 0.3 definition. Allocates its working arrays
 * (the profile's trays and one disc's landings) through the handle's allocator; two predictions without
 * standard errors and the profile (docs/c-api.md "Border and edge" gives the cost). Not re-entrant on
 * one handle. The search for a setting that meets the thresholds: spread_find_edge_setting. */
SPREAD_API spread_status spread_predict_edge(spread_tables* tables, const spread_prediction_def* def,
                                             const spread_edge_def* edge, spread_edge_result* result,
                                             double* rate_percent, size_t rate_capacity);

/* (appended in 0.6) The last pass's setting a search found: the edge-side disc's own, and the other
 * disc's drop point on that pass. Caller-owned. */
typedef struct spread_edge_setting {
  double disc_rpm;                       /* the edge-side disc's speed, r/min */
  double disc_drop_point_turn_rad;       /* the edge-side disc's drop-point turn, rad (as in the def) */
  double flow_fraction;                  /* the edge-side disc's flow, of the field's, [0, 1.2] (0: off) */
  double field_side_drop_point_turn_rad; /* the other disc's drop point on this pass, rad; NaN: the field's */
  int32_t predictions;                   /* predictions the search made */
  int32_t reserved;                      /* 0 */
} spread_edge_setting;

/* (appended in 0.6) The setting of the last pass that meets the edge's thresholds with the least
 * fertiliser missing (border) or misplaced (field edge) — or, when none searched meets them, the closest
 * (result->meets 0): the search of docs/field-calibration.md "Border and edge spreading" over the
 * edge-side disc's speed, drop point and flow and the other disc's drop point. def: the field's setting as
 * for spread_predict_edge, with every disc_rpm and disc_drop_point_turn_rad NaN (the search sets them);
 * edge: as for spread_predict_edge, its flow_fraction 1 (the default: the search sets the flow). *setting receives the setting,
 * *result and `rate` (may be NULL) the profile at it. The errors of spread_predict_edge. Hundreds of
 * predictions (docs/c-api.md "Border and edge" gives the cost): a call for a headland or a section
 * change, not for every control cycle. Allocates through the handle's allocator; not re-entrant on one
 * handle. */
SPREAD_API spread_status spread_find_edge_setting(spread_tables* tables, const spread_prediction_def* def,
                                                  const spread_edge_def* edge, spread_edge_setting* setting,
                                                  spread_edge_result* result, double* rate_percent,
                                                  size_t rate_capacity);

/* (appended in 0.6) spread_find_edge_setting within a budget a control loop can schedule: at most
 * max_predictions predictions (0: no limit; otherwise at least 3: the field's, the normal pass and the
 * answer's profile). *out_finished 1: the budget covered the whole search, whose answer is then
 * spread_find_edge_setting's bit for bit; 0: the settings beyond the budget were not flown, and *setting,
 * *result and `rate` are the best of those that were — never worse by the search's own ranking than the
 * normal setting at its best flow (setting->predictions says how many were made). Each prediction costs
 * about what one of spread_predict_edge's does, so a budget sets the call's time (docs/c-api.md "Border
 * and edge": 10 predictions, under 10 ms). The errors of spread_find_edge_setting, and
 * SPREAD_ERROR_OUT_OF_RANGE for a budget of 1 or 2 or below 0. */
SPREAD_API spread_status spread_find_edge_setting_within(spread_tables* tables, const spread_prediction_def* def,
                                                         const spread_edge_def* edge, int32_t max_predictions,
                                                         spread_edge_setting* setting, spread_edge_result* result,
                                                         double* rate_percent, size_t rate_capacity,
                                                         int32_t* out_finished);

/* ---------------------------------------------------------------------------------------------------
 * Single trajectory (no table needed)
 * ------------------------------------------------------------------------------------------------- */
typedef struct spread_trajectory_def {
  uint32_t struct_size;        /* sizeof(spread_trajectory_def) of the caller's header; set by _default() */
  double diameter_m;           /* granule diameter, m, in [1e-6, 0.1] (default 3 mm) */
  double density_kg_m3;        /* granule density, kg/m³, in [1, 25000] (default 1500) */
  double position_m[3];        /* launch position, m, each within ±1000 and z >= ground_z_m */
  double velocity_m_s[3];      /* launch velocity, m/s, each within ±1000 */
  double spin_rad_s[3];        /* launch angular velocity, rad/s, each within ±1e5 */
  double ground_z_m;           /* ground plane height, m, within ±1000 (default 0); the flight ends there */
  double air_density_kg_m3;    /* kg/m³, in [0, 100] (default 1.225) */
  double air_viscosity_pa_s;   /* dynamic viscosity, Pa·s, in (0, 1] (default 1.81e-5) */
  double wind_m_s[3];          /* m/s, each within ±100; used when SPREAD_EFFECT_WIND is set */
  uint32_t effects;            /* SPREAD_EFFECT_* bits (default: all) */
  uint32_t reserved;           /* fills the trailing padding; 0 from _default(), never read */
} spread_trajectory_def;

static inline spread_trajectory_def spread_trajectory_def_default(void) {
  spread_trajectory_def def;
  int i;
  def.struct_size = (uint32_t)sizeof(spread_trajectory_def);
  def.diameter_m = 3e-3;
  def.density_kg_m3 = 1500.0;
  for (i = 0; i < 3; ++i) {
    def.position_m[i] = 0.0;
    def.velocity_m_s[i] = 0.0;
    def.spin_rad_s[i] = 0.0;
    def.wind_m_s[i] = 0.0;
  }
  def.position_m[2] = 1.0;
  def.ground_z_m = 0.0;
  def.air_density_kg_m3 = 1.225;
  def.air_viscosity_pa_s = 1.81e-5;
  def.effects = SPREAD_EFFECT_ALL;
  def.reserved = 0u;
  return def;
}

typedef struct spread_landing {
  double position_m[3];        /* where the granule crosses the ground plane, m */
  double velocity_m_s[3];      /* its velocity there, m/s */
  double spin_rad_s[3];        /* its angular velocity there, rad/s */
  double flight_time_s;        /* s */
  int32_t steps;               /* accepted integrator steps */
  int32_t reserved;            /* fills the trailing padding; the library writes 0 */
} spread_landing;

/* Flies one granule to the ground (adaptive Dormand–Prince 5(4), the same settings as spread_predict).
 * SPREAD_ERROR_NOT_LANDED when it has not reached the ground after 60 s of flight (e.g. launched
 * upwards in a strong updraught) or after 3072 integrator steps (micrometre dust, whose stiff drag keeps
 * the steps tiny; the cap bounds the call's time, docs/c-api.md "Worst-case time"); *out_landing then
 * holds the last state. Thread-safe; no allocation. */
SPREAD_API spread_status spread_trajectory(const spread_trajectory_def* def, spread_landing* out_landing);

/* ---------------------------------------------------------------------------------------------------
 * Error detail (appended in 0.2)
 * ------------------------------------------------------------------------------------------------- */
/* A sentence on the last call on this thread that returned an error: for spread_open the file, record
 * and field (e.g. "t.sqlite: run urea @ 500.000000 rpm: sample BLOB has 4 bytes, expected sample_count
 * 200 x 48"), for the others the function and what was refused. Thread-local, so it works when
 * spread_open fails without a handle. Never NULL; "" before the first error on the thread. Successful
 * calls leave it unchanged. Valid until the next failing call on this thread; written without
 * allocating (cut at 511 characters). */
SPREAD_API const char* spread_last_error_detail(void);

/* ---------------------------------------------------------------------------------------------------
 * Caller's allocator (appended in 0.2)
 * ------------------------------------------------------------------------------------------------- */
typedef struct spread_allocator {
  /* Returns size bytes aligned to alignment (a power of two, at most 64), or NULL (then the call fails
   * with SPREAD_ERROR_OUT_OF_MEMORY). */
  void* (*alloc)(void* user, size_t size, size_t alignment);
  /* Releases a block from alloc, with the size it was asked for. Never called with NULL. */
  void (*free)(void* user, void* pointer, size_t size);
  void* user; /* passed to both */
} spread_allocator;

/* spread_open, with every block of the handle and of its workspaces (the launch samples, cells, all
 * prediction buffers and the handle itself) taken from *allocator, which is copied. Not from it: SQLite's
 * own memory while the file is read, and the reader's temporary records (freed before this returns),
 * and small strings the handle keeps (names; docs/c-api.md "Memory"). alloc and free may be called from
 * the thread that calls spread_open, spread_close, spread_workspace_create or spread_workspace_free, and
 * from nowhere else. */
SPREAD_API spread_status spread_open_with_allocator(const char* path, const spread_allocator* allocator,
                                                    spread_tables** out_tables);

/* ---------------------------------------------------------------------------------------------------
 * Per-thread workspace (appended in 0.2): share one handle between threads (as zstd's CDict / CCtx)
 * ------------------------------------------------------------------------------------------------- */
typedef struct spread_workspace spread_workspace; /* opaque */

/* A prediction workspace for `tables` (from the handle's allocator): no file access, no copy of the
 * table. Use it only while the handle is open; free it before or after spread_close. May run
 * concurrently with predictions on other workspaces of the same handle. */
SPREAD_API spread_status spread_workspace_create(const spread_tables* tables, spread_workspace** out_workspace);

/* Frees a workspace. NULL is a no-op; a workspace that is not live is left alone (best effort, as
 * spread_close). */
SPREAD_API void spread_workspace_free(spread_workspace* workspace);

/* spread_predict on the workspace's handle using this workspace: the same results, statuses and
 * guarantees (no allocation). One thread at a time per workspace; any number of workspaces of one handle
 * at once. SPREAD_ERROR_BAD_HANDLE when the workspace or its handle is not live. */
SPREAD_API spread_status spread_workspace_predict(spread_workspace* workspace, const spread_prediction_def* def,
                                                  spread_prediction* result, double* transverse_mass_fraction,
                                                  size_t transverse_capacity);

/* ---------------------------------------------------------------------------------------------------
 * Opening with flags, and what the file held (appended in 0.6)
 * ------------------------------------------------------------------------------------------------- */
/* Read a legacy table: one whose runs carry no checked list of them (meta runs_manifest with its
 * checksum, docs/table-format.md "Checksums") — written before 0.6, or with runs deleted together with
 * their list, which no reader can tell apart. Without this flag such a table is refused with
 * SPREAD_ERROR_FILE_WRONG_VERSION, the detail saying so; rerunning lookup_builder on it lists its runs. */
#define SPREAD_OPEN_LEGACY_FILES 0x1u

/* spread_open_with_allocator with SPREAD_OPEN_* flags (other bits: SPREAD_ERROR_OUT_OF_RANGE). allocator
 * NULL: malloc and free, as spread_open. */
SPREAD_API spread_status spread_open_with_flags(const char* path, uint32_t flags, const spread_allocator* allocator,
                                                spread_tables** out_tables);

/* SPREAD_TABLE_* bits of spread_table_flags: what spread_open found in the file. */
#define SPREAD_TABLE_RUNS_UNCHECKED 0x1u       /* a legacy table read with SPREAD_OPEN_LEGACY_FILES: its runs
                                                  were not checked against a list of them */
#define SPREAD_TABLE_LANDING_DATA_DERIVED 0x2u /* the file holds no current landing data for a material, so
                                                  spread_open flew its landing grid itself (tens of times
                                                  slower to open, docs/c-api.md "Landing grid"); rerun
                                                  lookup_builder on the file to store it */
SPREAD_API spread_status spread_table_flags(const spread_tables* tables, uint32_t* out_flags);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* SPREAD_SPREAD_H */
