// firmware_sim: the simulated spreader ECU. Talks LCM (command_t / status_t / heartbeat_t) and ISOBUS
// (address claim, process data) over SocketCAN or a spread-canbus socket, or replays a candump log
// deterministically. See docs/messages.md and docs/can-integration.md.
#include <CLI/CLI.hpp>
#include <lcm/lcm-cpp.hpp>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "firmware_sim/can/can_ecu_link.hpp"
#include "libspread/control/ecu.hpp"
#include "firmware_sim/ecu/fixed_rate_loop.hpp"
#include "firmware_sim/lcm/lcm_ecu_link.hpp"
#include "isobus/can/candump_log.hpp"
#include "isobus/can/unix_can_bus.hpp"
#include "isobus/iso_name.hpp"
#ifdef SPREAD_FIRMWARE_HAS_CAPI
#include "capi/cpp/capi_spread_predictor.hpp"
#endif

namespace {

using namespace spread;  // the clock (core)
using namespace spread::firmware;

std::atomic<bool> g_stop{false};
extern "C" void on_signal(int) { g_stop.store(true); }

constexpr double kDegreesPerRadian = 57.29577951308232;

const char* border_text(BorderMode mode, bool applied) {
  switch (mode) {
    case BorderMode::kOff: return "";
    case BorderMode::kLeftBorder: return applied ? "  border=left (applied)" : "  border=left";
    case BorderMode::kRightBorder: return applied ? "  border=right (applied)" : "  border=right";
    case BorderMode::kLeftFieldEdge: return applied ? "  border=field-left (applied)" : "  border=field-left";
    case BorderMode::kRightFieldEdge: return applied ? "  border=field-right (applied)" : "  border=field-right";
  }
  return "";
}

// Section 1 first: '1' on, '0' off.
std::string bits(std::uint16_t mask, std::int32_t count) {
  std::string out;
  for (std::int32_t i = 0; i < count; ++i) out += ((mask >> i) & 1u) != 0 ? '1' : '0';
  return out;
}

// Prints one status line a second for a person watching the terminal.
class StatusPrinter final : public LoopIo {
 public:
  void pump(Nanoseconds) override {}
  void after_step(const EcuStatus& s) override {
    if (last_ && s.time - *last_ < std::chrono::seconds(1)) return;
    last_ = s.time;
    std::printf("t=%8.2f s  mode=%s  rpm=%7.1f->%7.1f  rate=%6.1f kg/ha  W=%5.2f m  v=%5.2f m/s  Q=%6.3f kg/s  "
                "throw=%5.2f m  eff=%5.2f±%.2f m  CV=%5.1f±%.1f %%  sections=%s/%s  discs=%.1f/%.1f rpm "
                "turn=%.1f/%.1f deg flow=%.2f/%.2f%s%s%s  faults=0x%05X\n",
                to_seconds(s.time - start_), s.mode == Mode::kAutomatic ? "auto" : "manual", s.rpm_actual,
                s.rpm_target, s.rate_setpoint_kg_ha, s.width_setpoint_m, s.ground_speed_m_s, s.mass_flow_kg_s,
                s.throw_width_m, s.effective_width_m, 1.96 * s.effective_width_se_m, s.cv_percent,
                1.96 * s.cv_se_percent, bits(s.section_mask, s.section_count).c_str(),
                bits(s.section_actual_mask, s.section_count).c_str(), s.disc_rpm_actual[0], s.disc_rpm_actual[1],
                s.disc_drop_point_turn_rad[0] * kDegreesPerRadian, s.disc_drop_point_turn_rad[1] * kDegreesPerRadian,
                s.disc_flow_fraction[0], s.disc_flow_fraction[1], s.sides_pending != 0 ? " (planning)" : "",
                border_text(s.border_mode, s.border_applied), s.wind_compensated ? "  wind-compensated" : "",
                s.fault_codes);
    std::fflush(stdout);
  }
  void start_at(Nanoseconds t) { start_ = t; }

