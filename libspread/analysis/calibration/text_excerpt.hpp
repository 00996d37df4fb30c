#pragma once
// Quoting a file's text in a one-line message. A tray file comes from anywhere (a spreadsheet, a logger,
// a mistaken path), so what an error quotes from it is bounded and printable: a 5 MB cell must not
// become a 5 MB stderr line, and bytes of a binary file must not reach the terminal, where control
// bytes can move the cursor or change its state.
#include <cstddef>
#include <string>
#include <string_view>

namespace spread::calibration {

// Characters of a cell or line an error quotes; the cut is marked with "…".
inline constexpr std::size_t kExcerptCharacters = 60;

// `text` as a message may show it: control bytes, DEL and bytes that are not part of valid UTF-8
// written as \xNN (tab as \t), valid UTF-8 kept (a "°" or "ä" in a header), cut after
// `max_characters` shown characters (an escape counts as one) with "…" appended.
std::string excerpt(std::string_view text, std::size_t max_characters = kExcerptCharacters);

// Whether the start of a file is binary rather than text: a NUL byte, or more than 1 in 10 bytes that
// are control bytes other than tab, CR, LF and form feed, within the first `probe_bytes`. Text a
// spreadsheet exports has neither (UTF-16, which has NULs, is recognised before this by its BOM).
bool looks_binary(std::string_view text, std::size_t probe_bytes = 4096);

}  // namespace spread::calibration
