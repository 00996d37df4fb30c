#include "lookup_builder/run_message.hpp"

#include <bit>
#include <cstring>
#include <stdexcept>
#include <string>

#include "libspread/io/tables/run_schema.hpp"
#include "libspread/io/tables/sample_codec.hpp"

namespace spread::lookup {
namespace {

constexpr char kMagic[] = "SPRUN2";
constexpr std::size_t kMagicBytes = sizeof kMagic - 1;

class Writer {
 public:
  void u64(std::uint64_t v) {
    for (int i = 0; i < 8; ++i) bytes.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  }
  void f64(double v) { u64(std::bit_cast<std::uint64_t>(v)); }
  void text(const std::string& s) {
    u64(s.size());
    bytes.insert(bytes.end(), s.begin(), s.end());
  }
  void raw(std::span<const std::uint8_t> b) {
    u64(b.size());
    bytes.insert(bytes.end(), b.begin(), b.end());
  }
  std::vector<std::uint8_t> bytes;
};

class Reader {
 public:
  explicit Reader(std::span<const std::uint8_t> b) : bytes_(b) {}
  std::uint64_t u64() {
    need(8);
    std::uint64_t v = 0;
    for (int i = 0; i < 8; ++i) v |= static_cast<std::uint64_t>(bytes_[pos_ + static_cast<std::size_t>(i)]) << (8 * i);
    pos_ += 8;
    return v;
  }
  double f64() { return std::bit_cast<double>(u64()); }
  std::string text() {
    const std::size_t n = size();
    std::string s(reinterpret_cast<const char*>(bytes_.data() + pos_), n);
    pos_ += n;
    return s;
  }
  std::span<const std::uint8_t> raw() {
    const std::size_t n = size();
    const auto out = bytes_.subspan(pos_, n);
    pos_ += n;
    return out;
  }
  void magic() {
    need(kMagicBytes);
    if (std::memcmp(bytes_.data(), kMagic, kMagicBytes) != 0) fail("bad magic");
    pos_ += kMagicBytes;
  }
  void finish() const {
    if (pos_ != bytes_.size()) fail(std::to_string(bytes_.size() - pos_) + " trailing bytes");
  }

 private:
  std::size_t size() {
    const std::uint64_t n = u64();
    if (n > bytes_.size() - pos_) fail("length " + std::to_string(n) + " beyond the end");
    return static_cast<std::size_t>(n);
  }
  void need(std::size_t n) const {
    if (bytes_.size() - pos_ < n) fail("truncated");
  }
  [[noreturn]] static void fail(const std::string& why) {
    throw std::invalid_argument("serialised run: " + why);
  }
  std::span<const std::uint8_t> bytes_;
  std::size_t pos_ = 0;
};

}  // namespace

// The fields in the order of tables::kRunColumns (run_schema.hpp); of the samples' four columns only the
// records themselves (their count, layout and record size follow from them).
std::vector<std::uint8_t> serialise_run(const tables::Run& run) {
  using Kind = tables::RunColumn::Kind;
  Writer w;
  w.bytes.assign(kMagic, kMagic + kMagicBytes);
  for (const tables::RunColumn& column : tables::kRunColumns) {
    switch (column.kind) {
      case Kind::kText: w.text(run.*column.text); break;
      case Kind::kReal: w.f64(run.*column.real); break;
      case Kind::kInteger: w.u64(static_cast<std::uint64_t>(run.*column.integer)); break;
      case Kind::kSamples: w.raw(tables::encode_samples(run.samples)); break;
      case Kind::kSampleCount:
      case Kind::kRecordLayout:
      case Kind::kRecordBytes: break;
    }
  }
  return std::move(w.bytes);
}

tables::Run deserialise_run(std::span<const std::uint8_t> bytes) {
  using Kind = tables::RunColumn::Kind;
  Reader r(bytes);
  r.magic();
  tables::Run run;
  for (const tables::RunColumn& column : tables::kRunColumns) {
    switch (column.kind) {
      case Kind::kText: run.*column.text = r.text(); break;
      case Kind::kReal: run.*column.real = r.f64(); break;
      case Kind::kInteger: run.*column.integer = static_cast<std::int64_t>(r.u64()); break;
      case Kind::kSamples: {
        const auto samples = r.raw();
        if (samples.size() % tables::kSampleBytes != 0) {
          throw std::invalid_argument("serialised run: sample bytes not a multiple of the record size");
        }
        run.samples = tables::decode_samples(samples);
        break;
      }
      case Kind::kSampleCount:
      case Kind::kRecordLayout:
      case Kind::kRecordBytes: break;
    }
  }
  r.finish();
  return run;
}

// A job's runs: their count, then each serialised run as a length and its bytes.
std::vector<std::uint8_t> serialise_runs(const std::vector<tables::Run>& runs) {
  Writer w;
  w.u64(runs.size());
  for (const tables::Run& run : runs) w.raw(serialise_run(run));
  return std::move(w.bytes);
}

std::vector<tables::Run> deserialise_runs(std::span<const std::uint8_t> bytes) {
  Reader r(bytes);
  const std::uint64_t count = r.u64();
  std::vector<tables::Run> runs;
  for (std::uint64_t k = 0; k < count; ++k) runs.push_back(deserialise_run(r.raw()));
  r.finish();
  return runs;
}

}  // namespace spread::lookup
