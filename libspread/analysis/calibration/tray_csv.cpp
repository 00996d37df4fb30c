#include "libspread/analysis/calibration/tray_csv.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>

#include "libspread/analysis/calibration/pass_totals.hpp"
#include "libspread/analysis/calibration/text_excerpt.hpp"
#include "libspread/core/strict_number.hpp"

namespace spread::calibration {
namespace {

// Spacing and centre-line alignment tolerance: tray positions are measured with a tape, to the cm at
// best, but 0.5 m trays laid 1 cm off still collect what their nominal place does to within a few %.
constexpr double kPositionTolerance_m = 0.011;

std::string trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  const auto last = s.find_last_not_of(" \t\r");
  return std::string(s.substr(first, last - first + 1));
}

// One line split into cells, RFC 4180 style as spreadsheets export them: a cell may be quoted
// ("3", "pass 1_g"), a quoted cell may hold the separator or '#', and "" inside quotes is one quote.
// Whitespace around a cell (quoted or not) is dropped. A quoted cell cannot span lines here (a tray
// test has no use for it): an unterminated quote is an error, as are text after a closing quote and a
// quote inside an unquoted cell. `problem` is set and the cells are empty when the line is malformed.
struct Cells {
  std::vector<std::string> text;
  std::vector<bool> quoted;
};
Cells split(std::string_view line, char separator, std::string& problem) {
  Cells cells;
  std::size_t i = 0;
  const auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r'; };
  while (true) {
    while (i < line.size() && line[i] != separator && blank(line[i])) ++i;
    std::string cell;
    bool quoted = false;
    if (i < line.size() && line[i] == '"') {
      quoted = true;
      const std::size_t opened = i++;
      bool closed = false;
      while (i < line.size()) {
        if (line[i] == '"') {
          if (i + 1 < line.size() && line[i + 1] == '"') {
            cell += '"';
            i += 2;
            continue;
          }
          closed = true;
          ++i;
          break;
        }
        cell += line[i++];
      }
      if (!closed) {
        problem = "unterminated quote in cell " + std::to_string(cells.text.size() + 1) + " (opened at column " +
                  std::to_string(opened + 1) + "; a quoted cell must close on the same line)";
        return {};
      }
      while (i < line.size() && line[i] != separator && blank(line[i])) ++i;
      if (i < line.size() && line[i] != separator) {
        problem = "cell " + std::to_string(cells.text.size() + 1) + ": text after the closing quote";
        return {};
      }
    } else {
      const std::size_t begin = i;
      while (i < line.size() && line[i] != separator) {
        if (line[i] == '"') {
          problem = "cell " + std::to_string(cells.text.size() + 1) +
                    ": a quote inside an unquoted cell (quote the whole cell, and double a quote inside it)";
          return {};
        }
        ++i;
      }
      cell = trim(line.substr(begin, i - begin));
    }
    cells.text.push_back(std::move(cell));
    cells.quoted.push_back(quoted);
    if (i >= line.size()) break;
    ++i;  // the separator; a separator at the end leaves a trailing empty cell
  }
  return cells;
}

// The line without its comment: from the first '#' outside quotes.
std::string_view strip_comment(std::string_view line) {
  bool in_quotes = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    if (line[i] == '"') in_quotes = !in_quotes;  // "" inside quotes toggles twice: no change
    else if (line[i] == '#' && !in_quotes) return line.substr(0, i);
  }
  return line;
}

// The separator a header uses: ';' or tab (outside quotes) when there, else ','.
char separator_of(std::string_view header) {
  bool in_quotes = false, semicolon = false, tab = false, comma = false;
  for (char c : header) {
    if (c == '"') in_quotes = !in_quotes;
    else if (!in_quotes) {
      semicolon |= c == ';';
      tab |= c == '\t';
      comma |= c == ',';
    }
  }
  if (semicolon) return ';';
  if (tab && !comma) return '\t';
  return ',';
}

