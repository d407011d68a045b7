#include "tessera/core/progress.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdio>

namespace tessera {
namespace {
std::atomic<Progress::Mode> g_mode{Progress::Mode::automatic};

Progress::Mode resolve(Progress::Mode mode) {
  if (mode != Progress::Mode::automatic) return mode;
  return ::isatty(STDERR_FILENO) ? Progress::Mode::bar : Progress::Mode::none;
}
}  // namespace

void Progress::set_quiet(bool quiet) { g_mode = quiet ? Mode::none : Mode::automatic; }

void Progress::set_mode(Mode mode) { g_mode = mode; }

Progress::Progress(std::string label, int64_t total)
    : label_(std::move(label)),
      total_(total > 0 ? total : 1),
      mode_(resolve(g_mode)),
      start_(std::chrono::steady_clock::now()) {
  if (mode_ == Mode::plain) {
    fmt::print(stderr, "{}: started\n", label_);
    std::fflush(stderr);
  }
}

Progress::~Progress() { done(); }

void Progress::advance(int64_t n) {
  const int64_t count = count_.fetch_add(n) + n;
  if (mode_ == Mode::plain) return print_step(count);
  if (mode_ != Mode::bar) return;
  const auto now_ns =
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - start_).count();
  int64_t last = last_draw_ns_.load();
  if (now_ns - last < 100'000'000 && count < total_) return;
  if (!last_draw_ns_.compare_exchange_strong(last, now_ns)) return;
  draw(count);
}

void Progress::print_step(int64_t count) {
  // Each 10% step is printed once, by the thread that crossed it; steps below the last one printed are skipped.
  const int step = int(std::min<int64_t>(10, count * 10 / total_));
  int last = last_step_.load();
  while (step > last && step < 10)
    if (last_step_.compare_exchange_weak(last, step)) {
      std::lock_guard lock(draw_mutex_);
      if (!finished_) fmt::print(stderr, "{}: {}%\n", label_, step * 10);
      std::fflush(stderr);
      return;
    }
}

void Progress::draw(int64_t count) {
  std::lock_guard lock(draw_mutex_);
  if (finished_) return;
  const double frac = std::min(1.0, double(count) / double(total_));
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double eta = frac > 0 ? elapsed * (1 - frac) / frac : 0;
  constexpr int width = 30;
  const int filled = int(frac * width);
  std::string bar(size_t(filled), '#');
  bar.resize(width, '.');
  fmt::print(stderr, "\r{} [{}] {:3.0f}%  {:.1f}s elapsed, ETA {:.1f}s ", label_, bar, frac * 100, elapsed, eta);
  std::fflush(stderr);
}

void Progress::done() {
  std::lock_guard lock(draw_mutex_);
  if (finished_) return;
  finished_ = true;
  if (mode_ == Mode::bar) {
    fmt::print(stderr, "\r\033[K");
  } else if (mode_ == Mode::plain) {
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    fmt::print(stderr, "{}: done in {:.2f} s\n", label_, elapsed);
  }
  std::fflush(stderr);
}

}  // namespace tessera
