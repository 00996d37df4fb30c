#pragma once
// How well one table row pins down the answer a user acts on: the 95 % interval of the working width
// predicted from that row's launches alone, as the C API would predict it at the row's rpm (to-and-fro,
// CV target 15 %, 0.5 m trays, the machine's stored height, still air, the row's own flight effects).
// A DEM run goes on until this is within the scene's sweep.working_width_ci_m (docs/building-tables.md).
// The width is the first band's upper end (docs/metrics.md "Effective working width"): a smooth statistic
// of the launches, where the headline switches to a wider band once the launches establish it — a run
// that waited for the headline's interval would chase that switch.
#include "libspread/io/tables/table_format.hpp"

namespace spread::lookup {

// Half-width (m) of the 95 % interval, 1.96 standard errors (docs/metrics.md "Uncertainty"). NaN when no
// bout width meets the target (no working width, hence no interval). Throws as predict::Predictor does
// for a row it refuses.
double row_working_width_ci_m(const tables::Machine& machine, const tables::Material& material, const tables::Run& run);

}  // namespace spread::lookup
