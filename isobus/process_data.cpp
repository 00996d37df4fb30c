#include "isobus/process_data.hpp"

namespace spread::isobus {
namespace {

void put_header(ProcessDataBytes& b, std::uint8_t command, std::uint16_t element, std::uint16_t ddi) {
  b[0] = static_cast<std::uint8_t>((command & 0x0Fu) | ((element & 0x0Fu) << 4));
  b[1] = static_cast<std::uint8_t>((element >> 4) & 0xFFu);
  b[2] = static_cast<std::uint8_t>(ddi & 0xFFu);
  b[3] = static_cast<std::uint8_t>(ddi >> 8);
}

}  // namespace

ProcessDataBytes encode_process_data(const ProcessData& m) {
  ProcessDataBytes b{};
  put_header(b, m.command, m.element, m.ddi);
  const auto v = static_cast<std::uint32_t>(m.value);
  for (int i = 0; i < 4; ++i) b[static_cast<std::size_t>(4 + i)] = static_cast<std::uint8_t>(v >> (8 * i));
  return b;
}

ProcessData decode_process_data(const ProcessDataBytes& b) {
  ProcessData m;
  m.command = static_cast<std::uint8_t>(b[0] & 0x0Fu);
  m.element = static_cast<std::uint16_t>((b[0] >> 4) | (std::uint16_t{b[1]} << 4));
  m.ddi = static_cast<std::uint16_t>(b[2] | (std::uint16_t{b[3]} << 8));
  std::uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v |= std::uint32_t{b[static_cast<std::size_t>(4 + i)]} << (8 * i);
  m.value = static_cast<std::int32_t>(v);
  return m;
}

ProcessDataBytes encode_pdack(const ProcessData& request, std::uint8_t error_bits) {
  ProcessDataBytes b{};
  put_header(b, static_cast<std::uint8_t>(ProcessDataCommand::kAcknowledge), request.element, request.ddi);
  b[4] = error_bits;
  b[5] = static_cast<std::uint8_t>(0xF0u | (request.command & 0x0Fu));  // upper nibble reserved = 1s
  b[6] = 0xFF;
  b[7] = 0xFF;
  return b;
}

std::optional<Pdack> decode_pdack(const ProcessDataBytes& b) {
  const ProcessData header = decode_process_data(b);
  if (header.command != static_cast<std::uint8_t>(ProcessDataCommand::kAcknowledge)) return std::nullopt;
  return Pdack{header.element, header.ddi, b[4], static_cast<std::uint8_t>(b[5] & 0x0Fu)};
}

}  // namespace spread::isobus
