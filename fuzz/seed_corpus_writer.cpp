// Writes the seed corpora of the fuzz harnesses into fuzz/corpus/<harness>/ from real inputs:
// the shipped scenes, a small table built by the lookup_builder library, the recorded candump session of
// the firmware tests (as text and as raw can_frame records), LCM messages encoded by the generated types,
// well-formed C API definitions, and complete TP / ETP / BAM transfers as the receiver sees them. Run once after a format change:
//   build-fuzz/fuzz/seed_corpus_writer fuzz/corpus
// The corpora are committed; run-fuzz.sh and the replay tests use them as they are.
#include <linux/can.h>

#include <chrono>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "firmware_sim/can/spreader_ddop.hpp"
#include "isobus/can/candump_log.hpp"
#include "isobus/tc_messages.hpp"
#include "isobus/transport_protocol.hpp"
#include "libspread/io/scene/scene.hpp"
#include "lookup_builder/table_build.hpp"
#include "spread/command_t.hpp"
#include "spread/heartbeat_t.hpp"
#include "spread/status_t.hpp"

namespace fs = std::filesystem;

namespace {

void write_bytes(const fs::path& path, const void* data, std::size_t size) {
  fs::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
}
void write_bytes(const fs::path& path, const std::vector<std::uint8_t>& bytes) { write_bytes(path, bytes.data(), bytes.size()); }
void write_text(const fs::path& path, const std::string& text) { write_bytes(path, text.data(), text.size()); }

template <typename T>
void append(std::vector<std::uint8_t>& out, const T& value) {
  const auto* p = reinterpret_cast<const std::uint8_t*>(&value);
  out.insert(out.end(), p, p + sizeof(T));
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

template <typename Message>
std::vector<std::uint8_t> lcm_payload(std::uint8_t channel, Message& message) {
  std::vector<std::uint8_t> bytes(1 + static_cast<std::size_t>(message.getEncodedSize()));
  bytes[0] = channel;
  message.encode(bytes.data() + 1, 0, static_cast<int>(bytes.size() - 1));
  return bytes;
}

void scene_seeds(const fs::path& source, const fs::path& out) {
  for (const auto& entry : fs::directory_iterator(source / "scenes")) {
    if (entry.path().extension() == ".toml") fs::copy_file(entry.path(), out / "scene_parser" / entry.path().filename(), fs::copy_options::overwrite_existing);
  }
  write_text(out / "scene_parser" / "default_with_overrides.toml",
             read_text(source / "scenes/default.toml") +
                 "\n#--set\nmaterials.1.density_kg_m3=1800\nair.wind_m_s.0=2.5\nsimulate.material=Urea\nsweep.rpm=[500.0]\n");
}

void table_seeds(const fs::path& source, const fs::path& out) {
  // Small on purpose: libFuzzer mutates a few KB far more effectively than a large file.
  const fs::path table = out / "table_loader" / "default_small.sqlite";
  fs::create_directories(table.parent_path());
  fs::remove(table);
  const spread::scene::Scene scene = spread::scene::load_scene_file(
      (source / "scenes/default.toml").string(),
      {"sweep.source=\"analytic\"", "sweep.samples_per_run=4", "sweep.rpm=[450.0, 600.0]",
       "sweep.materials=[\"Urea\"]"});
  spread::lookup::BuildOptions options;
  options.output_path = table.string();
  spread::lookup::build_tables(scene, options);
  fs::create_directories(out / "capi_open");
  fs::copy_file(table, out / "capi_open" / "default_small.sqlite", fs::copy_options::overwrite_existing);
}

void can_seeds(const fs::path& source, const fs::path& out) {
  const fs::path log = source / "tests/firmware/data/process_data_session.log";
  fs::create_directories(out / "candump");
  fs::copy_file(log, out / "candump" / "process_data_session.log", fs::copy_options::overwrite_existing);
  const auto records = spread::isobus::can::read_candump_file(log.string()).records;
  std::vector<std::uint8_t> session;
  for (std::size_t i = 0; i < records.size(); ++i) {
    std::vector<std::uint8_t> one;
    append(one, records[i].frame);
    one.push_back(10);  // 10 ms loop step after the frame
    write_bytes(out / "can_frames" / ("frame_" + std::to_string(i) + ".bin"), one);
    session.insert(session.end(), one.begin(), one.end());
  }
  write_bytes(out / "can_frames" / "session.bin", session);
}

// fuzz_transport_protocol input: flag byte, then per frame: PGN selector, source, destination, 8 data bytes,
// milliseconds to advance. A real sender session talks to the node under test (0x80); every frame that
// reaches 0x80 is recorded.
void transport_seeds(const fs::path& out) {
  namespace iso = spread::isobus;
  auto selector = [](std::uint32_t pgn) -> std::uint8_t {
    if (pgn == iso::kTpConnectionManagementPgn) return 0;
    if (pgn == iso::kTpDataTransferPgn) return 1;
    if (pgn == iso::kEtpConnectionManagementPgn) return 2;
    return 3;
  };
  struct Case {
    const char* name;
    std::uint8_t flags;
    std::uint8_t peer;
    std::uint8_t destination;
    std::size_t size;
    int step_ms;
  };
  const Case cases[] = {{"tp_100", 0, 0x81, 0x80, 100, 0},      {"tp_1785", 0, 0x81, 0x80, 1785, 0},
                        {"etp_3000", 0, 0x82, 0x80, 3000, 0},    {"bam_30", 0, 0x83, 0xFF, 30, 50},
                        {"we_send_tp", 1, 0x81, 0x80, 0, 0},     {"we_send_etp", 2, 0x82, 0x80, 0, 0}};
  for (const Case& c : cases) {
    std::vector<std::uint8_t> bytes{c.flags};
    std::chrono::nanoseconds now{0};
    iso::TransportProtocol node(0x80, iso::TransportLimits{8192, 8, 16});
    iso::TransportProtocol peer(c.peer);
    std::vector<std::uint8_t> data(c.size);
    for (std::size_t i = 0; i < data.size(); ++i) data[i] = static_cast<std::uint8_t>(i * 13);
    if (c.size > 0) peer.send({0xCB00, c.peer, c.destination, data}, now);
    if ((c.flags & 1u) != 0) node.send({0xCB00, 0x80, 0x81, std::vector<std::uint8_t>(100, 0x55)}, now);
    if ((c.flags & 2u) != 0) node.send({0xCB00, 0x80, 0x82, std::vector<std::uint8_t>(2000, 0x66)}, now);
    for (int round = 0; round < 2000; ++round) {
      auto to_node = peer.take_frames();
      auto to_peer = node.take_frames();
      if (to_node.empty() && to_peer.empty()) {
        if (peer.session_count() == 0 && node.session_count() == 0) break;
        now += std::chrono::milliseconds(c.step_ms > 0 ? c.step_ms : 10);
        peer.update(now);
        node.update(now);
        continue;
      }
      for (const auto& f : to_node) {
        bytes.push_back(selector(f.pgn));
        bytes.push_back(f.source);
        bytes.push_back(f.destination);
        bytes.insert(bytes.end(), f.data.begin(), f.data.end());
        bytes.push_back(static_cast<std::uint8_t>(c.step_ms));
        node.handle_frame(f, now);
      }
      for (const auto& f : to_peer) peer.handle_frame(f, now);
    }
    write_bytes(out / "transport_protocol" / (std::string(c.name) + ".bin"), bytes);
  }
}

// fuzz_tc_server input: flag byte (bit 0: a client connects with the spreader's pool first), then records
// of kind, destination, 8 data bytes, milliseconds to advance. Seeds: the handshake without a pool, and an
// active client reporting values, sending client task messages, deactivating and activating again.
void tc_server_seeds(const fs::path& out) {
  namespace iso = spread::isobus;
  constexpr std::uint8_t kTc = 0xF7;
  auto record = [](std::vector<std::uint8_t>& bytes, std::uint8_t op, std::uint8_t destination,
                   const std::array<std::uint8_t, 8>& data, std::uint8_t advance_ms) {
    bytes.push_back(static_cast<std::uint8_t>(op | (8u << 4)));  // source 0x80, 8 bytes
    bytes.push_back(destination);
    bytes.insert(bytes.end(), data.begin(), data.end());
    bytes.push_back(advance_ms);
  };
  constexpr std::uint8_t kPd = 4;
  constexpr std::uint8_t kWsm = 5;
  std::vector<std::uint8_t> handshake{0};
  record(handshake, kWsm, 0xFF, iso::encode_working_set_master(), 10);
  record(handshake, kPd, kTc, iso::tc_frame(iso::TcMessage::kRequestVersion), 10);
  record(handshake, kPd, kTc, iso::encode_version(iso::TcVersion{}), 10);
  record(handshake, kPd, kTc, iso::tc_frame(iso::TcMessage::kRequestStructureLabel), 10);
  record(handshake, kPd, kTc, iso::tc_frame(iso::TcMessage::kRequestLocalizationLabel), 10);
  record(handshake, kPd, kTc, iso::encode_request_pool_transfer(1367), 10);
  record(handshake, kPd, kTc, iso::encode_activate(true), 250);
  write_bytes(out / "tc_server" / "handshake_no_pool.bin", handshake);

  std::vector<std::uint8_t> active{1};
  for (int i = 0; i < 4; ++i) {
    record(active, kPd, kTc, iso::encode_client_task(true), 250);
    record(active, kPd, kTc, {0x23, 0x00, 0x07, 0x00, 0xA8, 0x61, 0x00, 0x00}, 250);  // value, element 2, DDI 7
    record(active, 6, 0, {0x22, 0x01, 0x55, 0x00, 0xFF, 0xFF, 0, 0}, 250);            // set DDI 290
    record(active, 7, 0, {0x07, 0x00, 0, 0, 0, 0, 0, 0}, 250);                        // request DDI 7
  }
  record(active, kPd, kTc, iso::encode_activate(false), 100);
  record(active, kPd, kTc, iso::encode_activate(true), 255);
  write_bytes(out / "tc_server" / "active_client.bin", active);
}

// fuzz_ddop input: a pool's bytes. The spreader's pool for 1, 8 and 16 sections.
void ddop_seeds(const fs::path& out) {
  namespace iso = spread::isobus;
  for (const int sections : {1, 8, 16}) {
    spread::firmware::can::SpreaderDescription d;
    d.section_count = sections;
    d.name = 0xA00A8000001234ull;
    write_bytes(out / "ddop" / ("spreader_" + std::to_string(sections) + ".bin"),
                iso::write_ddop(spread::firmware::can::make_spreader_ddop(d)));
  }
}

void lcm_seeds(const fs::path& out) {
  spread::command_t command{};
  command.timestamp_us = 1000;
  command.sequence = 1;
  command.mode = spread::command_t::MODE_MANUAL;
  command.rate_setpoint_kg_ha = 250.0;
  command.width_setpoint_m = 24.0;
  command.ground_speed_m_s = 3.0;
  command.material = "Urea";
  command.rpm_setpoint = 600.0;
  command.work_state = true;
  command.num_sections = 4;
  command.section_on = {true, true, false, true};
  write_bytes(out / "lcm_handlers" / "command_manual.bin", lcm_payload(0, command));
  command.mode = spread::command_t::MODE_AUTOMATIC;
  command.sequence = 2;
  write_bytes(out / "lcm_handlers" / "command_automatic.bin", lcm_payload(0, command));

  spread::status_t status{};
  status.material = "Urea";
  status.num_sections = 2;
  status.section_on = {true, false};
  status.num_fault_counts = 3;
  status.fault_counts = {0, 1, 2};
  status.cv_percent = 12.5;
  write_bytes(out / "lcm_handlers" / "status.bin", lcm_payload(1, status));

  spread::heartbeat_t heartbeat{};
  heartbeat.node = "firmware_sim";
  heartbeat.loop_rate_mhz = 20000;
  write_bytes(out / "lcm_handlers" / "heartbeat.bin", lcm_payload(2, heartbeat));
}

// The byte layouts below follow the harnesses' readers (fuzz_capi_predict.cpp, fuzz_capi_trajectory.cpp).
void capi_seeds(const fs::path& out) {
  struct PredictSeed {
    const char* name;
    std::uint8_t raw_flags, material;
    std::uint16_t rpm;
    std::uint8_t height_default, height_cm;
    std::int8_t wind_x, wind_y;
    std::uint8_t cv_half_percent, effects, bout_quarter_m, tray_cm_above_2, buffer;
  };
  const PredictSeed predict[] = {
      {"defaults_mid_rpm", 0, 0, 32768, 0, 0, 0, 0, 30, 0x7, 0, 48, 2},
      {"stored_height_wind", 0, 1, 20000, 1, 80, 12, -8, 30, 0xF, 0, 48, 2},
      {"bout_width_small_buffer", 0, 2, 50000, 1, 60, 0, 0, 20, 0x3, 72, 23, 1},
      {"no_buffer_no_effects", 0, 0, 65535, 1, 0, 0, 0, 10, 0x0, 96, 98, 0},
  };
  for (const PredictSeed& s : predict) {
    std::vector<std::uint8_t> b;
    append(b, s.raw_flags);
    append(b, s.material);
    append(b, s.rpm);
    append(b, s.height_default);
    append(b, s.height_cm);
    append(b, s.wind_x);
    append(b, s.wind_y);
    append(b, s.cv_half_percent);
    append(b, s.effects);
    append(b, s.bout_quarter_m);
    append(b, s.tray_cm_above_2);
    append(b, s.buffer);
    write_bytes(out / "capi_predict" / (std::string(s.name) + ".bin"), b);
  }
  // Trajectory: all fields from their plausible ranges (flags 0); values are 16-bit fractions.
  const std::vector<std::vector<std::uint16_t>> trajectories = {
      {0, 19000, 18000, 32768, 32768, 32768, 20000, 45000, 33000, 32768, 32768, 32768, 32768, 32768, 32768, 40000, 10000, 32768, 32768, 32768},
      {0, 1000, 60000, 40000, 20000, 40000, 65535, 32768, 32768, 0, 50000, 30000, 40000, 32768, 20000, 16000, 30000, 50000, 10000, 32768},
  };
  int k = 0;
  for (const auto& fields : trajectories) {
    std::vector<std::uint8_t> b;
    for (std::uint16_t f : fields) append(b, f);
    b.push_back(0xF);  // effects
    write_bytes(out / "capi_trajectory" / ("plausible_" + std::to_string(k++) + ".bin"), b);
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: seed_corpus_writer OUTPUT_DIR (normally fuzz/corpus)\n";
    return 2;
  }
  const fs::path out = argv[1];
  const fs::path source = SPREAD_SOURCE_DIR;
  try {
    fs::create_directories(out / "scene_parser");
    scene_seeds(source, out);
    table_seeds(source, out);
    can_seeds(source, out);
    transport_seeds(out);
    ddop_seeds(out);
    tc_server_seeds(out);
    lcm_seeds(out);
    capi_seeds(out);
  } catch (const std::exception& e) {
    std::cerr << "seed_corpus_writer: " << e.what() << "\n";
    return 1;
  }
  std::cout << "seed corpora written to " << out << "\n";
  return 0;
}
