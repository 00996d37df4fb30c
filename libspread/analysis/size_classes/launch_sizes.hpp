#pragma once
// The sizes of the granules a table launches: the cumulative mass curve of its launch samples' diameters
// (each sample weighs its mass_kg), read as a sieve analysis is (libspread/core/sieve_analysis.hpp): d_p
// the diameter that p % of the mass lies below, the size guide number SGN = d50 (mm) × 100 and the
// uniformity index UI = d5 / d90 × 100. For a material given by a sieve analysis they are the sheet's
// figures to within sampling; for a lognormal one they are the figures a sieve test of its granules gives.
#include <span>

#include "libspread/io/tables/table_format.hpp"

namespace spread::size_classes {

// d_p (mm) of the samples' mass: linear between the sorted diameters' cumulative mass fractions (each
// sample's mass counted at its diameter's midpoint of the curve). NaN without samples.
double launch_passing_size_mm(std::span<const tables::LaunchSample> samples, double percent);

struct LaunchSizes {
  double d50_mm = 0.0;
  double size_guide_number = 0.0;  // d50 × 100
  double uniformity_index = 0.0;   // d5 / d90 × 100
};
LaunchSizes launch_sizes(std::span<const tables::LaunchSample> samples);

}  // namespace spread::size_classes
