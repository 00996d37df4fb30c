#include "libspread/analysis/plot/report_date.hpp"

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <stdexcept>

namespace spread::plot {
namespace {

constexpr std::int64_t kLatest_s = 253402300799;  // 9999-12-31 23:59:59 UTC

std::tm utc(std::int64_t time_s) {
  const std::time_t t = static_cast<std::time_t>(time_s);
  std::tm out{};
  if (gmtime_r(&t, &out) == nullptr) throw std::invalid_argument("time " + std::to_string(time_s) + " s has no UTC date");
  return out;
}

}  // namespace

std::int64_t report_time_s(const char* source_date_epoch, std::int64_t now_s) {
  if (source_date_epoch == nullptr || *source_date_epoch == '\0') return now_s;
  const std::string text(source_date_epoch);
  bool digits = true;
  for (char c : text) digits = digits && c >= '0' && c <= '9';
  errno = 0;
  const long long value = digits && text.size() <= 12 ? std::strtoll(text.c_str(), nullptr, 10) : -1;
  if (!digits || errno != 0 || value < 0 || value > kLatest_s) {
    throw std::invalid_argument("SOURCE_DATE_EPOCH '" + text +
                                "' is not a whole number of seconds since 1970-01-01 UTC (unset it to use the clock)");
  }
  return value;
}

std::int64_t report_time_s() {
  return report_time_s(std::getenv("SOURCE_DATE_EPOCH"), static_cast<std::int64_t>(std::time(nullptr)));
}

std::string utc_date(std::int64_t time_s) {
  const std::tm t = utc(time_s);
  char text[32];
  std::snprintf(text, sizeof text, "%04d-%02d-%02d", t.tm_year + 1900, t.tm_mon + 1, t.tm_mday);
  return text;
}

std::string utc_date_time(std::int64_t time_s) {
  const std::tm t = utc(time_s);
  char text[48];
  std::snprintf(text, sizeof text, "%04d-%02d-%02d %02d:%02d UTC", t.tm_year + 1900, t.tm_mon + 1, t.tm_mday,
                t.tm_hour, t.tm_min);
  return text;
}

}  // namespace spread::plot
