#pragma once
// Progress of a sweep. On a terminal: one line rewritten in place (runs done / total, the runs in
// progress, ETA). Otherwise (a log, CI): one plain line per finished or skipped run, nothing else.
// Thread-safe: worker threads report starts, the writer reports finishes.
#include <chrono>
#include <mutex>
#include <ostream>
#include <string>
#include <vector>

namespace spread::lookup {

class Progress {
 public:
  // out nullptr = silent. total = runs of the sweep (skipped ones included).
  Progress(std::ostream* out, bool terminal, int total);

  void skipped(const std::string& label);
  void started(const std::string& label);
  // detail: e.g. "812 samples (dem, converged at 0.25 s)"; cpu_s and cpu_s_per_1000: the run's CPU time and
  // that per 1,000 launches (< 0: not measured, not shown).
  void finished(const std::string& label, const std::string& detail, double seconds, double cpu_s = -1.0,
                double cpu_s_per_1000 = -1.0);
  void failed(const std::string& label, const std::string& message);
  // Ends the updating line on a terminal.
  void close();

 private:
  void redraw();  // terminal mode, mutex held
  std::string eta_text() const;

  std::ostream* out_;
  bool terminal_;
  int total_;
  int done_ = 0;          // finished + skipped
  int finished_now_ = 0;  // finished in this process (for the ETA)
  std::vector<std::string> running_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  std::mutex mutex_;
  bool line_open_ = false;
};

// "1m05s", "42s", "1h02m".
std::string format_duration(double seconds);

}  // namespace spread::lookup