bool ends_with(const std::string& s, std::string_view suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

std::string format_m(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3f", value);
  return text;
}

// What the reader does with a header's column.
enum class ColumnRole { kPosition, kGrams, kKilograms, kIgnored, kUnnamed };

// The header name lower-cased, with a unit in parentheses or brackets as a suffix: "Pass2 (g)" → "pass2_g".
std::string normalised_name(const std::string& name) {
  std::string n = lower(trim(name));
  const char close = n.empty() ? '\0' : n.back();
  const char open = close == ')' ? '(' : close == ']' ? '[' : '\0';
  const auto at = open == '\0' ? std::string::npos : n.rfind(open);
  if (at != std::string::npos) {
    const std::string base = trim(std::string_view(n).substr(0, at));
    const std::string unit = trim(std::string_view(n).substr(at + 1, n.size() - at - 2));
    n = base.empty() ? unit : base + "_" + unit;
  }
  return n;
}

// The role of a column, or a TrayCsvError at the header's line naming a column the reader will not take.
ColumnRole column_role(const std::string& name, const std::string& source, int line) {
  const std::string n = normalised_name(name);
  if (n.empty()) return ColumnRole::kUnnamed;
  if (n == "position_m" || n == "x_m") return ColumnRole::kPosition;
  if (ends_with(n, "_kg")) return ColumnRole::kKilograms;
  if (ends_with(n, "_g")) return ColumnRole::kGrams;
  // Tray numbers and notes as spreadsheets name them ("Tray #", "tray no.", "Nr"): letters and digits only.
  std::string key;
  for (const char c : n) {
    if (std::isalnum(static_cast<unsigned char>(c))) key += c;
  }
  static const std::set<std::string> kIgnored{"", "tray", "trayno", "traynr", "traynumber", "trayid", "no", "nr",
                                              "number", "id", "index", "note", "notes", "comment", "comments",
                                              "remark", "remarks"};
  if (kIgnored.count(key) > 0) return ColumnRole::kIgnored;
  const std::string quoted = "column '" + excerpt(name) + "'";
  const auto unit_at = n.rfind('_');
  const std::string unit = unit_at == std::string::npos ? std::string() : n.substr(unit_at + 1);
  static const std::set<std::string> kOtherMassUnits{"mg", "t", "lb", "lbs", "oz", "gr", "gram", "grams", "kilo",
                                                     "kilos", "kilogram", "kilograms", "kgs", "gm", "gms"};
  if (kOtherMassUnits.count(unit) > 0) {
    throw TrayCsvError(source, line,
                       quoted + ": mass in '" + excerpt(unit) + "' is not read — mass columns are in grams "
                       "(*_g or '(g)') or kilograms (*_kg or '(kg)'): convert the column and rename it");
  }
  const std::string base = unit_at == std::string::npos ? n : n.substr(0, unit_at);
  if (base == "position" || base == "x" || n == "position" || n == "x") {
    throw TrayCsvError(source, line,
                       quoted + ": positions are read in metres only — write them in metres and name the column "
                       "position_m");
  }
  throw TrayCsvError(source, line,
                     quoted + " is not one the reader knows, and no column is dropped unseen: position_m (or "
                     "x_m), mass columns *_g or *_kg (one per pass), or a tray number or notes column (tray, no, "
                     "id, notes); rename or delete it");
}

// The file's lines, ended by LF, CRLF or a CR alone.
class Lines {
 public:
  explicit Lines(std::string_view text) : text_(text) {}
  bool next(std::string_view& line) {
    if (at_ >= text_.size()) return false;
    const std::size_t end = text_.find_first_of("\r\n", at_);
    if (end == std::string_view::npos) {
      line = text_.substr(at_);
      at_ = text_.size();
      return true;
    }
    line = text_.substr(at_, end - at_);
    at_ = end + (text_[end] == '\r' && end + 1 < text_.size() && text_[end + 1] == '\n' ? 2 : 1);
    return true;
  }

 private:
  std::string_view text_;
  std::size_t at_ = 0;
};

// A UTF-16 file ("Unicode text") is text, but not what the reader takes: said so before its NUL bytes
// make it look binary. Anything else with NULs or many control bytes is not a tray test at all.
void require_text(std::string_view text, const std::string& source) {
  if (text.size() >= 2 && ((text[0] == '\xFF' && text[1] == '\xFE') || (text[0] == '\xFE' && text[1] == '\xFF'))) {
    throw TrayCsvError(source, 1, "the file is UTF-16 text (\"Unicode text\"): save it as CSV (UTF-8 or plain)");
  }
  if (looks_binary(text)) {
    throw TrayCsvError(source, 0,
                       "not a text file: binary content (a NUL or control bytes near the start) — give the tray "
                       "test saved as CSV");
  }
}

}  // namespace

