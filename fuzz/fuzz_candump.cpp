// Fuzz harness: the candump log reader (isobus/can/candump_log), used to replay recorded bus
// traffic into the ECU. Input: log text. Checked: no crash; every line is a record or an error; a
// parsed frame formats back to a line that parses to the same frame.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <sstream>
#include <string>

#include "fuzz/fuzz_input.hpp"
#include "isobus/can/candump_log.hpp"

namespace {

constexpr const char* kHarness = "fuzz_candump";
namespace can = spread::isobus::can;

bool same_frame(const can_frame& a, const can_frame& b) {
  return a.can_id == b.can_id && a.len == b.len && std::memcmp(a.data, b.data, a.len) == 0;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  const can::CandumpLog log = can::read_candump_log(in);
  for (const can::CandumpRecord& record : log.records) {
    if (record.frame.len > CAN_MAX_DLEN) spread::fuzz::fail(kHarness, "parsed a frame longer than 8 bytes");
    const std::string line = can::format_candump_line(record.time, record.interface, record.frame);
    std::string error;
    const auto again = can::parse_candump_line(line, error);
    if (!again) spread::fuzz::fail(kHarness, "formatted line does not parse: " + line + " (" + error + ")");
    if (!same_frame(again->frame, record.frame)) spread::fuzz::fail(kHarness, "frame does not round-trip: " + line);
    if (again->time != record.time) spread::fuzz::fail(kHarness, "time does not round-trip: " + line);
  }
  return 0;
}
