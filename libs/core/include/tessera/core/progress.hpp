#pragma once
// A progress bar with ETA on stderr, shown only when stderr is a terminal and not silenced.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>

namespace tessera {

/// Counts work units from any thread and redraws a one-line bar at most ten times a second.
class Progress {
 public:
  /// `label` names the job; `total` is the number of units. Shows nothing when quiet or stderr is no terminal.
  Progress(std::string label, int64_t total);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  /// Adds n finished units (thread-safe).
  void advance(int64_t n = 1);
  /// Erases the bar.
  void done();

  /// Silences every progress bar of the process (the CLI's --quiet).
  static void set_quiet(bool quiet);

 private:
  void draw(int64_t count);

  std::string label_;
  int64_t total_;
  std::atomic<int64_t> count_{0};
  bool enabled_;
  bool finished_ = false;
  std::chrono::steady_clock::time_point start_;
  std::atomic<int64_t> last_draw_ns_{0};
  std::mutex draw_mutex_;
};

}  // namespace tessera
