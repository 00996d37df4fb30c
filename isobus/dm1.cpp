#include "isobus/dm1.hpp"

#include <algorithm>

namespace spread::isobus {

std::vector<std::uint8_t> encode_dm1(const Lamps& lamps, std::span<const Dtc> active) {
  std::vector<std::uint8_t> b;
  b.reserve(2 + 4 * std::max<std::size_t>(active.size(), 1));
  b.push_back(static_cast<std::uint8_t>((lamps.malfunction ? 0x40 : 0) | (lamps.red_stop ? 0x10 : 0) |
                                        (lamps.amber_warning ? 0x04 : 0) | (lamps.protect ? 0x01 : 0)));
  b.push_back(0xFF);
  if (active.empty()) {
    b.insert(b.end(), {0, 0, 0, 0});
    return b;
  }
  for (const Dtc& d : active) {
    b.push_back(static_cast<std::uint8_t>(d.spn & 0xFFu));
    b.push_back(static_cast<std::uint8_t>((d.spn >> 8) & 0xFFu));
    b.push_back(static_cast<std::uint8_t>(((d.spn >> 11) & 0xE0u) | (static_cast<std::uint8_t>(d.fmi) & 0x1Fu)));
    b.push_back(static_cast<std::uint8_t>(std::min<std::uint8_t>(d.occurrences, 126) & 0x7Fu));
  }
  return b;
}

std::optional<Dm1> decode_dm1(std::span<const std::uint8_t> b) {
  if (b.size() < 6 || (b.size() - 2) % 4 != 0) return std::nullopt;
  Dm1 m;
  m.lamps = {(b[0] & 0xC0) == 0x40, (b[0] & 0x30) == 0x10, (b[0] & 0x0C) == 0x04, (b[0] & 0x03) == 0x01};
  for (std::size_t i = 2; i + 4 <= b.size(); i += 4) {
    Dtc d;
    d.spn = b[i] | (std::uint32_t{b[i + 1]} << 8) | (std::uint32_t{static_cast<std::uint8_t>(b[i + 2] & 0xE0u)} << 11);
    d.fmi = static_cast<Fmi>(b[i + 2] & 0x1Fu);
    d.occurrences = static_cast<std::uint8_t>(b[i + 3] & 0x7Fu);
    if (d.spn == 0 && b[i + 2] == 0 && b[i + 3] == 0) continue;  // the "no active fault" DTC
    m.active.push_back(d);
  }
  return m;
}

}  // namespace spread::isobus
