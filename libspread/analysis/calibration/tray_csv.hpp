#pragma once
// Tray-test files (docs/field-calibration.md, "CSV format"): one row per tray across the driving
// direction (ISO 5690 / EN 13739: trays of 0.5 m, usually), a header naming the columns.
//
//   # comment lines and trailing comments start with '#'; blank lines are skipped
//   position_m,pass1_g,pass2_g,pass3_g
//   -12.25,10.2,9.8,10.5
//   ...
//
// Cells may be quoted as spreadsheets export them (RFC 4180: "3", a separator or '#' inside quotes, ""
// for a quote); with ';' or tab separators a decimal comma ("0,221") is read as a decimal point. A UTF-8
// byte-order mark (spreadsheets' "CSV UTF-8") is skipped. A mass cell that is empty or `NA` is a missing
// reading (a tray knocked over, a bag lost): a tray missing in every pass is left out of the CVs and the
// fit; a tray missing in some passes is the mean of the others.
// Lines end in LF, CRLF or CR alone (old Mac spreadsheets' "CSV (Macintosh)").
// Columns (separator ',' — or ';' / tab when the header uses it); a unit may also be written in
// parentheses or brackets, "pass2 (g)" being pass2_g:
//   position_m (or x_m)  tray centre, lateral, metres from the tractor centre line, left negative;
//   one or more mass columns named *_g (grams) or *_kg (kilograms): one per pass, averaged per tray;
//   a tray number or notes column (tray, no, nr, id, number, index, notes, comment) is ignored, as is
//   a column with neither name nor values (a trailing separator). Every other column is refused by
//   name, so a pass is never dropped unseen: a mass in another unit (pass1_lb), a position in another
//   unit (position_cm), an unknown name.
// Checks, each failure a TrayCsvError whose message starts "<file>:<line>: ": quoting closed on its
// line, nothing after a closing quote, no quote inside an unquoted cell; a header with a position
// and at least one mass column; every row the header's cell count; numbers that parse completely and are
// finite; masses >= 0 and within what a tray can catch (tray_plausibility.hpp); trays within
// TrayCsvOptions::farthest_tray_m of the centre line and at least narrowest_tray_m apart; positions strictly increasing with one uniform spacing (within 1 mm); the
// tray centres on the half-tray grid of the centre line (centres at multiples of the spacing, or
// midway between), so the pattern can be overlapped about x = 0; at least kMinimumTrays trays with a
// reading; some mass.
#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "libspread/core/error.hpp"
#include "libspread/analysis/calibration/tray_plausibility.hpp"
#include "libspread/analysis/metrics/metrics.hpp"

namespace spread::calibration {

inline constexpr int kMinimumTrays = 5;  // fewer cannot describe a pattern, nor give a CV over a bout

// A tray file the tool cannot read: kind kCorrupt for its content, kMissing when it cannot be opened;
// where() is the file, what() names file, line and column.
class TrayCsvError : public Error {
 public:
  TrayCsvError(const std::string& source, int line, const std::string& problem,
               ErrorKind kind = ErrorKind::kCorrupt);
  int line() const { return line_; }  // 1-based; 0 when the problem is with the file as a whole

 private:
  int line_;
};

struct TrayTest {
  std::string source;                       // file name (for messages and reports)
  std::vector<std::string> mass_columns;    // the pass columns, as named in the header
  double tray_width_m = 0.5;                // the spacing of the tray centres
  std::vector<double> position_m;           // tray centres as read (ascending)
  std::vector<double> mass_kg;              // per tray, mean over the passes read (0 for a missing tray)
  // Per pass (mass column) and tray as read, kg; NaN where the cell was empty or NA.
  std::vector<std::vector<double>> pass_mass_kg;
  std::vector<bool> missing;                // per tray as read: no reading in any pass
  int missing_cells = 0;                    // empty or NA mass cells, of missing trays too
  // The same trays on the symmetric layout the metrics use (centre line x = 0): trays missing on the
  // shorter side are added with zero mass, so a one-sided or off-centre row of trays is still overlapped
  // about the centre line.
  metrics::TrayLayout layout;
  std::vector<double> layout_mass_kg;
  std::vector<bool> layout_missing;         // per layout tray: a missing tray (padded trays are not missing)
  int padded_trays = 0;                     // trays added with zero mass
  int padded_left = 0;                      // of which on the left (x < 0) side

  double total_mass_kg() const;
  int missing_trays() const;                // trays with no reading in any pass
  bool has_missing_trays() const { return missing_trays() > 0; }
  // Positions (m) of the trays with no reading in any pass, and of those read in some passes only.
  std::vector<double> missing_positions_m() const;
  std::vector<double> partly_missing_positions_m() const;
};

// What a layout must be. The defaults are the full tray test's (step 2). A quick check (quick_check.hpp)
// lays 4–8 trays between two tramlines, measured from one of them: fewer trays, and positions that need
// not sit on the tractor's centre-line grid.
struct TrayCsvOptions {
  int minimum_trays = kMinimumTrays;  // trays with a reading
  bool centre_line_grid = true;       // require the centres on the centre line's grid
  double farthest_tray_m = kFarthestTray_m;    // |position_m| at most this
  double narrowest_tray_m = kNarrowestTray_m;  // tray spacing at least this
};

// A tray test of the largest plausible row (4,000 trays, tray_plausibility.hpp) with a dozen passes is
// about 1 MB; 64 MB leaves room for long comments and still refuses a wrong file (a disc image, a
// device such as /dev/zero) before it fills the memory.
inline constexpr std::size_t kLargestTrayFile_bytes = 64'000'000;

TrayTest parse_tray_csv(std::string_view text, const std::string& source, const TrayCsvOptions& options = {});
// Reads the file; a file that cannot be opened, a directory, a file over kLargestTrayFile_bytes and a
// binary file are each a TrayCsvError with line 0 saying which — read no further than the limit, and for
// binary content no further than the first 64 KiB.
TrayTest read_tray_csv(const std::string& path, const TrayCsvOptions& options = {});

// Writes a tray-test CSV (position_m and one column per pass in grams), with '#' comment lines first.
// For examples and synthetic tests; read_tray_csv() reads it back. Throws std::runtime_error naming the
// path when it cannot be written.
void write_tray_csv(const std::string& path, const std::vector<double>& position_m,
                    const std::vector<std::vector<double>>& pass_mass_g, const std::vector<std::string>& comments);

}  // namespace spread::calibration
