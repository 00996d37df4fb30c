// Fuzz harness: the device descriptor object pool reader (isobus/ddop), as a task controller
// meets a pool from an unknown implement. Input: the pool's bytes.
// Checked: a pool the reader accepts is written back byte for byte (reader and writer are each other's
// inverse), and what it refuses comes with a reason.
#include <cstddef>
#include <cstdint>
#include <span>

#include "fuzz/fuzz_input.hpp"
#include "isobus/ddop.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  constexpr const char* kHarness = "fuzz_ddop";
  namespace iso = spread::isobus;
  const std::span<const std::uint8_t> bytes(data, size);
  const iso::DdopParseResult result = iso::parse_ddop(bytes);
  if (!result.pool) {
    if (result.error.empty()) spread::fuzz::fail(kHarness, "refused without a reason");
    return 0;
  }
  const std::vector<std::uint8_t> written = iso::write_ddop(*result.pool);
  if (written.size() != size || !std::equal(written.begin(), written.end(), bytes.begin())) {
    spread::fuzz::fail(kHarness, "an accepted pool does not write back to the same bytes");
  }
  return 0;
}
