#pragma once
// Provenance hash of a scene text: FNV-1a 64 as 16 lower-case hex digits (Run::scene_hash).
// Not cryptographic: it tells whether two runs came from the same scene text, nothing more.
#include <string>
#include <string_view>

namespace spread::tables {

std::string fnv1a64_hex(std::string_view text);

}  // namespace spread::tables