 private:
  std::optional<Nanoseconds> last_;
  Nanoseconds start_{};
};

std::string hex_byte(std::uint8_t b) {
  char buf[3];
  std::snprintf(buf, sizeof buf, "%02X", unsigned{b});
  return buf;
}

void print_fault_summary(const Ecu& ecu) {
  std::fprintf(stderr, "firmware_sim: fault counts:");
  bool any = false;
  for (std::size_t i = 0; i < kFaultCount; ++i) {
    const auto f = static_cast<Fault>(i);
    if (ecu.faults().count(f) == 0) continue;
    any = true;
    std::fprintf(stderr, " %.*s=%llu", static_cast<int>(fault_name(f).size()), fault_name(f).data(),
                 static_cast<unsigned long long>(ecu.faults().count(f)));
  }
  std::fprintf(stderr, "%s\n", any ? "" : " none");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"firmware_sim: simulated centrifugal spreader ECU (LCM + ISOBUS/CAN)"};
  std::string lcm_url;
  bool no_lcm = false;
  std::string channel_prefix(lcm_link::kDefaultChannelPrefix);
  std::string command_channel, status_channel, heartbeat_channel;  // "" = prefix + COMMAND / STATUS / HEARTBEAT
  std::string can_interface;
  int can_address = 0x80;
  std::string tables_path;
  double cv_target_percent = 15.0;
  double rate_hz = 20.0;
  std::string replay_path;
  std::string record_path;
  double duration_s = 0.0;
  bool print_status = false;
  EcuParameters parameters;
  double command_timeout_s = 2.0;
  isobus::IsoName iso_name;  // defaults: agriculture, fertilisers, rate control (isobus/iso_name.hpp)
  std::string iso_name_hex;

