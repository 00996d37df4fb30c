// Writer → reader round trip, the record codec, and the writer's rules (replace flag, foreign files).
#include <gtest/gtest.h>

#include <bit>
#include <cstring>
#include <filesystem>
#include <memory_resource>

#include "libspread/io/tables/machine_schema.hpp"
#include "libspread/io/tables/sample_codec.hpp"
#include "libspread/io/tables/table_reader.hpp"
#include "libspread/io/tables/table_writer.hpp"
#include "table_fixtures.hpp"
#include "tests/support/temp_path.hpp"

namespace spread::tables {
namespace {

using spread::testing::TempPath;

bool same_bits(const LaunchSample& a, const LaunchSample& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(TableFormat, SampleIsTwelvePackedFloats) {
  static_assert(sizeof(LaunchSample) == kSampleFloats * sizeof(float));
  EXPECT_EQ(kSampleBytes, 48u);
}

TEST(TableFormat, EncodesLittleEndianExplicitly) {
  LaunchSample s{};
  s.x_m = 1.0f;  // 0x3f800000 → bytes 00 00 80 3f
  s.mass_kg = -2.0f;  // 0xc0000000
  const std::vector<std::uint8_t> bytes = encode_samples(std::span<const LaunchSample>(&s, 1));
  ASSERT_EQ(bytes.size(), kSampleBytes);
  EXPECT_EQ(bytes[0], 0x00);
  EXPECT_EQ(bytes[2], 0x80);
  EXPECT_EQ(bytes[3], 0x3f);
  EXPECT_EQ(bytes[47], 0xc0);
  const std::vector<LaunchSample> back = decode_samples(bytes);
  ASSERT_EQ(back.size(), 1u);
  EXPECT_TRUE(same_bits(back[0], s));
}

TEST(TableRoundTrip, EverythingWrittenIsReadBack) {
  TempPath file("roundtrip");
  spread::testing::write_sample_table(file.path(), 100);
  const TableContents contents = read_table_file(file.path());

  const Machine expected_machine = spread::testing::sample_machine();
  for (const MachineColumn& c : kMachineColumns) {  // every column the schema lists
    switch (c.kind) {
      case MachineColumn::Kind::kText: EXPECT_EQ(contents.machine.*c.text, expected_machine.*c.text) << c.name; break;
      case MachineColumn::Kind::kReal: EXPECT_EQ(contents.machine.*c.real, expected_machine.*c.real) << c.name; break;
      case MachineColumn::Kind::kInteger:
        EXPECT_EQ(contents.machine.*c.integer, expected_machine.*c.integer) << c.name;
        break;
    }
  }

  ASSERT_EQ(contents.materials.size(), 2u);
  EXPECT_EQ(contents.materials[0].name, "A");
  EXPECT_EQ(contents.materials[1].name, "B");
  EXPECT_EQ(contents.materials[1].friction_wall, 0.6);
  EXPECT_EQ(contents.materials[0].youngs_modulus_pa, 5e7);
  EXPECT_EQ(contents.materials[0].rolling_friction, 0.05);

  ASSERT_EQ(contents.runs.size(), 3u);  // sorted by (material, rpm)
  EXPECT_EQ(contents.runs[0].material, "A");
  EXPECT_EQ(contents.runs[0].rpm, 450.0);
  EXPECT_EQ(contents.runs[1].rpm, 600.0);
  EXPECT_EQ(contents.runs[2].material, "B");
  const tables::Run expected = spread::testing::sample_run("A", 600.0, 100);
  const tables::Run& run = contents.runs[1];
  ASSERT_EQ(run.samples.size(), expected.samples.size());
  for (std::size_t k = 0; k < run.samples.size(); ++k) EXPECT_TRUE(same_bits(run.samples[k], expected.samples[k])) << k;
  EXPECT_EQ(run.source, expected.source);
  EXPECT_EQ(run.scene_hash, expected.scene_hash);
  EXPECT_EQ(run.scene_text, expected.scene_text);
  EXPECT_EQ(run.effects, expected.effects);
  EXPECT_EQ(run.dt_contact_s, expected.dt_contact_s);
  EXPECT_EQ(run.dt_flight_s, expected.dt_flight_s);
  EXPECT_EQ(run.particle_count, expected.particle_count);
  EXPECT_EQ(run.software_version, expected.software_version);
  EXPECT_EQ(run.created_utc, expected.created_utc);
  EXPECT_EQ(run.stats_json, expected.stats_json);
  EXPECT_EQ(run.convergence_json, expected.convergence_json);
}

// Counts what a reader asks of a memory resource.
class CountingMemory final : public std::pmr::memory_resource {
 public:
  int allocations = 0;
  std::size_t bytes = 0;

 private:
  void* do_allocate(std::size_t size, std::size_t alignment) override {
    ++allocations;
    bytes += size;
    return std::pmr::new_delete_resource()->allocate(size, alignment);
  }
  void do_deallocate(void* p, std::size_t size, std::size_t alignment) override {
    std::pmr::new_delete_resource()->deallocate(p, size, alignment);
  }
  bool do_is_equal(const std::pmr::memory_resource& other) const noexcept override { return this == &other; }
};

// Read with a sample memory, every run's samples lie in one block from it, run after run, bit for bit the
// samples read run by run; the block is reserved once from the declared counts.
TEST(TableRoundTrip, PooledSamplesAreTheRunsInOneBlock) {
  TempPath file("pooled");
  spread::testing::write_sample_table(file.path(), 100);
  const TableContents plain = read_table_file(file.path());
  CountingMemory memory;
  const TableContents pooled = read_table_file(file.path(), &memory);
  ASSERT_EQ(pooled.runs.size(), plain.runs.size());
  ASSERT_EQ(pooled.pooled_offset.size(), plain.runs.size() + 1);
  EXPECT_EQ(pooled.pooled_offset.front(), 0u);
  EXPECT_EQ(pooled.pooled_offset.back(), pooled.pooled_samples.size());
  for (std::size_t k = 0; k < plain.runs.size(); ++k) {
    EXPECT_TRUE(pooled.runs[k].samples.empty());
    const std::size_t begin = pooled.pooled_offset[k];
    ASSERT_EQ(pooled.pooled_offset[k + 1] - begin, plain.runs[k].samples.size()) << k;
    for (std::size_t i = 0; i < plain.runs[k].samples.size(); ++i) {
      ASSERT_TRUE(same_bits(pooled.pooled_samples[begin + i], plain.runs[k].samples[i])) << k << " " << i;
    }
  }
  EXPECT_EQ(memory.allocations, 1);
  EXPECT_EQ(memory.bytes, pooled.pooled_samples.size() * sizeof(LaunchSample));
}

// A damaged sample count cannot make the pooled read reserve more than the file could hold, nor overflow:
// the run is refused as damaged, naming it.
TEST(TableRoundTrip, PooledReadOfAHugeDeclaredCountIsCorruptNotOutOfMemory) {
  TempPath file("pooled_huge");
  spread::testing::write_sample_table(file.path(), 100);
  spread::testing::raw_exec(file.path(), "UPDATE runs SET sample_count = 4611686018427387904 WHERE rpm = 600");
  CountingMemory memory;
  try {
    read_table_file(file.path(), &memory);
    ADD_FAILURE() << "read";
  } catch (const TableError& e) {
    EXPECT_EQ(e.kind(), TableErrorKind::kCorrupt) << e.what();
    EXPECT_NE(std::string(e.what()).find("run A @ 600"), std::string::npos) << e.what();
  }
  EXPECT_LE(memory.bytes, std::filesystem::file_size(file.path()));
}

TEST(TableWriter, SecondWriteOfARunNeedsReplace) {
  TempPath file("replace");
  spread::testing::write_sample_table(file.path(), 8);
  TableWriter writer(file.path());  // reopen an existing table of ours
  EXPECT_TRUE(writer.has_run("A", 450.0));
  EXPECT_FALSE(writer.has_run("A", 500.0));
  tables::Run changed = spread::testing::sample_run("A", 450.0, 5);
  EXPECT_THROW(writer.write_run(changed), RunExistsError);
  EXPECT_EQ(read_table_file(file.path()).runs[0].samples.size(), 8u);  // untouched
  writer.write_run(changed, /*replace=*/true);
  const TableContents contents = read_table_file(file.path());
  ASSERT_EQ(contents.runs.size(), 3u);
  EXPECT_EQ(contents.runs[0].samples.size(), 5u);
}

TEST(TableWriter, RefusesRunOfUnknownMaterialAndEmptyRun) {
  TempPath file("unknown_material");
  spread::testing::write_sample_table(file.path(), 4);
  TableWriter writer(file.path());
  EXPECT_THROW(writer.write_run(spread::testing::sample_run("C", 450.0, 4)), std::invalid_argument);
  EXPECT_THROW(writer.write_run(spread::testing::sample_run("A", 700.0, 0)), std::invalid_argument);
  EXPECT_EQ(read_table_file(file.path()).runs.size(), 3u);
}

TEST(TableWriter, RefusesGarbageFileAndLeavesItByteIdentical) {
  TempPath file("writer_garbage");
  std::vector<char> garbage(3000);
  for (std::size_t i = 0; i < garbage.size(); ++i) garbage[i] = static_cast<char>((i * 131 + 7) % 251);
  spread::testing::write_bytes(file.path(), garbage);
  try {
    TableWriter writer(file.path());
    FAIL() << "writer accepted a garbage file";
  } catch (const TableError& e) {
    EXPECT_EQ(e.kind(), TableErrorKind::kNotOurs);
    EXPECT_NE(std::string(e.what()).find(file.path()), std::string::npos);
  }
  EXPECT_EQ(spread::testing::file_bytes(file.path()), garbage);
}

}  // namespace
}  // namespace spread::tables
