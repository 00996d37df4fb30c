#pragma once
// A finished run as a byte buffer, for sending it from an MPI worker to the writing rank 0.
// Layout: magic "SPRUN1", then every Run field in declaration order — strings as u64 length + bytes,
// doubles as their IEEE-754 bits in u64, integers as u64, all little-endian — and the samples in the
// table's own float32 record codec (sample_codec.hpp). Hosts of different byte order interoperate.
#include <cstdint>
#include <span>
#include <vector>

#include "libspread/io/tables/table_format.hpp"

namespace spread::lookup {

std::vector<std::uint8_t> serialise_run(const tables::Run& run);

// Throws std::invalid_argument for a buffer that is not a whole serialised run.
tables::Run deserialise_run(std::span<const std::uint8_t> bytes);

// The runs of one job (one material's run, or a blend's run per component): their count (u64), then
// each serialised run as u64 length + bytes. Throws std::invalid_argument as deserialise_run.
std::vector<std::uint8_t> serialise_runs(const std::vector<tables::Run>& runs);
std::vector<tables::Run> deserialise_runs(std::span<const std::uint8_t> bytes);

}  // namespace spread::lookup
