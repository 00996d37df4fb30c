#pragma once
// A section pattern typed by a person ("11110000": section 1 first, 1 on, 0 off) as the value of the
// set-point condensed work state DDI 290 (ISO 11783-11): 2 bits per section, section 1 in bits 0-1,
// 00 off, 01 on, 11 "not installed / leave unchanged" for the sections the pattern does not name.
#include <cstdint>
#include <optional>
#include <string_view>

namespace spread::tractor {

inline std::optional<std::int32_t> condensed_work_state_from_pattern(std::string_view pattern) {
  if (pattern.empty() || pattern.size() > 16) return std::nullopt;
  std::uint32_t value = 0xFFFFFFFFu;
  for (std::size_t i = 0; i < pattern.size(); ++i) {
    std::uint32_t bits = 0;
    if (pattern[i] == '1') {
      bits = 1;
    } else if (pattern[i] != '0') {
      return std::nullopt;
    }
    value = (value & ~(3u << (2 * i))) | (bits << (2 * i));
  }
  return static_cast<std::int32_t>(value);
}

}  // namespace spread::tractor
