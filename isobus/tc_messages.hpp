#pragma once
// The task-controller connection messages of ISO 11783-10 (process data PGN 0xCB00), shared by the ECU's
// TC client and the TC role of spread-tractor. Byte 0 holds the command in its low nibble and, for the
// commands below, a sub-command in its high nibble; unused bytes are 0xFF. Messages longer than 8 bytes
// (only the object-pool transfer) travel by TP/ETP (transport_protocol.hpp).
//
//   command 0x0 technical capabilities   0x00 request version / 0x10 version (both directions)
//   command 0x1 device descriptor        0x01/0x11 structure label request / answer,
//                                        0x21/0x31 localisation label request / answer,
//                                        0x41/0x51 request object-pool transfer (size) / answer,
//                                        0x61/0x71 object-pool transfer (pool bytes) / answer,
//                                        0x81/0x91 object-pool activate-deactivate / answer
//   command 0xE task controller status   TC -> all, every 2 s
//   command 0xF client task              client -> TC, every 2 s
// and, before any of them, the working-set master message (PGN 0xFE0D, ISO 11783-7 / -1) naming how many
// control functions the implement's working set has.
#include <array>
#include <chrono>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace spread::isobus {

inline constexpr std::uint32_t kWorkingSetMasterPgn = 0xFE0D;
inline constexpr std::uint8_t kTcMessagePriority = 3;
// ISO 11783-10: the TC status and the client task message are sent every 2 s; a partner silent for 6 s
// (three messages) is gone.
inline constexpr std::chrono::seconds kTcStatusInterval{2};
inline constexpr std::chrono::seconds kTcPartnerTimeout{6};

enum class TcMessage : std::uint8_t {
  kRequestVersion = 0x00,
  kVersion = 0x10,
  kRequestStructureLabel = 0x01,
  kStructureLabel = 0x11,
  kRequestLocalizationLabel = 0x21,
  kLocalizationLabel = 0x31,
  kRequestPoolTransfer = 0x41,
  kRequestPoolTransferResponse = 0x51,
  kPoolTransfer = 0x61,
  kPoolTransferResponse = 0x71,
  kActivatePool = 0x81,
  kActivatePoolResponse = 0x91,
  kTcStatus = 0xFE,   // command 0xE with element nibble 0xF
  kClientTask = 0xFF, // command 0xF with element nibble 0xF
};

// Version message (ISO 11783-10 technical capabilities): bytes 1 version, 2 boot time [s] (0xFF = n.a.),
// 3 provided options bits, 4 reserved, 5 booms, 6 sections, 7 control channels.
struct TcVersion {
  std::uint8_t version = 4;
  std::uint8_t boot_time_s = 0xFF;
  std::uint8_t options = 0;
  std::uint8_t booms = 1;
  std::uint8_t sections = 0;
  std::uint8_t channels = 1;
};

using TcFrame = std::array<std::uint8_t, 8>;

inline TcFrame tc_frame(TcMessage m) {
  TcFrame f;
  f.fill(0xFF);
  f[0] = static_cast<std::uint8_t>(m);
  return f;
}

inline TcFrame encode_version(const TcVersion& v) {
  TcFrame f = tc_frame(TcMessage::kVersion);
  f[1] = v.version;
  f[2] = v.boot_time_s;
  f[3] = v.options;
  f[4] = 0x00;
  f[5] = v.booms;
  f[6] = v.sections;
  f[7] = v.channels;
  return f;
}

inline TcVersion decode_version(std::span<const std::uint8_t> b) {
  TcVersion v;
  if (b.size() < 8) return v;
  v.version = b[1];
  v.boot_time_s = b[2];
  v.options = b[3];
  v.booms = b[5];
  v.sections = b[6];
  v.channels = b[7];
  return v;
}

// Structure / localisation label answers: bytes 1-7 the label (all 0xFF: the TC holds no pool of ours).
inline TcFrame encode_label(TcMessage answer, const std::array<std::uint8_t, 7>& label) {
  TcFrame f = tc_frame(answer);
  for (std::size_t i = 0; i < 7; ++i) f[i + 1] = label[i];
  return f;
}

// Request object-pool transfer: bytes 1-4 the pool size [bytes], little endian.
inline TcFrame encode_request_pool_transfer(std::uint32_t pool_bytes) {
  TcFrame f = tc_frame(TcMessage::kRequestPoolTransfer);
  for (int i = 0; i < 4; ++i) f[static_cast<std::size_t>(1 + i)] = static_cast<std::uint8_t>(pool_bytes >> (8 * i));
  return f;
}

// Answers with an error byte in byte 1 (0 = accepted): request-pool-transfer answer (1 = not enough
// memory), pool-transfer answer (bit 0 pool error, bit 1 out of memory; bytes 2-5 the size received),
// activate answer (bit 0 error in the pool, bit 1 out of memory, ...; bytes 2-3 parent of the faulty
// object, 4-5 the faulty object, 6 its error code).
inline TcFrame encode_error_answer(TcMessage answer, std::uint8_t error) {
  TcFrame f = tc_frame(answer);
  f[1] = error;
  return f;
}

// Activate / deactivate: byte 1 0xFF activate, 0x00 deactivate.
inline TcFrame encode_activate(bool activate) {
  TcFrame f = tc_frame(TcMessage::kActivatePool);
  f[1] = activate ? 0xFF : 0x00;
  return f;
}

// The object-pool transfer message: the sub-command byte, then the pool.
inline std::vector<std::uint8_t> encode_pool_transfer(std::span<const std::uint8_t> pool) {
  std::vector<std::uint8_t> m;
  m.reserve(pool.size() + 1);
  m.push_back(static_cast<std::uint8_t>(TcMessage::kPoolTransfer));
  m.insert(m.end(), pool.begin(), pool.end());
  return m;
}

// TC status: byte 4 status bits (bit 0 task active), byte 5 the client being commanded (0xFF none),
// byte 6 the command being processed. Client task: byte 4 bit 0 = the client is ready.
inline TcFrame encode_tc_status(bool task_active) {
  TcFrame f = tc_frame(TcMessage::kTcStatus);
  f[4] = task_active ? 0x01 : 0x00;
  return f;
}
inline TcFrame encode_client_task(bool ready) {
  TcFrame f = tc_frame(TcMessage::kClientTask);
  f[4] = ready ? 0x01 : 0x00;
  return f;
}

// Working-set master message: byte 0 the number of members (this ECU alone: 1).
inline TcFrame encode_working_set_master(std::uint8_t members = 1) {
  TcFrame f;
  f.fill(0xFF);
  f[0] = members;
  return f;
}

// The message kind of a received PGN 0xCB00 payload, for the connection messages above.
inline std::optional<TcMessage> tc_message_kind(std::span<const std::uint8_t> b) {
  if (b.empty()) return std::nullopt;
  switch (b[0]) {
    case 0x00: case 0x10: case 0x01: case 0x11: case 0x21: case 0x31: case 0x41: case 0x51: case 0x61:
    case 0x71: case 0x81: case 0x91: case 0xFE: case 0xFF:
      return static_cast<TcMessage>(b[0]);
    default:
      return std::nullopt;
  }
}

}  // namespace spread::isobus
