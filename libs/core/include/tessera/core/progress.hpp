#pragma once
// Progress on stderr: a redrawn bar with ETA on a terminal, or plain lines (a start line, 10% steps, a done line) for
// batch logs, or nothing.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>

namespace tessera {

/// Counts work units from any thread and reports them in the process's ProgressMode.
class Progress {
 public:
  /// How every Progress of the process reports.
  enum class Mode {
    automatic,  ///< a bar when stderr is a terminal, else nothing (the default)
    bar,        ///< a bar redrawn at most ten times a second
    plain,      ///< one line when the phase starts, one per 10% step, one when it ends (for logs)
    none,       ///< nothing (the CLI's --quiet)
  };

  /// `label` names the job; `total` is the number of units.
  Progress(std::string label, int64_t total);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  /// Adds n finished units (thread-safe).
  void advance(int64_t n = 1);
  /// Erases the bar.
  void done();

  /// Silences every progress report of the process (the CLI's --quiet): set_mode(Mode::none).
  static void set_quiet(bool quiet);
  /// Chooses how every later Progress reports (the CLI's --progress).
  static void set_mode(Mode mode);

 private:
  void draw(int64_t count);
  void print_step(int64_t count);

  std::string label_;
  int64_t total_;
  std::atomic<int64_t> count_{0};
  Mode mode_;                      ///< Bar, Plain or None (Auto resolved at construction)
  std::atomic<int> last_step_{0};  ///< Plain: the last 10% step printed
  bool finished_ = false;
  std::chrono::steady_clock::time_point start_;
  std::atomic<int64_t> last_draw_ns_{0};
  std::mutex draw_mutex_;
};

}  // namespace tessera
