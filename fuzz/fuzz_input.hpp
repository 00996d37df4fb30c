#pragma once
// Helpers shared by the fuzz harnesses: reading typed values off the front of the fuzzer's bytes.
// Header-only so each harness stays one translation unit (libFuzzer links one harness per binary).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <string_view>

namespace spread::fuzz {

// Consumes bytes front to back; once exhausted every read returns zeros, so a short input is still a
// complete (if dull) test case rather than a rejected one.
class FuzzInput {
 public:
  FuzzInput(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}

  std::size_t remaining() const { return size_ - offset_; }

  template <typename T>
  T take() {
    T value{};
    const std::size_t n = remaining() < sizeof(T) ? remaining() : sizeof(T);
    if (n > 0) std::memcpy(&value, data_ + offset_, n);
    offset_ += n;
    return value;
  }

  // A double from 8 raw bytes: every bit pattern, NaNs and infinities included.
  double take_raw_double() { return take<double>(); }

  std::string take_string(std::size_t max_length) {
    const std::size_t wanted = take<std::uint8_t>();
    const std::size_t length = wanted < max_length ? wanted : max_length;
    const std::size_t n = length < remaining() ? length : remaining();
    std::string out(reinterpret_cast<const char*>(data_ + offset_), n);
    offset_ += n;
    return out;
  }

  std::string_view rest() {
    std::string_view out(reinterpret_cast<const char*>(data_ + offset_), remaining());
    offset_ = size_;
    return out;
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t offset_ = 0;
};

// Stops the run the way libFuzzer recognises as a crash, with a message saying which invariant broke.
[[noreturn]] inline void fail(const char* harness, const std::string& what) {
  std::fprintf(stderr, "%s: invariant broken: %s\n", harness, what.c_str());
  std::abort();
}

}  // namespace spread::fuzz
