// spread_trajectory: one flight with the prediction's integrator settings. Inputs are checked here so
// that every bad input has its status code (the flight module would throw std::invalid_argument).
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdio>

#include "capi/src/error_detail.hpp"
#include "capi/src/fault_seam.hpp"
#include "capi/src/tables_handle.hpp"
#include "libspread/analysis/predict/flight_defaults.hpp"

namespace {

spread::Vec3 vec(const double (&v)[3]) { return spread::Vec3(v[0], v[1], v[2]); }
void put(const spread::Vec3& v, double (&out)[3]) {
  out[0] = v.x();
  out[1] = v.y();
  out[2] = v.z();
}

// The physical domain of a single flight. Beyond it the inputs are finite but absurd (a launch at
// 3e307 m/s overflowed the position to inf, found by fuzz_capi_trajectory), so they are refused with
// SPREAD_ERROR_OUT_OF_RANGE rather than flown. The bounds are far outside any spreader and documented
// in spread.h and docs/c-api.md.
struct TrajectoryDomain {
  double min_diameter_m = 1e-6, max_diameter_m = 0.1;              // dust to a 10 cm stone
  double min_density_kg_m3 = 1.0, max_density_kg_m3 = 25'000.0;   // above osmium's 22,600
  double max_abs_position_m = 1000.0;    // each launch coordinate and the ground height
  double max_abs_speed_m_s = 1000.0;     // each launch velocity component (about Mach 3)
  double max_abs_spin_rad_s = 1e5;       // each spin component (about 1e6 rpm)
  double max_air_density_kg_m3 = 100.0;
  double max_air_viscosity_pa_s = 1.0;   // water is 1e-3 Pa·s
  double max_abs_wind_m_s = 100.0;       // each component, as predict::PredictorLimits
};

// Each input with its name as the definition spells it and its range; `low_open`: the range excludes
// its lower end.
struct Field {
  const char* name;
  int index;  // the component of an array field, -1 a scalar
  double value, low, high;
  bool low_open;
};

// NaN or infinite inputs first (SPREAD_ERROR_NOT_FINITE, whatever their range), then the domain
// (SPREAD_ERROR_OUT_OF_RANGE), each refusal naming the field, its value and its range.
spread_status check_fields(const spread_trajectory_def& d) {
  using spread::capi::fail;
  constexpr TrajectoryDomain k;
  constexpr const char* kFunction = "spread_trajectory";
  // On the stack: spread_trajectory does not allocate.
  std::array<Field, 17> fields{};
  std::size_t n = 0;
  fields[n++] = {"diameter_m", -1, d.diameter_m, k.min_diameter_m, k.max_diameter_m, false};
  fields[n++] = {"density_kg_m3", -1, d.density_kg_m3, k.min_density_kg_m3, k.max_density_kg_m3, false};
  fields[n++] = {"ground_z_m", -1, d.ground_z_m, -k.max_abs_position_m, k.max_abs_position_m, false};
  fields[n++] = {"air_density_kg_m3", -1, d.air_density_kg_m3, 0.0, k.max_air_density_kg_m3, false};
  fields[n++] = {"air_viscosity_pa_s", -1, d.air_viscosity_pa_s, 0.0, k.max_air_viscosity_pa_s, true};
  for (int i = 0; i < 3; ++i) {
    fields[n++] = {"position_m", i, d.position_m[i], -k.max_abs_position_m, k.max_abs_position_m, false};
    fields[n++] = {"velocity_m_s", i, d.velocity_m_s[i], -k.max_abs_speed_m_s, k.max_abs_speed_m_s, false};
    fields[n++] = {"spin_rad_s", i, d.spin_rad_s[i], -k.max_abs_spin_rad_s, k.max_abs_spin_rad_s, false};
    fields[n++] = {"wind_m_s", i, d.wind_m_s[i], -k.max_abs_wind_m_s, k.max_abs_wind_m_s, false};
  }
  char name[40];
  const auto named = [&](const Field& f) {
    if (f.index < 0) return f.name;
    std::snprintf(name, sizeof name, "%s[%d]", f.name, f.index);
    return static_cast<const char*>(name);
  };
  for (const Field& f : fields) {
    if (!std::isfinite(f.value)) return fail(SPREAD_ERROR_NOT_FINITE, "%s: def->%s is %g", kFunction, named(f), f.value);
  }
  for (const Field& f : fields) {
    const bool above_low = f.low_open ? f.value > f.low : f.value >= f.low;
    if (!above_low || f.value > f.high) {
      return fail(SPREAD_ERROR_OUT_OF_RANGE, "%s: def->%s %g outside %s%g, %g]", kFunction, named(f), f.value,
                  f.low_open ? "(" : "[", f.low, f.high);
    }
  }
  if (d.position_m[2] < d.ground_z_m) {
    return fail(SPREAD_ERROR_OUT_OF_RANGE, "%s: def->position_m[2] %g is below def->ground_z_m %g (launched below the ground)",
                kFunction, d.position_m[2], d.ground_z_m);
  }
  return SPREAD_OK;
}

}  // namespace

