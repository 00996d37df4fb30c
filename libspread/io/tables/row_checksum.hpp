#pragma once
// Checksums of the rows of a launch-table file (docs/table-format.md, "Checksums"). SQLite's own page
// checks (PRAGMA quick_check) see a damaged b-tree, not a changed value: a flipped bit inside a sample
// BLOB or a REAL column leaves a valid page. Each machine, material and run row therefore stores the
// CRC-64/XZ (ECMA-182 polynomial, reflected, as in xz) of its values in a canonical byte form, written
// by TableWriter and verified by the reader before anything is used.
//
// Canonical form, in column order: a REAL as its IEEE-754 binary64 bits, an INTEGER as int64, both
// little-endian; TEXT and BLOB as their byte length (uint64, little-endian) followed by the bytes.
// Stored as 16 lowercase hex digits.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "libspread/io/tables/landing_data.hpp"
#include "libspread/io/tables/table_format.hpp"

namespace spread::tables {

// CRC-64/XZ: width 64, poly 0x42F0E1EBA9EA3693 (reflected 0xC96C5795D7870F42), init and xorout all ones.
// Check value of "123456789": 0x995DC9BBDF1939FA.
class Crc64 {
 public:
  void bytes(std::span<const std::uint8_t> data);
  void real(double value);
  void integer(std::int64_t value);
  void text(std::string_view value);
  void blob(std::span<const std::uint8_t> value);
  std::uint64_t value() const { return ~state_; }
  std::string hex() const;

 private:
  void raw(const void* data, std::size_t size);
  std::uint64_t state_ = ~std::uint64_t{0};
};


std::string machine_checksum(const Machine& machine);
std::string material_checksum(const Material& material);
// `samples_blob` is the stored BLOB (encode_samples of the run's samples, sample_count of them, whether
// they are in run.samples or pooled); `record_layout` and `record_bytes` the stored layout columns.
std::string run_checksum(const Run& run, std::int64_t sample_count, std::span<const std::uint8_t> samples_blob,
                         std::string_view record_layout, std::int64_t record_bytes);
std::string landing_data_checksum(const LandingData& landing);

}  // namespace spread::tables
