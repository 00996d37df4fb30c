// Fuzz harness: the launch-table loader (libspread/io/tables read_table_file) on arbitrary file bytes.
// Seeds are real table files, so mutations reach past the SQLite header into records and BLOBs.
// Contract checked: read_table_file returns contents or throws TableError — never another exception,
// never a crash — and accepted contents keep the reader's promises (runs sorted, non-empty samples,
// every run's material described).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz/fuzz_input.hpp"
#include "fuzz/temp_input_file.hpp"
#include "libspread/io/tables/table_reader.hpp"

namespace {

constexpr const char* kHarness = "fuzz_table_loader";

void check_contents(const spread::tables::TableContents& contents) {
  if (contents.runs.empty()) spread::fuzz::fail(kHarness, "accepted a table without runs");
  for (const auto& run : contents.runs) {
    if (run.samples.empty()) spread::fuzz::fail(kHarness, "accepted a run without samples");
    const bool described = std::any_of(contents.materials.begin(), contents.materials.end(),
                                       [&](const spread::tables::Material& m) { return m.name == run.material; });
    if (!described) spread::fuzz::fail(kHarness, "accepted a run of an undescribed material " + run.material);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static spread::fuzz::TempInputFile file("spread_fuzz_table");
  if (!file.write(data, size)) spread::fuzz::fail(kHarness, "cannot write " + file.path());
  try {
    check_contents(spread::tables::read_table_file(file.path()));
  } catch (const spread::tables::TableError&) {
    // The documented refusal, with its kind.
  }
  return 0;
}
