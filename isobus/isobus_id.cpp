#include "isobus/isobus_id.hpp"

namespace spread::isobus {

bool is_pdu1(std::uint32_t pgn) { return ((pgn >> 8) & 0xFFu) < 240u; }

std::uint32_t encode_id(const IsobusId& id) {
  std::uint32_t pgn = id.pgn & 0x3FFFFu;
  if (is_pdu1(pgn)) pgn = (pgn & 0x3FF00u) | id.destination;
  return (std::uint32_t{id.priority & 7u} << 26) | (pgn << 8) | id.source;
}

IsobusId decode_id(std::uint32_t id29) {
  IsobusId id;
  id.priority = static_cast<std::uint8_t>((id29 >> 26) & 7u);
  id.source = static_cast<std::uint8_t>(id29 & 0xFFu);
  const std::uint32_t pgn_field = (id29 >> 8) & 0x3FFFFu;
  if (is_pdu1(pgn_field)) {
    id.pgn = pgn_field & 0x3FF00u;
    id.destination = static_cast<std::uint8_t>(pgn_field & 0xFFu);
  } else {
    id.pgn = pgn_field;
    id.destination = kGlobalAddress;
  }
  return id;
}

}  // namespace spread::isobus