TrayCsvError::TrayCsvError(const std::string& source, int line, const std::string& problem, ErrorKind kind)
    : Error(kind, source, source + ":" + (line > 0 ? std::to_string(line) + ": " : std::string(" ")) + problem),
      line_(line) {}

double TrayTest::total_mass_kg() const {
  double sum = 0.0;
  for (double m : mass_kg) sum += m;
  return sum;
}

int TrayTest::missing_trays() const {
  return static_cast<int>(std::count(missing.begin(), missing.end(), true));
}

std::vector<double> TrayTest::missing_positions_m() const {
  std::vector<double> positions;
  for (std::size_t i = 0; i < position_m.size() && i < missing.size(); ++i) {
    if (missing[i]) positions.push_back(position_m[i]);
  }
  return positions;
}

std::vector<double> TrayTest::partly_missing_positions_m() const {
  std::vector<double> positions;
  for (std::size_t i = 0; i < position_m.size() && i < missing.size(); ++i) {
    if (missing[i]) continue;
    for (const auto& pass : pass_mass_kg) {
      if (i < pass.size() && std::isnan(pass[i])) {
        positions.push_back(position_m[i]);
        break;
      }
    }
  }
  return positions;
}

TrayTest parse_tray_csv(std::string_view text, const std::string& source, const TrayCsvOptions& options) {
  TrayTest test;
  test.source = source;

  struct Column {
    std::size_t index;
    double to_kg;
  };
  std::size_t position_column = 0;
  bool have_position = false;
  std::vector<Column> mass_columns;
  std::vector<std::size_t> unnamed_columns;  // read only to check that they hold nothing
  std::size_t cell_count = 0;
  char separator = ',';
  bool have_header = false;
  std::vector<int> row_line;  // source line of each tray, for the spacing messages

  // Spreadsheets save "CSV UTF-8" with a byte-order mark: invisible in the header the error would quote.
  constexpr std::string_view kUtf8Bom = "\xEF\xBB\xBF";
  if (text.substr(0, kUtf8Bom.size()) == kUtf8Bom) text.remove_prefix(kUtf8Bom.size());
  require_text(text, source);
  Lines lines(text);
  std::string_view raw;
  int line_number = 0;
  while (lines.next(raw)) {
    ++line_number;
    const std::string line = trim(strip_comment(raw));
    if (line.empty()) continue;
    std::string problem;

    if (!have_header) {
      have_header = true;
      separator = separator_of(line);
      const std::vector<std::string> names = split(line, separator, problem).text;
      if (!problem.empty()) throw TrayCsvError(source, line_number, "header: " + problem);
      cell_count = names.size();
      for (std::size_t i = 0; i < names.size(); ++i) {
        switch (column_role(names[i], source, line_number)) {
          case ColumnRole::kPosition:
            if (have_position) {
              throw TrayCsvError(source, line_number, "two position columns ('" + excerpt(names[i]) + "')");
            }
            have_position = true;
            position_column = i;
            break;
          case ColumnRole::kKilograms:
            mass_columns.push_back({i, 1.0});
            test.mass_columns.push_back(names[i]);
            break;
          case ColumnRole::kGrams:
            mass_columns.push_back({i, 1e-3});
            test.mass_columns.push_back(names[i]);
            break;
          case ColumnRole::kUnnamed:
            unnamed_columns.push_back(i);
            break;
          case ColumnRole::kIgnored:
            break;
        }
      }
      if (!have_position) {
        throw TrayCsvError(source, line_number,
                           "missing column position_m (tray centre in metres from the centre line); header is '" +
                               excerpt(line) + "'");
      }
      if (mass_columns.empty()) {
        throw TrayCsvError(source, line_number,
                           "missing mass column: name at least one column *_g (grams) or *_kg, e.g. mass_g or "
                           "pass1_g,pass2_g; header is '" + excerpt(line) + "'");
      }
      test.pass_mass_kg.resize(mass_columns.size());
      continue;
    }

    const Cells split_cells = split(line, separator, problem);
    if (!problem.empty()) throw TrayCsvError(source, line_number, problem);
    const std::vector<std::string>& cells = split_cells.text;
    if (cells.size() != cell_count) {
      // With ',' separators a decimal comma splits a number in two: more cells than the header names.
      const bool comma_hint = separator == ',' && cells.size() > cell_count;
      throw TrayCsvError(source, line_number,
                         "expected " + std::to_string(cell_count) + " cells as in the header, found " +
                             std::to_string(cells.size()) +
                             (comma_hint ? " (decimal commas? with ',' separators '0,221' is two cells: write "
                                           "0.221, or save the file with ';' separators)"
                                         : ""));
    }
    for (const std::size_t column : unnamed_columns) {
      if (!cells[column].empty()) {
        throw TrayCsvError(source, line_number,
                           "cell " + std::to_string(column + 1) + " '" + excerpt(cells[column]) +
                               "' is in a column without a name: name the column in the header, or delete it");
      }
    }
    auto number = [&](std::size_t column, const std::string& what) {
      std::string cell = trim(cells[column]);
      // A decimal comma ("0,221"), as spreadsheets in many locales export it next to ';' or tab
      // separators. Not with ',' separators: there "1,234" may be a thousands separator.
      if (separator != ',' && cell.find(',') != std::string::npos && cell.find('.') == std::string::npos &&
          cell.find(',') == cell.rfind(',')) {
        cell[cell.find(',')] = '.';
      }
      const std::optional<double> value = parse_finite_number(cell);
      if (!value) {
        const bool comma = separator == ',' && cell.find(',') != std::string::npos;
        throw TrayCsvError(source, line_number,
                           excerpt(what) + ": '" + excerpt(cells[column]) + "' is not a number" +
                               (comma ? " (decimal commas only in files separated by ';' or tab)" : ""));
      }
      return *value;
    };
    const double position = number(position_column, "position_m");
    if (!(std::abs(position) <= options.farthest_tray_m)) {
      char message[256];
      std::snprintf(message, sizeof message,
                    "position_m %.6g is %.6g m from the centre line: no spreader throws beyond about 50 m, and "
                    "trays are read up to %g m — position_m in centimetres or millimetres? it takes metres",
                    position, std::abs(position), options.farthest_tray_m);
      throw TrayCsvError(source, line_number, message);
    }
    double sum_kg = 0.0;
    int read = 0;
    for (std::size_t c = 0; c < mass_columns.size(); ++c) {
      const std::string& cell = cells[mass_columns[c].index];
      if (cell.empty() || lower(cell) == "na") {
        test.pass_mass_kg[c].push_back(std::numeric_limits<double>::quiet_NaN());
        ++test.missing_cells;
        continue;
      }
      const double mass = number(mass_columns[c].index, test.mass_columns[c]);
      if (mass < 0.0) {
        throw TrayCsvError(source, line_number, excerpt(test.mass_columns[c]) + ": negative mass " + excerpt(cell));
      }
      if (const std::string implausible = tray_mass_problem(mass, mass_columns[c].to_kg, test.mass_columns[c]);
          !implausible.empty()) {
        throw TrayCsvError(source, line_number, implausible);
      }
      test.pass_mass_kg[c].push_back(mass * mass_columns[c].to_kg);
      sum_kg += mass * mass_columns[c].to_kg;
      ++read;
    }
    if (!test.position_m.empty() && !(position > test.position_m.back())) {
      throw TrayCsvError(source, line_number,
                         "position_m " + excerpt(cells[position_column]) + " is not greater than the previous tray's " +
                             format_m(test.position_m.back()) + " (list the trays from left to right)");
    }
    test.position_m.push_back(position);
    test.mass_kg.push_back(read > 0 ? sum_kg / read : 0.0);
    test.missing.push_back(read == 0);
    row_line.push_back(line_number);
  }

  if (!have_header) throw TrayCsvError(source, 0, "empty file: no header and no trays");
  const int trays = static_cast<int>(test.position_m.size());
  const int minimum_trays = std::max(2, options.minimum_trays);
  if (trays < minimum_trays) {
    throw TrayCsvError(source, line_number,
                       "too few trays: " + std::to_string(trays) + " (need at least " +
                           std::to_string(minimum_trays) + ")");
  }

  const double spacing = test.position_m[1] - test.position_m[0];
  for (int k = 2; k < trays; ++k) {
    const auto ku = static_cast<std::size_t>(k);
    const double step = test.position_m[ku] - test.position_m[ku - 1];
    if (std::abs(step - spacing) > kPositionTolerance_m) {
      throw TrayCsvError(source, row_line[ku],
                         "non-uniform tray spacing: " + format_m(step) + " m from the previous tray, but " +
                             format_m(spacing) + " m between the first two (a missing tray? enter its row with NA as the mass)");
    }
  }
  test.tray_width_m = (test.position_m.back() - test.position_m.front()) / (trays - 1);
  if (!(test.tray_width_m >= options.narrowest_tray_m - 1e-12)) {
    throw TrayCsvError(source, row_line[1],
                       "the trays are " + format_m(test.tray_width_m) + " m apart: no collecting tray is narrower "
                       "than " + format_m(options.narrowest_tray_m) + " m — position_m in kilometres? it takes "
                       "metres");
  }

  // Symmetric layout: with an odd tray count the centres sit at multiples of the width, with an even
  // count midway between. Which of the two the first tray is on decides the parity.
  const double w = test.tray_width_m;
  const double phase = test.position_m.front() / w - std::floor(test.position_m.front() / w);  // [0, 1)
  const bool on_multiples = std::min(phase, 1.0 - phase) * w <= kPositionTolerance_m;
  const bool on_halves = std::abs(phase - 0.5) * w <= kPositionTolerance_m;
  if (options.centre_line_grid && !on_multiples && !on_halves) {
    throw TrayCsvError(source, row_line.front(),
                       "tray centres are not on the centre-line grid: with " + format_m(w) +
                           " m trays the centres must be at multiples of " + format_m(w) + " m or midway between "
                           "(measure position_m from the tractor centre line)");
  }
  const double half_extent = std::max(std::abs(test.position_m.front()), std::abs(test.position_m.back())) + 0.5 * w;
  int count = static_cast<int>(std::lround(2.0 * half_extent / w));
  if ((count % 2 == 1) != on_multiples) ++count;  // keep the parity of the grid the trays are on
  test.layout.tray_width_m = w;
  test.layout.tray_count = count;
  test.layout_mass_kg.assign(static_cast<std::size_t>(count), 0.0);
  test.layout_missing.assign(static_cast<std::size_t>(count), false);
  long first_index = 0;
  for (int k = 0; k < trays; ++k) {
    const auto ku = static_cast<std::size_t>(k);
    const long index = std::clamp(std::lround((test.position_m[ku] - test.layout.left_edge_m()) / w - 0.5), 0L,
                                  static_cast<long>(count - 1));
    if (k == 0) first_index = index;
    test.layout_mass_kg[static_cast<std::size_t>(index)] = test.mass_kg[ku];
    test.layout_missing[static_cast<std::size_t>(index)] = test.missing[ku];
  }
  test.padded_trays = count - trays;
  test.padded_left = static_cast<int>(first_index);
  if (test.missing_trays() > trays - minimum_trays) {
    throw TrayCsvError(source, 0,
                       std::to_string(test.missing_trays()) + " of " + std::to_string(trays) +
                           " trays are missing (NA or empty in every pass): need at least " +
                           std::to_string(minimum_trays) + " with a reading");
  }

  if (!(test.total_mass_kg() > 0.0)) throw TrayCsvError(source, 0, "no mass in any tray");
  std::vector<double> kg_per_unit;
  for (const Column& c : mass_columns) kg_per_unit.push_back(c.to_kg);
  if (const std::string problem = pass_totals_problem(test, kg_per_unit); !problem.empty()) {
    throw TrayCsvError(source, 0, problem);
  }
  return test;
}