extern "C" spread_status spread_trajectory(const spread_trajectory_def* def, spread_landing* out_landing) {
  using spread::capi::fail;
  if (def == nullptr) return fail(SPREAD_ERROR_NULL_POINTER, "spread_trajectory: def is NULL");
  if (out_landing == nullptr) return fail(SPREAD_ERROR_NULL_POINTER, "spread_trajectory: out_landing is NULL");
  if (def->struct_size < spread::capi::kTrajectoryDefV1Size) {
    return fail(SPREAD_ERROR_OUT_OF_RANGE, "spread_trajectory: def->struct_size %u is smaller than the first published %zu",
                static_cast<unsigned>(def->struct_size), spread::capi::kTrajectoryDefV1Size);
  }
  if (const spread_status s = check_fields(*def); s != SPREAD_OK) return s;
  if ((def->effects & ~uint32_t{SPREAD_EFFECT_ALL}) != 0) {
    return fail(SPREAD_ERROR_UNKNOWN_EFFECT, "spread_trajectory: effects 0x%x has bits outside SPREAD_EFFECT_ALL",
                static_cast<unsigned>(def->effects));
  }
  try {
    spread::capi::detail::fault_point();
    spread::flight::Granule granule;
    granule.diameter_m = def->diameter_m;
    granule.density_kg_m3 = def->density_kg_m3;
    spread::flight::State launch;
    launch.position_m = vec(def->position_m);
    launch.velocity_m_s = vec(def->velocity_m_s);
    launch.spin_rad_s = vec(def->spin_rad_s);
    spread::flight::Air air;
    air.density_kg_m3 = def->air_density_kg_m3;
    air.viscosity_pa_s = def->air_viscosity_pa_s;
    air.wind_m_s = vec(def->wind_m_s);
    // The step cap of the default settings bounds the worst case (docs/c-api.md "Worst-case time").
    const spread::flight::Settings settings = spread::predict::default_flight_settings();
    const auto landing = spread::flight::fly_to_ground(granule, launch, def->ground_z_m, air, def->effects, settings);
    put(landing.state.position_m, out_landing->position_m);
    put(landing.state.velocity_m_s, out_landing->velocity_m_s);
    put(landing.state.spin_rad_s, out_landing->spin_rad_s);
    out_landing->flight_time_s = landing.flight_time_s;
    out_landing->steps = landing.steps;
    // Only a caller whose header has the reserved fields is sure to have room for this one.
    if (def->struct_size >= spread::capi::kTrajectoryDefReservedSize) out_landing->reserved = 0;
    if (landing.landed) return SPREAD_OK;
    return fail(SPREAD_ERROR_NOT_LANDED, "spread_trajectory: not on the ground after %g s of flight and %d steps (limits %g s, %d steps)",
                landing.flight_time_s, landing.steps, settings.max_time_s, settings.max_steps);
  } catch (const std::bad_alloc&) {
    return fail(SPREAD_ERROR_OUT_OF_MEMORY, "spread_trajectory: out of memory");
  } catch (const std::exception& e) {
    return fail(SPREAD_ERROR_INTERNAL, "spread_trajectory: %.400s", e.what());
  } catch (...) {
    return fail(SPREAD_ERROR_INTERNAL, "spread_trajectory: unknown exception");
  }
}
