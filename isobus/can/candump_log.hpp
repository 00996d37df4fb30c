#pragma once
// candump log files (can-utils `candump -L` / `canplayer` format), one frame a line:
//   (1700000000.123456) can0 0CCB8081#0306000064000000
// 8 hex digits = 29-bit extended id, 3 = 11-bit standard id; `#R` = remote frame. CAN FD (`##`) is
// not supported and reported as a bad line.
#include <cstdint>
#include <iosfwd>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "isobus/can/can_frame_port.hpp"
#include "libspread/core/clock.hpp"

namespace spread::isobus::can {

struct CandumpRecord {
  Nanoseconds time{};     // timestamp of the line (resolution 1 us)
  std::string interface;  // e.g. "can0"
  can_frame frame{};
  int line = 0;           // 1-based line number in its file
};

// Largest seconds part of a timestamp: (kMaxCandumpSeconds + 0.999999) s still fits Nanoseconds (int64 ns,
// about year 2262); a larger timestamp is a bad line.
inline constexpr std::uint64_t kMaxCandumpSeconds = 9'223'372'035;

// nullopt with `error` describing what is wrong (for an empty/comment line: nullopt, empty error).
std::optional<CandumpRecord> parse_candump_line(std::string_view line, std::string& error);
std::string format_candump_line(Nanoseconds time, std::string_view interface, const can_frame& frame);

struct CandumpLog {
  std::vector<CandumpRecord> records;
  std::vector<std::string> errors;  // "line N: what"
};
CandumpLog read_candump_log(std::istream& in);
// Throws std::runtime_error when the file cannot be opened.
CandumpLog read_candump_file(const std::string& path);

// Appends every frame sent through it to a log, stamped with the injected clock plus `epoch_offset`:
// candump stamps wall-clock time since the Unix epoch, so a live recording on the monotonic clock
// passes (wall clock - monotonic clock) at start; a replay already runs on the log's own time (0).
class CandumpWriter final : public CanFrameSink {
 public:
  CandumpWriter(std::ostream& out, const Clock& clock, std::string interface,
                Nanoseconds epoch_offset = Nanoseconds::zero());
  bool send(const can_frame& frame) override;
  std::uint64_t lines_written() const { return lines_; }

 private:
  std::ostream& out_;
  const Clock& clock_;
  std::string interface_;
  Nanoseconds epoch_offset_;
  std::uint64_t lines_ = 0;
};

// Sends every frame to two sinks (the bus and a recording); true when the first accepted it.
class TeeSink final : public CanFrameSink {
 public:
  TeeSink(CanFrameSink& primary, CanFrameSink* copy) : primary_(primary), copy_(copy) {}
  bool send(const can_frame& frame) override {
    if (copy_ != nullptr) copy_->send(frame);
    return primary_.send(frame);
  }

 private:
  CanFrameSink& primary_;
  CanFrameSink* copy_;
};

}  // namespace spread::isobus::can
