#include "libspread/io/tables/row_checksum.hpp"

#include <array>
#include <bit>
#include <cstring>

#include "libspread/io/tables/material_schema.hpp"

namespace spread::tables {
namespace {

constexpr std::uint64_t kReflectedPoly = 0xC96C5795D7870F42ull;

constexpr std::array<std::uint64_t, 256> make_table() {
  std::array<std::uint64_t, 256> table{};
  for (std::uint64_t i = 0; i < 256; ++i) {
    std::uint64_t crc = i;
    for (int bit = 0; bit < 8; ++bit) crc = (crc & 1u) != 0 ? (crc >> 1) ^ kReflectedPoly : crc >> 1;
    table[i] = crc;
  }
  return table;
}
constexpr std::array<std::uint64_t, 256> kTable = make_table();

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
  for (std::size_t i = 0; i < size; ++i) crc = kTable[(crc ^ p[i]) & 0xFFu] ^ (crc >> 8);
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

std::string stored_stats_json(const Run& run) { return run.stats_json.empty() ? "{}" : run.stats_json; }
std::string stored_convergence_json(const Run& run) {
  return run.convergence_json.empty() ? "[]" : run.convergence_json;
}

std::string machine_checksum(const Machine& m) {
  Crc64 crc;
  crc.text(m.name);
  crc.real(m.disc_radius_m);
  crc.real(m.disc_height_m);
  crc.real(m.disc_spacing_m);
  crc.integer(m.disc_count);
  crc.integer(m.vane_count);
  crc.real(m.cone_angle_rad);
  crc.integer(m.rotation_sense);
  return crc.hex();
}

std::string material_checksum(const Material& m) {
  Crc64 crc;
  crc.text(m.name);
  for (const MaterialQuantity& q : kMaterialQuantities) crc.real(m.*q.member);
  return crc.hex();
}

std::string run_checksum(const Run& run, std::span<const std::uint8_t> samples_blob, std::string_view record_layout,
                         std::int64_t record_bytes) {
  Crc64 crc;
  crc.text(run.material);
  crc.real(run.rpm);
  crc.text(run.source);
  crc.integer(static_cast<std::int64_t>(run.samples.size()));
  crc.text(record_layout);
  crc.integer(record_bytes);
  crc.blob(samples_blob);
  crc.text(run.scene_hash);
  crc.text(run.inputs_hash);
  crc.text(run.scene_text);
  crc.text(run.effects);
  crc.real(run.dt_contact_s);
  crc.real(run.dt_flight_s);
  crc.integer(run.particle_count);
  crc.text(run.software_version);
  crc.text(run.created_utc);
  crc.text(stored_stats_json(run));
  crc.text(stored_convergence_json(run));
  return crc.hex();
}

}  // namespace spread::tables
