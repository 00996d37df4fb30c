#pragma once
// One `[[materials]]` entry (or one `[[products]]` entry of a product library) read into a Material: the
// schema's quantities (libspread/io/tables/material_schema.hpp) and the size distribution, lognormal or a
// sieve analysis. Ranges are checked later with the scene's effects; what is checked here is what only
// the entry's keys can tell: the sieve lists given together, valid, and not beside a lognormal key.
#include "libspread/io/scene/scene.hpp"
#include "libspread/io/scene/toml_document.hpp"

namespace spread::scene {

// `base`: a product the entry starts from (nullptr: the schema's defaults). The entry's own keys replace
// the base's values; any of its size keys (diameter_mean_m, diameter_sd_m, sieve_mm, sieve_retained_pct)
// replaces the base's sizes as a whole. Does not call s.finish() (the caller may read more keys).
Material read_material_entry(TomlSection& s, const Material* base);

}  // namespace spread::scene
