#include "libspread/io/scene/material_entry.hpp"

#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "libspread/core/sieve_analysis.hpp"
#include "libspread/io/tables/material_schema.hpp"

namespace spread::scene {
namespace {

constexpr std::array<const char*, 4> kSizeKeys{"diameter_mean_m", "diameter_sd_m", "sieve_mm", "sieve_retained_pct"};

bool is_size_quantity(const tables::MaterialQuantity& q) {
  return q.member == &Material::diameter_mean_m || q.member == &Material::diameter_sd_m;
}

// A sieve analysis instead of the lognormal: both lists or neither, never with the lognormal's keys (a
// value that would not act is refused, not dropped); the row's diameter_mean_m and diameter_sd_m become
// the analysis's number mean and sd, so every reader of the row sees the sizes the feed releases.
void read_sieve(TomlSection& s, Material& m) {
  for (const tables::MaterialList& list : tables::kMaterialSieveLists) {
    if (std::optional<std::vector<double>> v = s.numbers(std::string(list.name))) m.sieve.*list.member = std::move(*v);
  }
  const bool sizes = s.present("sieve_mm"), fractions = s.present("sieve_retained_pct");
  if (!sizes && !fractions) return;
  if (!sizes) s.fail("sieve_mm", "missing: sieve_retained_pct needs the sieve sizes it is retained between");
  if (!fractions) s.fail("sieve_retained_pct", "missing: sieve_mm needs the mass % retained between its sieves");
  for (const char* key : {"diameter_mean_m", "diameter_sd_m"}) {
    if (s.present(key)) {
      s.fail(key, "is a lognormal size, but this material gives its sizes as a sieve analysis (sieve_mm, "
                  "sieve_retained_pct): remove one of the two");
    }
  }
  const std::string problem = sieve_problem(m.sieve);
  if (!problem.empty()) {
    const std::size_t colon = problem.find(": ");
    s.fail(problem.substr(0, colon), problem.substr(colon + 2));
  }
  const SieveNumberDistribution number(m.sieve);
  m.diameter_mean_m = number.mean_m();
  m.diameter_sd_m = number.sd_m();
}

}  // namespace

Material read_material_entry(TomlSection& s, const Material* base) {
  Material m = base != nullptr ? *base : Material{};
  m.name = s.string("name").value_or(base != nullptr ? base->name : "");
  bool own_sizes = base == nullptr;
  for (const char* key : kSizeKeys) own_sizes = own_sizes || s.present(key);
  for (const tables::MaterialQuantity& q : tables::kMaterialQuantities) {
    // A required quantity left out reads as 0, which its bounds (> 0) then refuse naming the key.
    const double schema_default = std::isnan(q.scene_default) ? 0.0 : q.scene_default;
    const bool from_base = base != nullptr && !(own_sizes && is_size_quantity(q));
    m.*q.member = s.number(std::string(q.name)).value_or(from_base ? base->*q.member : schema_default);
  }
  if (own_sizes) {
    m.sieve = {};
    read_sieve(s, m);
  }
  return m;
}

}  // namespace spread::scene
