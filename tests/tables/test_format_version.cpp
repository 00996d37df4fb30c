// The table format's version moves with its schema: a change to the SQL schema or to the launch sample's
// record layout without a bump of kFormatVersion fails here. Readers refuse files of another version
// (TableErrorKind::kWrongVersion), so a changed schema under the old number would let an old reader take a
// new file for one it knows (or the reverse).
#include <gtest/gtest.h>

#include <cstdint>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "libspread/io/tables/row_checksum.hpp"
#include "libspread/io/tables/table_format.hpp"
#include "libspread/io/tables/table_schema.hpp"

namespace spread::tables {
namespace {

// Each format version with the fingerprint of its schema: when the test fails, bump kFormatVersion
// (table_format.hpp), say what changed in docs/table-format.md, and add the new version's line here.
const std::vector<std::pair<std::int32_t, std::string>> kVersionFingerprints = {
    {2, "da596ac83ac40dae"},
    {3, "71da013bf23cf39c"},
};

// CRC-64/XZ of the schema's statements (white space collapsed: layout changes nothing) and the record layout.
std::string schema_fingerprint() {
  std::istringstream words(detail::kSchemaSql);
  std::string word, flat;
  while (words >> word) flat += word + " ";
  Crc64 crc;
  crc.text(flat);
  crc.text(kSampleLayout);
  return crc.hex();
}

TEST(FormatVersion, TheSchemaIsTheOneItsVersionRecorded) {
  const std::string now = schema_fingerprint();
  const std::string hint = "the table schema's fingerprint is " + now + ": bump kFormatVersion (now " +
                           std::to_string(kFormatVersion) + ") and record {" + std::to_string(kFormatVersion + 1) +
                           ", \"" + now + "\"} in tests/tables/test_format_version.cpp";
  bool recorded = false;
  for (const auto& [version, fingerprint] : kVersionFingerprints) {
    if (version != kFormatVersion) continue;
    recorded = true;
    EXPECT_EQ(fingerprint, now) << "the schema changed under format version " << version << "; " << hint;
  }
  EXPECT_TRUE(recorded) << "format version " << kFormatVersion << " has no fingerprint recorded: add {"
                        << kFormatVersion << ", \"" << now << "\"}";
  // One fingerprint per version, and no two versions with one schema.
  for (std::size_t a = 0; a < kVersionFingerprints.size(); ++a) {
    for (std::size_t b = 0; b < a; ++b) {
      EXPECT_NE(kVersionFingerprints[a].first, kVersionFingerprints[b].first);
      EXPECT_NE(kVersionFingerprints[a].second, kVersionFingerprints[b].second);
    }
  }
}

}  // namespace
}  // namespace spread::tables
