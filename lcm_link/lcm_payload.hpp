#pragma once
// Checked decoding of LCM payloads. lcm-gen 1.3's decoders trust length fields: a string length of
// INT32_MIN overflows (`len - 1`) and a negative or zero length becomes a huge std::string::assign (a
// segmentation fault, not an exception); a negative array count asks std::vector for a huge size. So every
// decode goes through here: the payload's length fields are first checked against the message's fixed
// layout (`payload_layout_valid`), and only a payload whose every length is sane and whose encoded size is
// exactly the payload size reaches the generated decoder. A payload is classified as decoded, of another
// type (fingerprint), or undecodable — never a crash.
#include <cstddef>
#include <cstdint>
#include <exception>
#include <span>

namespace spread {
class command_t;
class status_t;
class heartbeat_t;
}  // namespace spread

namespace spread::lcm_link {

enum class DecodeOutcome { kDecoded, kWrongFingerprint, kUndecodable };

// The first 8 bytes of an LCM payload: the type fingerprint, big endian.
inline bool read_fingerprint(const void* data, std::uint32_t size, std::int64_t& fingerprint) {
  if (data == nullptr || size < 8) return false;
  const auto* bytes = static_cast<const std::uint8_t*>(data);
  std::uint64_t value = 0;
  for (int i = 0; i < 8; ++i) value = (value << 8) | bytes[i];
  fingerprint = static_cast<std::int64_t>(value);
  return true;
}

// One field of an LCM message in .lcm order, as LCM encodes it (big endian, no padding):
//   kFixed   a scalar of `bytes` bytes (int8/boolean 1, int32 4, int64/double 8);
//   kString  int32 length including the terminating NUL (so >= 1), then that many bytes;
//   kCount   a signed integer of `bytes` bytes sizing the next kArray (must be >= 0);
//   kArray   (count of the last kCount) elements of `bytes` bytes each.
struct LcmField {
  enum Kind : std::uint8_t { kFixed, kString, kCount, kArray };
  Kind kind;
  std::uint8_t bytes;
};

// The layout of each message, after the 8-byte fingerprint. Must follow the .lcm files; tests/firmware
// (test_lcm.cpp, LayoutMatchesTheGeneratedEncoder) checks each against lcm-gen's encoder. A message
// without a layout here cannot be decoded through decode_checked (the primary template is undefined).
template <typename Message>
struct LcmLayout;

template <>
struct LcmLayout<spread::command_t> {  // command_t.lcm
  static constexpr LcmField fields[] = {
      {LcmField::kFixed, 8},  {LcmField::kFixed, 8},  {LcmField::kFixed, 1},  // timestamp_us, sequence, mode
      {LcmField::kFixed, 8},  {LcmField::kFixed, 8},  {LcmField::kFixed, 8},  // rate, width, ground speed
      {LcmField::kString, 0},                                                 // material
      {LcmField::kFixed, 8},  {LcmField::kFixed, 1},                          // rpm_setpoint, work_state
      {LcmField::kCount, 1},  {LcmField::kArray, 1},                          // num_sections, section_on
      {LcmField::kFixed, 1},  {LcmField::kFixed, 8},                          // border_mode, border_gap_m
      {LcmField::kFixed, 1},  {LcmField::kFixed, 8},  {LcmField::kFixed, 8},  // wind_compensation, wind_m_s[2]
  };
};

template <>
struct LcmLayout<spread::status_t> {  // status_t.lcm
  static constexpr LcmField fields[] = {
      {LcmField::kFixed, 8}, {LcmField::kFixed, 8}, {LcmField::kFixed, 8},  // timestamp_us, step, last seq.
      {LcmField::kFixed, 1},                                                // mode
      {LcmField::kString, 0},                                               // material
      {LcmField::kFixed, 8}, {LcmField::kFixed, 8}, {LcmField::kFixed, 8},  // rpm actual/target, rate set
      {LcmField::kFixed, 8}, {LcmField::kFixed, 8}, {LcmField::kFixed, 8},  // rate actual, width set/actual
      {LcmField::kFixed, 8}, {LcmField::kFixed, 8}, {LcmField::kFixed, 8},  // speed, mass flow, throw width
      {LcmField::kFixed, 8}, {LcmField::kFixed, 8},                         // effective width, cv
      {LcmField::kFixed, 8}, {LcmField::kFixed, 8}, {LcmField::kFixed, 8},  // their standard errors
      {LcmField::kFixed, 1}, {LcmField::kFixed, 1}, {LcmField::kFixed, 1},  // width_reachable, work states
      {LcmField::kCount, 1}, {LcmField::kArray, 1},                         // num_sections, section_on
      {LcmField::kArray, 1},                                                // section_actual_on
      {LcmField::kFixed, 8}, {LcmField::kFixed, 8},                         // disc_rpm_actual[2]
      {LcmField::kFixed, 8}, {LcmField::kFixed, 8},                         // disc_rpm_target[2]
      {LcmField::kFixed, 8}, {LcmField::kFixed, 8},                         // disc_drop_point_turn_rad[2]
      {LcmField::kFixed, 8}, {LcmField::kFixed, 8},                         // disc_flow_fraction[2]
      {LcmField::kFixed, 1},                                                // sides_pending
      {LcmField::kFixed, 1}, {LcmField::kFixed, 1}, {LcmField::kFixed, 1},  // border_mode, applied, wind
      {LcmField::kFixed, 4},                                                // fault_codes
      {LcmField::kFixed, 8}, {LcmField::kFixed, 8}, {LcmField::kFixed, 8},  // rejected_*
      {LcmField::kFixed, 8}, {LcmField::kFixed, 8}, {LcmField::kFixed, 8},  // rejected_stale, can_*
      {LcmField::kCount, 1}, {LcmField::kArray, 8},                         // num_fault_counts, fault_counts
  };
};

template <>
struct LcmLayout<spread::heartbeat_t> {  // heartbeat_t.lcm
  static constexpr LcmField fields[] = {
      {LcmField::kFixed, 8}, {LcmField::kFixed, 8},  // timestamp_us, sequence
      {LcmField::kString, 0},                        // node
      {LcmField::kFixed, 4},                         // loop_rate_mhz
      {LcmField::kFixed, 8}, {LcmField::kFixed, 8},  // loop_ticks, loop_overruns
      {LcmField::kFixed, 4},                         // fault_codes
  };
};

// Walks `layout` over the payload (fingerprint included): true when every string length is in
// [1, remaining bytes], every array count is >= 0 and fits, and the fields end exactly at `size`.
inline bool payload_layout_valid(std::span<const LcmField> layout, const void* data, std::uint32_t size) {
  if (data == nullptr || size < 8) return false;
  const auto* bytes = static_cast<const std::uint8_t*>(data);
  std::uint64_t pos = 8;  // 64-bit: no sum below can wrap
  std::uint64_t count = 0;
  const auto read_signed = [&](unsigned width) {  // big endian, sign-extended from `width` bytes
    std::uint64_t value = 0;
    for (unsigned i = 0; i < width; ++i) value = (value << 8) | bytes[pos + i];
    if (width >= 8) return static_cast<std::int64_t>(value);
    const std::uint64_t sign = std::uint64_t{1} << (8 * width - 1);
    return static_cast<std::int64_t>(value ^ sign) - static_cast<std::int64_t>(sign);
  };
  for (const LcmField& field : layout) {
    switch (field.kind) {
      case LcmField::kFixed:
        pos += field.bytes;
        break;
      case LcmField::kString: {
        if (pos + 4 > size) return false;
        const std::int64_t length = read_signed(4);
        pos += 4;
        if (length < 1 || static_cast<std::uint64_t>(length) > size - pos) return false;
        pos += static_cast<std::uint64_t>(length);
        break;
      }
      case LcmField::kCount: {
        if (pos + field.bytes > size) return false;
        const std::int64_t value = read_signed(field.bytes);
        if (value < 0) return false;
        count = static_cast<std::uint64_t>(value);
        pos += field.bytes;
        break;
      }
      case LcmField::kArray:
        if (field.bytes != 0 && count > (size - pos) / field.bytes) return false;
        pos += count * field.bytes;
        break;
    }
    if (pos > size) return false;
  }
  // Trailing bytes mean the sender's layout differs from ours despite the fingerprint.
  return pos == size;
}

template <typename Message>
bool payload_layout_valid(const void* data, std::uint32_t size) {
  return payload_layout_valid(std::span<const LcmField>(LcmLayout<Message>::fields), data, size);
}

template <typename Message>
DecodeOutcome decode_checked(const void* data, std::uint32_t size, Message& out) {
  std::int64_t fingerprint = 0;
  if (!read_fingerprint(data, size, fingerprint)) return DecodeOutcome::kUndecodable;
  if (fingerprint != Message::getHash()) return DecodeOutcome::kWrongFingerprint;
  // Lengths first: lcm-gen's decoder must never see a length it would overflow or over-allocate on.
  if (!payload_layout_valid<Message>(data, size)) return DecodeOutcome::kUndecodable;
  try {
    const int used = out.decode(data, 0, static_cast<int>(size));
    if (used < 0 || static_cast<std::uint32_t>(used) != size) return DecodeOutcome::kUndecodable;
  } catch (const std::exception&) {
    return DecodeOutcome::kUndecodable;
  }
  return DecodeOutcome::kDecoded;
}

}  // namespace spread::lcm_link
