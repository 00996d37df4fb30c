#pragma once
// Checked decoding of LCM payloads. lcm-gen 1.3's decoders trust length fields (a negative string or
// array length throws from std::string/std::vector), so every decode goes through here: a payload is
// classified as decoded, of another type (fingerprint), or undecodable — never a crash.
#include <cstdint>
#include <exception>

namespace spread::firmware::lcm_link {

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

template <typename Message>
DecodeOutcome decode_checked(const void* data, std::uint32_t size, Message& out) {
  std::int64_t fingerprint = 0;
  if (!read_fingerprint(data, size, fingerprint)) return DecodeOutcome::kUndecodable;
  if (fingerprint != Message::getHash()) return DecodeOutcome::kWrongFingerprint;
  try {
    const int used = out.decode(data, 0, static_cast<int>(size));
    // Trailing bytes mean the sender's layout differs from ours despite the fingerprint.
    if (used < 0 || static_cast<std::uint32_t>(used) != size) return DecodeOutcome::kUndecodable;
  } catch (const std::exception&) {
    return DecodeOutcome::kUndecodable;
  }
  return DecodeOutcome::kDecoded;
}

}  // namespace spread::firmware::lcm_link
