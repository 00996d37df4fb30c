#pragma once
// The bytes of one material's landing data in a table file (tables::LandingData, docs/table-format.md
// "landing_data"): what the Predictor derives from the material's rows at construction — its landing
// grid (landing_grid.hpp) and the quantile cells of its rows (launch_quantile_cells.hpp) — so that
// opening a table reads them instead of flying them. Layout, every number little-endian:
//   u32 has_grid; if 1: u32 effects (flight effect bits), per axis (LandingGrid::Axis order) f64 first,
//     f64 step, u32 count; then the grid's values as f32 (LandingGrid::values());
//   u32 celled_rows; per row interpolated by quantile cells, in rpm order: u32 sample_count,
//     u32 cell_count, sample_count × u8 cell of each sample, cell_count × 48-byte cell means in the
//     launch-sample record layout (tables::kSampleLayout).
// The model tag (landing_data_model) names what else the bytes depend on: this layout's version, the
// grid's nodes and domain, and the flight settings of the grid and of the cells' landing keys. A table
// whose tag differs from the reader's is derived afresh, as one without landing data.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "libspread/analysis/predict/landing_grid.hpp"
#include "libspread/physics/flight/flight.hpp"

namespace spread::predict {

// Bump when the layout above, the grid's flights or the cells' assignment change.
inline constexpr int kLandingDataVersion = 1;

std::string landing_data_model(const LandingDomain& domain, const flight::Settings& grid_settings,
                               const flight::Settings& key_settings);

class LandingDataWriter {
 public:
  void u32(std::uint32_t value);
  void f64(double value);
  void f32s(std::span<const float> values);
  void bytes(std::span<const std::uint8_t> values);
  std::vector<std::uint8_t> take() { return std::move(bytes_); }

 private:
  std::vector<std::uint8_t> bytes_;
};

// Reads what LandingDataWriter wrote; every read returns false past the end (the caller reports the
// data as damaged).
class LandingDataReader {
 public:
  explicit LandingDataReader(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}
  bool u32(std::uint32_t& value);
  bool f64(double& value);
  bool f32s(std::span<float> values);
  // The next `count` bytes as a view (false past the end).
  bool bytes(std::size_t count, std::span<const std::uint8_t>& values);
  bool at_end() const { return offset_ == bytes_.size(); }

 private:
  std::span<const std::uint8_t> bytes_;
  std::size_t offset_ = 0;
};

}  // namespace spread::predict