  app.add_option("--lcm-url", lcm_url, "LCM provider URL (default: LCM's default udpm://239.255.76.67:7667?ttl=0)");
  app.add_flag("--no-lcm", no_lcm, "do not use LCM at all");
  app.add_option("--channel-prefix", channel_prefix, "prefix of the LCM channels <P>COMMAND, <P>STATUS, <P>HEARTBEAT")
      ->capture_default_str();
  app.add_option("--command-channel", command_channel, "full name of the command_t channel (overrides the prefix)");
  app.add_option("--status-channel", status_channel, "full name of the status_t channel (overrides the prefix)");
  app.add_option("--heartbeat-channel", heartbeat_channel,
                 "full name of the heartbeat_t channel (overrides the prefix)");
  app.add_option("--can", can_interface, "ISOBUS: a SocketCAN interface (can0) or a spread-canbus socket (unix:PATH)");
  app.add_option("--can-address", can_address, "this ECU's ISOBUS source address (0..253)")
      ->check(CLI::Range(0, 253))
      ->capture_default_str();
  // ISO 11783-5 NAME of the ECU: a whole 64-bit value, or the fields a user normally sets per unit.
  auto* name_hex = app.add_option("--isobus-name", iso_name_hex,
                                  "ISO 11783-5 NAME as 16 hex digits (overrides the --isobus-* fields)");
  auto* name_fields = app.add_option_group("isobus NAME fields");
  name_fields->add_flag("--isobus-self-configurable", iso_name.self_configurable,
                        "may take another address in 128..247 when it loses its own");
  name_fields->add_option("--isobus-function", iso_name.function, "NAME function (128: rate control)")
      ->capture_default_str();
  name_fields->add_option("--isobus-function-instance", iso_name.function_instance, "NAME function instance (0..31)")
      ->check(CLI::Range(0, 31));
  name_fields->add_option("--isobus-ecu-instance", iso_name.ecu_instance, "NAME ECU instance (0..7)")
      ->check(CLI::Range(0, 7));
  name_fields->add_option("--isobus-device-class-instance", iso_name.device_class_instance,
                          "NAME device class instance (0..15)")
      ->check(CLI::Range(0, 15));
  name_fields->add_option("--isobus-manufacturer", iso_name.manufacturer_code, "NAME manufacturer code (0..2047)")
      ->check(CLI::Range(0, 2047));
  auto* identity = name_fields->add_option("--isobus-identity", iso_name.identity_number,
                                           "NAME identity number (0..2097151)")
                        ->check(CLI::Range(0, 2097151))
                        ->capture_default_str();
  // ISO 11783-5: the identity number makes a unit's NAME unique among units of one manufacturer; two units
  // with one NAME both lose their address. Each unit is started with its own serial number.
  name_fields->add_option("--serial", iso_name.identity_number,
                          "this unit's serial number (0..2097151): the NAME's identity number and the pool's "
                          "serial SIM-<n>; give every unit its own")
      ->check(CLI::Range(0, 2097151))
      ->excludes(identity);
  name_fields->excludes(name_hex);
  app.add_option("--tables", tables_path, "launch-table file (lookup_builder output); enables automatic mode")
      ->check(CLI::ExistingFile);
  app.add_option("--cv-target", cv_target_percent, "CV target of the effective working width [%]")
      ->check(CLI::Range(0.1, 100.0))
      ->capture_default_str();
  app.add_option("--rate-hz", rate_hz, "loop frequency [Hz]")->check(CLI::Range(0.1, 1000.0))->capture_default_str();
  app.add_option("--replay", replay_path, "replay a candump log into the ECU (simulated time) and print answers")
      ->check(CLI::ExistingFile);
  app.add_option("--record", record_path, "write every CAN frame received and sent to this candump log");
  app.add_option("--duration", duration_s, "stop after this many seconds (0: until Ctrl-C; replay: log length + 1 s)")
      ->check(CLI::NonNegativeNumber);
  app.add_flag("--print-status", print_status, "print a status line once a second");
  app.add_option("--disc-time-constant", parameters.disc_time_constant_s, "disc drive first-order lag [s]")
      ->capture_default_str();
  app.add_option("--sections", parameters.section_count, "sections installed (1..16)")->capture_default_str();
  app.add_option("--discs", parameters.disc_count, "spinning discs, 1 or 2 (two: section control through the discs)")
      ->check(CLI::Range(1, 2))
      ->capture_default_str();
  std::string material;
  app.add_option("--material", material,
                 "material in the hopper until an LCM command names one (a CAN-only machine: as chosen at its "
                 "terminal); needs --tables");
  app.add_option("--max-width", parameters.width_max_m, "maximum working width [m] (DDI 70)")->capture_default_str();
  app.add_option("--command-timeout", command_timeout_s, "close metering after this long without input [s] (0: off)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  if (!replay_path.empty() && !can_interface.empty()) {
    std::cerr << "firmware_sim: error: --replay and --can are exclusive (replay feeds the log instead of a bus)\n";
    return 2;
  }
  parameters.command_timeout = from_seconds(command_timeout_s);
  std::uint64_t name_value = isobus::encode_name(iso_name);
  if (!iso_name_hex.empty()) {
    const auto parsed = isobus::parse_name_hex(iso_name_hex);
    if (!parsed) {
      std::cerr << "firmware_sim: error: --isobus-name '" << iso_name_hex << "' is not 1 to 16 hex digits\n";
      return 2;
    }
    name_value = *parsed;
  }

