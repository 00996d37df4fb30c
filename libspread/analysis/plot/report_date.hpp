#pragma once
// The time a report is stamped with: the system clock, or SOURCE_DATE_EPOCH when it is set (the
// reproducible-builds convention: seconds since 1970-01-01 UTC), so a report made twice from the same
// data is the same file and tests can compare it.
#include <cstdint>
#include <string>

namespace spread::plot {

// `source_date_epoch` is the variable's value (nullptr or "" = not set: `now_s` is used). A value that is
// not a whole number of seconds in [0, 253402300799] (up to 9999-12-31) throws std::invalid_argument
// naming SOURCE_DATE_EPOCH: a typo must not stamp a report with a wrong date silently.
std::int64_t report_time_s(const char* source_date_epoch, std::int64_t now_s);
// The same from the environment and the system clock.
std::int64_t report_time_s();

// UTC calendar date "YYYY-MM-DD" and time "YYYY-MM-DD HH:MM UTC" of seconds since 1970.
std::string utc_date(std::int64_t time_s);
std::string utc_date_time(std::int64_t time_s);

}  // namespace spread::plot
