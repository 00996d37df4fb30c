#include "libspread/io/tables/scene_hash.hpp"

#include <cstdint>

namespace spread::tables {

std::string fnv1a64_hex(std::string_view text) {
  // FNV-1a, 64-bit offset basis and prime (Fowler, Noll, Vo).
  std::uint64_t hash = 0xcbf29ce484222325ull;
  for (char c : text) {
    hash ^= static_cast<std::uint8_t>(c);
    hash *= 0x100000001b3ull;
  }
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string hex(16, '0');
  for (int i = 15; i >= 0; --i) {
    hex[static_cast<std::size_t>(i)] = kDigits[hash & 0xfu];
    hash >>= 4;
  }
  return hex;
}

}  // namespace spread::tables
