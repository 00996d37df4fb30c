#include "lookup_builder/progress.hpp"

#include <algorithm>
#include <cstdio>

namespace spread::lookup {

std::string format_duration(double seconds) {
  const long s = std::max(0L, static_cast<long>(seconds + 0.5));
  char text[32];
  if (s >= 3600) {
    std::snprintf(text, sizeof text, "%ldh%02ldm", s / 3600, (s % 3600) / 60);
  } else if (s >= 60) {
    std::snprintf(text, sizeof text, "%ldm%02lds", s / 60, s % 60);
  } else {
    std::snprintf(text, sizeof text, "%lds", s);
  }
  return text;
}

Progress::Progress(std::ostream* out, bool terminal, int total) : out_(out), terminal_(terminal), total_(total) {}

std::string Progress::eta_text() const {
  if (finished_now_ == 0) return "ETA --";
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  // Runs finish at the rate seen so far in this process (parallel workers included).
  const double per_run = elapsed / finished_now_;
  return "ETA " + format_duration(per_run * (total_ - done_));
}

void Progress::redraw() {
  std::string line = "[" + std::to_string(done_) + "/" + std::to_string(total_) + " done] ";
  if (!running_.empty()) {
    line += "running ";
    for (std::size_t i = 0; i < running_.size(); ++i) line += (i ? ", " : "") + running_[i];
    line += " | ";
  }
  line += eta_text();
  *out_ << "\r\033[K" << line << std::flush;  // carriage return + erase line: one updating line
  line_open_ = true;
}

void Progress::skipped(const std::string& label) {
  if (out_ == nullptr) return;
  std::lock_guard lock(mutex_);
  ++done_;
  if (terminal_) {
    redraw();
  } else {
    *out_ << "[" << done_ << "/" << total_ << "] " << label << ": exists, skipped\n" << std::flush;
  }
}

void Progress::started(const std::string& label) {
  if (out_ == nullptr) return;
  std::lock_guard lock(mutex_);
  running_.push_back(label);
  if (terminal_) redraw();
}

void Progress::finished(const std::string& label, const std::string& detail, double seconds, double cpu_s,
                        double cpu_s_per_1000) {
  if (out_ == nullptr) return;
  std::lock_guard lock(mutex_);
  ++done_;
  ++finished_now_;
  std::erase(running_, label);
  char timing[96];
  if (cpu_s >= 0.0 && cpu_s_per_1000 >= 0.0)
    std::snprintf(timing, sizeof timing, "%.2f s (CPU %.2f s, %.2f s per 1000 launches)", seconds, cpu_s, cpu_s_per_1000);
  else
    std::snprintf(timing, sizeof timing, "%.2f s", seconds);
  if (terminal_) {
    redraw();
  } else {
    *out_ << "[" << done_ << "/" << total_ << "] " << label << ": " << detail << ", " << timing << "\n" << std::flush;
  }
}

void Progress::failed(const std::string& label, const std::string& message) {
  if (out_ == nullptr) return;
  std::lock_guard lock(mutex_);
  std::erase(running_, label);
  if (terminal_ && line_open_) *out_ << "\n";
  line_open_ = false;
  *out_ << label << ": FAILED: " << message << "\n" << std::flush;
}

void Progress::close() {
  if (out_ == nullptr) return;
  std::lock_guard lock(mutex_);
  if (terminal_ && line_open_) *out_ << "\n" << std::flush;
  line_open_ = false;
}

}  // namespace spread::lookup