  try {
    std::unique_ptr<SpreadPredictor> predictor;
    // Section control through the discs searches on a thread of its own with its own C API handle.
    std::unique_ptr<SpreadPredictor> planner_predictor;
    if (!tables_path.empty()) {
#ifdef SPREAD_FIRMWARE_HAS_CAPI
      predictor = std::make_unique<CapiSpreadPredictor>(tables_path, cv_target_percent);
      planner_predictor = std::make_unique<CapiSpreadPredictor>(tables_path, cv_target_percent);
#else
      std::cerr << "firmware_sim: error: built without the C API (target spreadc): --tables is unavailable\n";
      return 2;
#endif
    }

    // Replay runs on simulated time starting at the log's first timestamp, so answers are reproducible.
    std::optional<isobus::can::CandumpLog> replay_log;
    std::unique_ptr<Clock> clock;
    if (!replay_path.empty()) {
      replay_log = isobus::can::read_candump_file(replay_path);
      for (const auto& e : replay_log->errors) std::cerr << "firmware_sim: " << replay_path << ": " << e << "\n";
      const Nanoseconds start = replay_log->records.empty() ? Nanoseconds::zero() : replay_log->records.front().time;
      clock = std::make_unique<ManualClock>(start);
    } else {
      clock = std::make_unique<SteadyClock>();
    }

    // A replay plans inline on its simulated clock: the same log gives the same answers.
    std::unique_ptr<SectionPlanner> planner;
    if (planner_predictor) {
      planner = std::make_unique<SectionPlanner>(
          *planner_predictor, parameters.section_max_beyond_percent,
          replay_log ? SectionPlanner::Threading::kInline : SectionPlanner::Threading::kWorker);
    }
    Ecu ecu(*clock, parameters, predictor.get(), planner.get());
    if (!material.empty()) {
      if (!predictor) throw std::invalid_argument("--material " + material + " needs --tables");
      if (ecu.set_material(material)) throw std::invalid_argument("--material " + material + ": not in the tables");
    }
    if (replay_log) {
      for (std::size_t i = 0; i < replay_log->errors.size(); ++i) ecu.record_fault(Fault::kReplayParseError);
    }
    FixedRateLoop loop(*clock, rate_hz);
    LoopIoGroup io;

    std::unique_ptr<lcm::LCM> lcm;
    std::unique_ptr<LcmEcuLink> lcm_io;
    if (!no_lcm) {
      lcm = std::make_unique<lcm::LCM>(lcm_url);
      if (!lcm->good()) throw std::runtime_error("LCM: cannot create an instance for URL '" + lcm_url + "'");
      lcm_io = std::make_unique<LcmEcuLink>(*lcm, ecu, lcm_link::channels_from(channel_prefix, command_channel, status_channel, heartbeat_channel));
      lcm_io->attach_loop(&loop);
      io.add(*lcm_io);
    }

    std::ofstream record_file;
    std::unique_ptr<isobus::can::CandumpWriter> recorder;
    if (!record_path.empty()) {
      record_file.open(record_path);
      if (!record_file) throw std::runtime_error("cannot write candump log '" + record_path + "'");
      // candump stamps wall-clock time; a replay's clock already runs on the log's own timestamps.
      const Nanoseconds epoch_offset =
          replay_log ? Nanoseconds::zero()
                     : std::chrono::duration_cast<Nanoseconds>(std::chrono::system_clock::now().time_since_epoch()) -
                           clock->now();
      recorder = std::make_unique<isobus::can::CandumpWriter>(record_file, *clock, isobus::can::can_bus_log_name(can_interface),
                                                      epoch_offset);
    }

    can::CanEcuSettings can_settings;
    can_settings.address = static_cast<std::uint8_t>(can_address);
    can_settings.name = name_value;
    isobus::can::CanFramePort can_port;
    std::unique_ptr<can::CanPortIo> can_io;
    if (!can_interface.empty()) {
      can_port = isobus::can::open_can_bus(can_interface);
      can_io = std::make_unique<can::CanPortIo>(can_port, ecu, *clock, can_settings, recorder.get());
      can_io->processor().start_address_claim();
      io.add(*can_io);
    }

    // Replay answers go to stdout as candump lines (and to --record with the received frames).
    std::unique_ptr<isobus::can::CandumpWriter> replay_answers;
    std::unique_ptr<isobus::can::TeeSink> replay_tx;
    std::unique_ptr<can::CanEcuProcessor> replay_processor;
    std::unique_ptr<can::CandumpReplayIo> replay_io;
    if (replay_log) {
      replay_answers = std::make_unique<isobus::can::CandumpWriter>(std::cout, *clock, "can0");
      replay_tx = std::make_unique<isobus::can::TeeSink>(*replay_answers, recorder.get());
      replay_processor = std::make_unique<can::CanEcuProcessor>(ecu, *clock, *replay_tx, can_settings);
      replay_io = std::make_unique<can::CandumpReplayIo>(*replay_log, *replay_processor, *clock, recorder.get());
      io.add(*replay_io);
    }

    StatusPrinter printer;
    printer.start_at(clock->now());
    if (print_status) io.add(printer);

    std::signal(SIGINT, on_signal);
    std::signal(SIGTERM, on_signal);
    std::optional<Nanoseconds> duration;
    if (duration_s > 0.0) duration = from_seconds(duration_s);
    if (replay_io && !duration) duration = replay_io->span() + std::chrono::seconds(1);
    std::cerr << "firmware_sim: running at " << rate_hz << " Hz"
              << (lcm_io ? ", LCM channels " + lcm_io->channels().command + "/" + lcm_io->channels().status : "")
              << (can_io ? ", CAN " + can_interface + ", " + isobus::describe_name(name_value) : "") << (replay_io ? ", replaying " + replay_path : "")
              << (predictor ? ", tables " + tables_path : ", no tables (manual mode only)") << "\n";
    loop.run(ecu, io, duration, &g_stop);
    std::cerr << "firmware_sim: " << loop.statistics().ticks << " ticks, " << loop.statistics().overruns
              << " overruns, worst step " << std::chrono::duration<double, std::micro>(loop.statistics().worst_step).count()
              << " us\n";
    print_fault_summary(ecu);
    const can::CanEcuProcessor* processor =
        can_io ? &can_io->processor() : replay_processor ? replay_processor.get() : nullptr;
    if (processor != nullptr) {
      // The partner task controller (ISO 11783-10): whom the ECU obeyed, and what it ignored from others.
      const auto& partner = processor->task_controller_partner();
      const auto& c = processor->counters();
      std::fprintf(stderr,
                   "firmware_sim: task controller %s, partners chosen %llu lost %llu%s%s, ignored from other nodes "
                   "%llu, TC status of other TCs %llu\n",
                   partner.address() ? ("0x" + hex_byte(*partner.address())).c_str() : "none",
                   static_cast<unsigned long long>(partner.counters().partners_chosen),
                   static_cast<unsigned long long>(partner.counters().partners_lost),
                   partner.last_loss().empty() ? "" : ", last lost: ", partner.last_loss().c_str(),
                   static_cast<unsigned long long>(c.not_from_partner),
                   static_cast<unsigned long long>(c.other_task_controllers));
    }
    if (can_io) {
      const auto& network = can_io->processor().network();
      const auto& claim = network.claim().counters();
      std::fprintf(stderr,
                   "firmware_sim: ISOBUS address %s0x%02X, claims sent %llu, contentions won %llu lost %llu, "
                   "cannot-claim sent %llu, requests NACKed %llu, our NAME from another node %llu (hold-offs "
                   "%llu), address violations %llu, address losses %llu, TC refusals %llu, process data before "
                   "reconnection %llu, TC connections %llu\n",
                   network.has_address() ? "" : "none, last ", unsigned{network.address()},
                   static_cast<unsigned long long>(claim.claims_sent),
                   static_cast<unsigned long long>(claim.contentions_won),
                   static_cast<unsigned long long>(claim.contentions_lost),
                   static_cast<unsigned long long>(claim.cannot_claim_sent),
                   static_cast<unsigned long long>(network.counters().requests_nacked),
                   static_cast<unsigned long long>(claim.duplicate_names),
                   static_cast<unsigned long long>(claim.duplicate_name_holds),
                   static_cast<unsigned long long>(claim.address_violations),
                   static_cast<unsigned long long>(network.counters().address_losses),
                   static_cast<unsigned long long>(can_io->processor().counters().tc_refusals),
                   static_cast<unsigned long long>(can_io->processor().counters().before_reconnection),
                   static_cast<unsigned long long>(can_io->processor().task_controller_client().connections()));
    }
  } catch (const std::exception& e) {
    std::cerr << "firmware_sim: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
