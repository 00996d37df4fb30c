#pragma once
// One row per material quantity. The name is the scene key (`[[materials]]`), the table column, the
// struct member, the `inspect` JSON key and the docs' row — one name everywhere. The scene reader takes
// default, range and effect from here; the table writer, reader and checksum take the column list and
// its order; `inspect` and docs/scene-format.md list the rows (tests/scene/test_parameter_schema.cpp
// checks the doc's rows and the table's CREATE statement against them).
#include <array>
#include <limits>
#include <string_view>
#include <vector>

#include "libspread/core/effect_registry.hpp"
#include "libspread/io/tables/table_format.hpp"

namespace spread::tables {

// A closed or open interval bound; ±infinity when unbounded.
struct Bounds {
  double low;
  bool low_open;
  double high;
  bool high_open;
};

struct MaterialQuantity {
  std::string_view name;
  double Material::* member;
  std::string_view unit;        // "–" when dimensionless
  double scene_default;         // NaN: required in a scene
  Bounds scene_bounds;          // what a simulation accepts (DEM practice; the analytic model's domain)
  Bounds table_bounds;          // what a table file may hold (PlausibleLimits): calibrated values included
  effect::EffectSet effect;     // the quantity acts only with this effect on (0: always); a scene that
                                // sets it away from its default with the effect off is refused
  std::string_view meaning;
};

namespace material_schema_detail {
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
using L = PlausibleLimits;
}  // namespace material_schema_detail

// In the table's column order, which is also the order of the checksum's values (docs/table-format.md).
inline constexpr std::array<MaterialQuantity, 9> kMaterialQuantities{{
    {"density_kg_m3", &Material::density_kg_m3, "kg/m³", material_schema_detail::kNaN,
     {0.0, true, material_schema_detail::L::kMaxDensity_kg_m3, false},
     {0.0, true, material_schema_detail::L::kMaxDensity_kg_m3, false}, 0, "particle density"},
    {"diameter_mean_m", &Material::diameter_mean_m, "m", 3.2e-3,
     {0.0, true, material_schema_detail::L::kMaxDiameter_m, false},
     {0.0, true, material_schema_detail::L::kMaxDiameter_m, false}, 0, "lognormal feed: mean diameter"},
    {"diameter_sd_m", &Material::diameter_sd_m, "m", 0.6e-3, {0.0, false, material_schema_detail::L::kMaxDiameter_m, false},
     {0.0, false, material_schema_detail::L::kMaxDiameter_m, false}, 0, "lognormal feed: diameter standard deviation"},
    {"friction_wall", &Material::friction_wall, "–", 0.4, {0.0, false, material_schema_detail::L::kMaxFriction, false},
     {0.0, false, material_schema_detail::L::kMaxFriction, false}, 0,
     "particle–disc/vane sliding friction (the analytic model's μ)"},
    {"friction_particle", &Material::friction_particle, "–", 0.4,
     {0.0, false, material_schema_detail::L::kMaxFriction, false},
     {0.0, false, material_schema_detail::L::kMaxFriction, false}, 0, "particle–particle sliding friction"},
    {"restitution", &Material::restitution, "–", 0.5, {0.01, false, 1.0, false}, {0.0, false, 1.0, false}, 0,
     "coefficient of restitution (normal)"},
    {"youngs_modulus_pa", &Material::youngs_modulus_pa, "Pa", 5e7,
     {0.0, true, material_schema_detail::L::kMaxYoungsModulus_pa, false},
     {0.0, false, material_schema_detail::L::kMaxYoungsModulus_pa, false}, 0,
     "Young's modulus (DEM practice: softer than the real granule for a usable Δt)"},
    {"poisson_ratio", &Material::poisson_ratio, "–", 0.25, {0.0, false, 0.499, false}, {-1.0, true, 0.5, false}, 0,
     "Poisson's ratio"},
    {"rolling_friction", &Material::rolling_friction, "–", 0.0,
     {0.0, false, material_schema_detail::L::kMaxFriction, false},
     {0.0, false, material_schema_detail::L::kMaxFriction, false}, effect::kRolling,
     "rolling resistance coefficient μ_r"},
}};

// The size distribution as a spec sheet gives it (SieveAnalysis, libspread/core/sieve_analysis.hpp): two
// lists of a `[[materials]]` entry, given together and instead of the lognormal's diameter_mean_m and
// diameter_sd_m. Not table columns: a sieve material's row holds the analysis's number mean and sd.
struct MaterialList {
  std::string_view name;
  std::vector<double> SieveAnalysis::* member;
  std::string_view unit;
  std::string_view meaning;
};
inline constexpr std::array<MaterialList, 2> kMaterialSieveLists{{
    {"sieve_mm", &SieveAnalysis::sieve_mm, "mm",
     "sieve feed: N + 1 sieve apertures, strictly increasing; the first is the product's bottom, the last its top"},
    {"sieve_retained_pct", &SieveAnalysis::retained_pct, "%",
     "sieve feed: N mass fractions, the mass % between consecutive sieves; each >= 0, sum 100 (± 0.5)"},
}};

}  // namespace spread::tables
