#pragma once
// Keys of a launch-table row's quantile cells (launch_quantile_cells.hpp): where each sample lands when
// flown at the row's own rpm, from the machine's stored disc height, in still air with drag, Magnus lift
// and spin decay (a fixed set: a flight effect added later does not reorder the rows of a table).
//
// Why the landing point and not a launch quantity: the throw width, R̄ and ξ are statistics of the
// landings, and a landing depends jointly on the launch direction, speed, elevation and granule diameter
// (drag), so no single launch quantity orders granules by where they land. The keys are only an order: a
// request at another height, wind or effect set moves the landings but hardly reorders them. Cost: one
// flight per sample, once, when the table is loaded.
//
// Keys: primary = landing distance from the disc centre (m; the radius of R̄ and ξ, Eqs. 51–52, and what
// rpm changes most), secondary = transverse landing x (m, about the disc centre; the coordinate of the
// trays and the throw width).
#include <span>

#include "libspread/physics/flight/flight.hpp"
#include "libspread/io/tables/table_format.hpp"

namespace spread::predict {

// Writes the keys of every sample of the row (outputs sized samples.size(), else std::invalid_argument).
// A sample that does not land within the settings' limits is keyed by where its flight stopped (by its
// launch point if that is not finite).
void landing_rank_keys(std::span<const tables::LaunchSample> samples, double rpm, double disc_radius_m,
                       double disc_height_m, double density_kg_m3, const flight::Settings& settings,
                       std::span<double> radius_m, std::span<double> transverse_x_m);

}  // namespace spread::predict
