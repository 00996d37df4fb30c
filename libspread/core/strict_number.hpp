#pragma once
// The one strict reading of a number from text, shared by command-line options, list options and table
// cells: the whole text, spaces or tabs around it allowed, must be one finite decimal number — no
// trailing characters, no "inf" or "nan", no hexadecimal, no dependence on the locale (std::from_chars).
// A leading '+' is accepted, as std::stod accepted it.
#include <charconv>
#include <cmath>
#include <cstddef>
#include <optional>
#include <string_view>
#include <system_error>
#include <vector>

namespace spread {

inline std::optional<double> parse_finite_number(std::string_view text) {
  const auto blank = [](char c) { return c == ' ' || c == '\t'; };
  while (!text.empty() && blank(text.front())) text.remove_prefix(1);
  while (!text.empty() && blank(text.back())) text.remove_suffix(1);
  if (text.size() > 1 && text.front() == '+' && text[1] != '-' && text[1] != '+') text.remove_prefix(1);
  double value = 0.0;
  const char* end = text.data() + text.size();
  const auto result = std::from_chars(text.data(), end, value);
  if (text.empty() || result.ec != std::errc{} || result.ptr != end || !std::isfinite(value)) return std::nullopt;
  return value;
}

// Items separated by commas ("12,15,18"; an empty text has none), each parse_finite_number. Returns false
// at the first item that is not one (an empty item included, as in "12,,15" or "12,"), which `bad_item`
// then holds; `values` holds the items before it.
inline bool parse_number_list(std::string_view text, std::vector<double>& values, std::string_view& bad_item) {
  values.clear();
  if (text.empty()) return true;
  for (std::size_t start = 0;;) {
    const std::size_t comma = text.find(',', start);
    const std::string_view item = text.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start);
    const std::optional<double> value = parse_finite_number(item);
    if (!value) {
      bad_item = item;
      return false;
    }
    values.push_back(*value);
    if (comma == std::string_view::npos) return true;
    start = comma + 1;
  }
}

}  // namespace spread
