// The pipeline's scheduling: the raster thread that runs each pass's raster job beside the caller, the oneTBB arenas
// of its two sides, and pipeline_for, which shares the ThreadLimit's threads between them.
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <utility>

#include "tessera/core/parallel.hpp"
#include "tessera/raster3d/pipeline.hpp"

namespace tessera::raster3d::detail {

// One thread that runs raster jobs one at a time, in order: a one-job slot, filled by submit once the job before is
// done (llvmpipe's rasterizer thread beside the application's).
class RasterThread {
 public:
  RasterThread() : thread_([this] { run(); }) {}
  ~RasterThread() {
    {
      const std::lock_guard lock(mutex_);
      stop_ = true;
    }
    wake_.notify_one();
    thread_.join();  // after the job in the slot, if any
  }

  void submit(std::function<void()> job) {
    std::unique_lock lock(mutex_);
    // Blocked here the caller's core is free, as in wait(): the running job's next loops may take it.
    caller_waiting_.store(true, std::memory_order_relaxed);
    done_.wait(lock, [&] { return !job_; });
    caller_waiting_.store(false, std::memory_order_relaxed);
    job_ = std::move(job);
    busy_.store(true, std::memory_order_relaxed);
    lock.unlock();
    wake_.notify_one();
  }

  void wait() {
    std::unique_lock lock(mutex_);
    caller_waiting_.store(true, std::memory_order_relaxed);
    done_.wait(lock, [&] { return !job_; });
    caller_waiting_.store(false, std::memory_order_relaxed);
  }

  bool idle() const noexcept { return !busy_.load(std::memory_order_relaxed); }
  bool caller_waiting() const noexcept { return caller_waiting_.load(std::memory_order_relaxed); }

  std::exception_ptr take_error() {
    const std::lock_guard lock(mutex_);
    return std::exchange(error_, nullptr);
  }

 private:
  void run() {
    std::unique_lock lock(mutex_);
    for (;;) {
      wake_.wait(lock, [&] { return job_ || stop_; });
      if (!job_) return;
      lock.unlock();  // submit only replaces an empty slot: the job is not touched while it runs
      std::exception_ptr error;
      try {
        job_();
      } catch (...) {
        error = std::current_exception();
      }
      lock.lock();
      if (error && !error_) error_ = error;
      job_ = nullptr;  // its captures (e.g. what keeps the shaders alive) go here, on this thread
      busy_.store(false, std::memory_order_relaxed);
      done_.notify_all();
    }
  }

  std::mutex mutex_;
  std::condition_variable wake_, done_;
  std::function<void()> job_;                // the slot: the job running or about to run
  std::atomic<bool> busy_{false};            // job_ is set: read by the caller without the lock, as a hint
  std::atomic<bool> caller_waiting_{false};  // the caller is in wait(): read by the job as a hint
  std::exception_ptr error_;                 // the first exception a job ended with, until finish_raster takes it
  bool stop_ = false;
  std::thread thread_;  // last: it starts once the members above exist
};

struct PipelineArenas {
  std::unique_ptr<tbb::task_arena> of_side[2];
};

namespace {

void pipeline_for_piece(RasterScratch& scratch, PipelineSide side, int n, int64_t first, int64_t last, int64_t grain,
                        const std::function<void(int64_t, int64_t)>& body) {
  const bool other_busy = side == PipelineSide::raster
                              ? !(scratch.raster_thread && scratch.raster_thread->caller_waiting())
                              : !raster_idle(scratch);
  const int slots = other_busy ? n - 1 : n;
  if (slots >= n) return parallel_for(first, last, grain, body);
  if (slots <= 1) {
    for (int64_t b = first; b < last; b += grain) body(b, std::min(last, b + grain));
    return;
  }
  // Each side's arena is made and used only by that side's thread (the holder exists from the start).
  std::unique_ptr<tbb::task_arena>& arena = scratch.arenas->of_side[side == PipelineSide::raster];
  if (!arena || arena->max_concurrency() != slots) arena = std::make_unique<tbb::task_arena>(slots);
  arena->execute([&] { parallel_for(first, last, grain, body); });
}

}  // namespace

void pipeline_for(RasterScratch& scratch, PipelineSide side, int64_t first, int64_t last, int64_t grain,
                  const std::function<void(int64_t, int64_t)>& body) {
  if (last <= first) return;
  const int n = thread_count();
  // The raster job's loop runs in four pieces, each counting the threads anew: the caller may start waiting for the
  // job (flush: then its core is free) after the loop has begun. The pieces end on multiples of grain: same chunks.
  const int pieces = side == PipelineSide::raster && n > 1 ? 4 : 1;
  const int64_t chunks = (last - first + grain - 1) / grain;
  for (int p = 0; p < pieces; ++p) {
    const int64_t begin = first + chunks * p / pieces * grain;
    const int64_t end = std::min(last, first + chunks * (p + 1) / pieces * grain);
    if (begin < end) pipeline_for_piece(scratch, side, n, begin, end, grain, body);
  }
}

RasterScratch::RasterScratch() : arenas(std::make_unique<PipelineArenas>()) {}
RasterScratch::~RasterScratch() = default;

void submit_raster(RasterScratch& scratch, std::function<void()> job) {
  if (!scratch.raster_thread) scratch.raster_thread = std::make_unique<RasterThread>();
  scratch.raster_thread->submit(std::move(job));
}

void finish_raster(RasterScratch& scratch) {
  if (!scratch.raster_thread) return;
  scratch.raster_thread->wait();
  if (std::exception_ptr error = scratch.raster_thread->take_error()) std::rethrow_exception(error);
}

uint64_t collect_raster(RasterScratch& scratch) {
  wait_raster(scratch);
  const uint64_t rasterized = scratch.job_rasterized.exchange(0);
  finish_raster(scratch);
  return rasterized;
}

bool raster_idle(const RasterScratch& scratch) noexcept {
  return !scratch.raster_thread || scratch.raster_thread->idle();
}

void wait_raster(RasterScratch& scratch) noexcept {
  if (scratch.raster_thread) scratch.raster_thread->wait();
}

}  // namespace tessera::raster3d::detail
