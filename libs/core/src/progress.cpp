#include "tessera/core/progress.hpp"

#include <cstdio>

#include <unistd.h>

#include <fmt/format.h>

namespace tessera {
namespace {
std::atomic<bool> g_quiet{false};
}

void Progress::set_quiet(bool quiet) { g_quiet = quiet; }

Progress::Progress(std::string label, int64_t total)
    : label_(std::move(label)),
      total_(total > 0 ? total : 1),
      enabled_(!g_quiet && ::isatty(STDERR_FILENO)),
      start_(std::chrono::steady_clock::now()) {}

Progress::~Progress() { done(); }

void Progress::advance(int64_t n) {
  const int64_t count = count_.fetch_add(n) + n;
  if (!enabled_) return;
  const auto now_ns =
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - start_).count();
  int64_t last = last_draw_ns_.load();
  if (now_ns - last < 100'000'000 && count < total_) return;
  if (!last_draw_ns_.compare_exchange_strong(last, now_ns)) return;
  draw(count);
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
  if (enabled_) {
    fmt::print(stderr, "\r\033[K");
    std::fflush(stderr);
  }
}

}  // namespace tessera