TrayTest read_tray_csv(const std::string& path, const TrayCsvOptions& options) {
  namespace fs = std::filesystem;
  std::error_code ignored;
  const fs::file_status status = fs::status(path, ignored);
  if (fs::is_directory(status)) {
    throw TrayCsvError(path, 0, "is a directory, not a tray-test file", ErrorKind::kMissing);
  }
  char text[160];
  if (fs::is_regular_file(status)) {
    std::error_code error;
    const std::uintmax_t bytes = fs::file_size(path, error);
    if (!error && bytes > kLargestTrayFile_bytes) {
      std::snprintf(text, sizeof text, "the file is %.1f MB: a tray-test file is read up to %.0f MB (a tray test "
                    "is well under 1 MB) — is it the right file?", static_cast<double>(bytes) / 1e6,
                    static_cast<double>(kLargestTrayFile_bytes) / 1e6);
      throw TrayCsvError(path, 0, text);
    }
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw TrayCsvError(path, 0, "cannot open the file", ErrorKind::kMissing);
  // In blocks, so that a device or a growing file stops at the limit, and binary content at its first block.
  std::string content;
  std::vector<char> block(64 * 1024);
  while (in.read(block.data(), static_cast<std::streamsize>(block.size())) || in.gcount() > 0) {
    const bool first = content.empty();
    content.append(block.data(), static_cast<std::size_t>(in.gcount()));
    if (first) require_text(content, path);
    if (content.size() > kLargestTrayFile_bytes) {
      std::snprintf(text, sizeof text, "more than %.0f MB read: a tray-test file is read up to that (a tray "
                    "test is well under 1 MB) — is it the right file?", static_cast<double>(kLargestTrayFile_bytes) / 1e6);
      throw TrayCsvError(path, 0, text);
    }
  }
  if (in.bad()) throw TrayCsvError(path, 0, "cannot read the file", ErrorKind::kIo);
  return parse_tray_csv(content, path, options);
}

void write_tray_csv(const std::string& path, const std::vector<double>& position_m,
                    const std::vector<std::vector<double>>& pass_mass_g, const std::vector<std::string>& comments) {
  std::ofstream out(path, std::ios::trunc);
  if (!out) throw std::runtime_error(path + ": cannot write the tray-test file");
  for (const std::string& c : comments) out << "# " << c << "\n";
  out << "position_m";
  for (std::size_t p = 0; p < pass_mass_g.size(); ++p) out << ",pass" << p + 1 << "_g";
  out << "\n";
  char cell[48];
  for (std::size_t k = 0; k < position_m.size(); ++k) {
    std::snprintf(cell, sizeof cell, "%.3f", position_m[k]);
    out << cell;
    for (const auto& pass : pass_mass_g) {
      std::snprintf(cell, sizeof cell, ",%.3f", pass.at(k));
      out << cell;
    }
    out << "\n";
  }
  if (!out) throw std::runtime_error(path + ": write failed");
}

}  // namespace spread::calibration
