#include "libspread/io/tables/row_checksum.hpp"

#include <array>
#include <bit>
#include <cstring>

#include "libspread/io/tables/machine_schema.hpp"
#include "libspread/io/tables/material_schema.hpp"
#include "libspread/io/tables/run_schema.hpp"

namespace spread::tables {
namespace {

constexpr std::uint64_t kReflectedPoly = 0xC96C5795D7870F42ull;

// Slicing by 8 (Kounavis and Berry, "A systematic approach to building high performance software-based
// CRC generators", 2005): kTables[k][b] is the CRC state after byte b followed by k zero bytes, so eight
// input bytes fold into the state with eight independent lookups instead of a chain of eight.
using Tables = std::array<std::array<std::uint64_t, 256>, 8>;
constexpr Tables make_tables() {
  Tables tables{};
  for (std::uint64_t i = 0; i < 256; ++i) {
    std::uint64_t crc = i;
    for (int bit = 0; bit < 8; ++bit) crc = (crc & 1u) != 0 ? (crc >> 1) ^ kReflectedPoly : crc >> 1;
    tables[0][i] = crc;
  }
  for (std::size_t k = 1; k < 8; ++k) {
    for (std::size_t i = 0; i < 256; ++i) {
      const std::uint64_t previous = tables[k - 1][i];
      tables[k][i] = (previous >> 8) ^ tables[0][previous & 0xFFu];
    }
  }
  return tables;
}
constexpr Tables kTables = make_tables();

// Little-endian bytes of a 64-bit word, whatever the host order.
std::array<std::uint8_t, 8> little_endian(std::uint64_t word) {
  std::array<std::uint8_t, 8> out{};
  for (int i = 0; i < 8; ++i) out[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(word >> (8 * i));
  return out;
}

}  // namespace

void Crc64::raw(const void* data, std::size_t size) {
  const auto* p = static_cast<const std::uint8_t*>(data);
  std::uint64_t crc = state_;
  for (; size >= 8; size -= 8, p += 8) {
    std::uint64_t word = 0;
    if constexpr (std::endian::native == std::endian::little) {
      std::memcpy(&word, p, 8);  // one load
    } else {
      for (int i = 0; i < 8; ++i) word |= static_cast<std::uint64_t>(p[i]) << (8 * i);
    }
    crc ^= word;
    crc = kTables[7][crc & 0xFFu] ^ kTables[6][(crc >> 8) & 0xFFu] ^ kTables[5][(crc >> 16) & 0xFFu] ^
          kTables[4][(crc >> 24) & 0xFFu] ^ kTables[3][(crc >> 32) & 0xFFu] ^ kTables[2][(crc >> 40) & 0xFFu] ^
          kTables[1][(crc >> 48) & 0xFFu] ^ kTables[0][crc >> 56];
  }
  for (; size > 0; --size, ++p) crc = kTables[0][(crc ^ *p) & 0xFFu] ^ (crc >> 8);
  state_ = crc;
}

void Crc64::bytes(std::span<const std::uint8_t> data) { raw(data.data(), data.size()); }

void Crc64::real(double value) {
  const auto le = little_endian(std::bit_cast<std::uint64_t>(value));
  raw(le.data(), le.size());
}

void Crc64::integer(std::int64_t value) {
  const auto le = little_endian(static_cast<std::uint64_t>(value));
  raw(le.data(), le.size());
}

void Crc64::text(std::string_view value) {
  integer(static_cast<std::int64_t>(value.size()));
  raw(value.data(), value.size());
}

void Crc64::blob(std::span<const std::uint8_t> value) {
  integer(static_cast<std::int64_t>(value.size()));
  raw(value.data(), value.size());
}

std::string Crc64::hex() const {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string out(16, '0');
  const std::uint64_t v = value();
  for (int i = 0; i < 16; ++i) out[static_cast<std::size_t>(15 - i)] = kDigits[(v >> (4 * i)) & 0xFu];
  return out;
}

std::string machine_checksum(const Machine& m) {
  Crc64 crc;
  for (const MachineColumn& c : kMachineColumns) {
    switch (c.kind) {
      case MachineColumn::Kind::kText: crc.text(m.*c.text); break;
      case MachineColumn::Kind::kReal: crc.real(m.*c.real); break;
      case MachineColumn::Kind::kInteger: crc.integer(m.*c.integer); break;
    }
  }
  return crc.hex();
}

std::string material_checksum(const Material& m) {
  Crc64 crc;
  crc.text(m.name);
  for (const MaterialQuantity& q : kMaterialQuantities) crc.real(m.*q.member);
  return crc.hex();
}

std::string run_checksum(const Run& run, std::int64_t sample_count, std::span<const std::uint8_t> samples_blob,
                         std::string_view record_layout, std::int64_t record_bytes) {
  Crc64 crc;
  for (const RunColumn& column : kRunColumns) {
    switch (column.kind) {
      case RunColumn::Kind::kText: crc.text(column.stored_text(run)); break;
      case RunColumn::Kind::kReal: crc.real(run.*column.real); break;
      case RunColumn::Kind::kInteger: crc.integer(run.*column.integer); break;
      case RunColumn::Kind::kSampleCount: crc.integer(sample_count); break;
      case RunColumn::Kind::kRecordLayout: crc.text(record_layout); break;
      case RunColumn::Kind::kRecordBytes: crc.integer(record_bytes); break;
      case RunColumn::Kind::kSamples: crc.blob(samples_blob); break;
    }
  }
  return crc.hex();
}

std::string landing_data_checksum(const LandingData& landing) {
  Crc64 crc;
  crc.text(landing.material);
  crc.text(landing.model);
  crc.text(landing.source_key);
  crc.blob(landing.data);
  return crc.hex();
}

}  // namespace spread::tables
