#include "tessera/farm/mpi.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <climits>
#include <condition_variable>
#include <cstdio>
#include <cstring>
#include <deque>
#include <exception>
#include <mutex>
#include <thread>

#include "tessera/core/error.hpp"

#if TESSERA_HAS_MPI
#include <mpi.h>
#endif

namespace tessera::mpi {

bool available() { return TESSERA_HAS_MPI != 0; }

#if TESSERA_HAS_MPI

namespace {

enum Tag : int { kRequest = 1, kAssign, kHeader, kPixels };

// A unit's header on the wire: unit index, width, height; the seconds travel as a second message field.
struct Header {
  int unit, width, height;
  double seconds;
};

[[noreturn]] void abort_job(const char* what) {
  std::fputs(fmt::format("tessera: error: {}\n", what).c_str(), stderr);
  std::fflush(stderr);
  MPI_Abort(MPI_COMM_WORLD, 1);
  std::abort();  // MPI_Abort does not return
}

UnitResult timed_render(const std::function<ImageRGB(int)>& render, int unit) {
  const auto start = std::chrono::steady_clock::now();
  UnitResult r{unit, render(unit), 0.0};
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

// Rank 0: serves the other ranks' requests and gathers their results on this (the main) thread, while a second
// thread renders rank 0's own share from the same counter.
void serve(const Session& session, int count, const std::function<ImageRGB(int)>& render,
           const std::function<void(UnitResult&&)>& deliver) {
  std::atomic<int> next{0};
  std::mutex mutex;
  std::condition_variable ready;
  std::deque<UnitResult> local;
  std::exception_ptr local_error;
  bool local_done = false;
  std::thread worker([&] {
    try {
      for (int unit; (unit = next++) < count;) {
        UnitResult r = timed_render(render, unit);
        const std::lock_guard lock(mutex);
        local.push_back(std::move(r));
        ready.notify_one();
      }
    } catch (...) {
      local_error = std::current_exception();
    }
    const std::lock_guard lock(mutex);
    local_done = true;
    ready.notify_one();
  });
  int delivered = 0, released = 0;
  const int others = session.size() - 1;
  try {
    while (delivered < count || released < others) {
      // Results of this rank first, then every message waiting; when there is nothing, wait a millisecond for either
      // (a blocking MPI receive would spin a core that the local renderer needs, and so would polling much more
      // often; the other ranks ask for their next unit ahead, so the wait delays no one).
      std::deque<UnitResult> mine;
      {
        std::unique_lock lock(mutex);
        ready.wait_for(lock, std::chrono::milliseconds(1), [&] { return !local.empty() || local_done; });
        mine.swap(local);
        if (local_error) std::rethrow_exception(local_error);
      }
      for (UnitResult& r : mine) ++delivered, deliver(std::move(r));
      for (int flag = 1; flag;) {
        MPI_Status status;
        MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &status);
        if (!flag) break;
        const int source = status.MPI_SOURCE;
        if (status.MPI_TAG == kRequest) {
          int ignored = 0;
          MPI_Recv(&ignored, 1, MPI_INT, source, kRequest, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
          int unit = next++;
          if (unit >= count) unit = -1, ++released;
          MPI_Send(&unit, 1, MPI_INT, source, kAssign, MPI_COMM_WORLD);
        } else if (status.MPI_TAG == kHeader) {
          Header h{};
          MPI_Recv(&h, sizeof h, MPI_BYTE, source, kHeader, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
          UnitResult r{h.unit, ImageRGB(h.width, h.height), h.seconds};
          MPI_Recv(r.image.pixels().data(), int(r.image.pixels().size() * 3), MPI_FLOAT, source, kPixels,
                   MPI_COMM_WORLD, MPI_STATUS_IGNORE);
          ++delivered;
          deliver(std::move(r));
        } else {
          abort_job(fmt::format("MPI: unexpected message tag {} from rank {}", status.MPI_TAG, source).c_str());
        }
      }
    }
  } catch (const std::exception& e) {
    abort_job(e.what());
  }
  worker.join();
}

// Ranks 1..: ask rank 0 for a unit, and before rendering it ask for the next one, so that the answer (which rank 0
// gives between its own polls) is there when the unit is done; send each result back, until rank 0 answers -1.
void work(const std::function<ImageRGB(int)>& render) {
  try {
    const int ask = 0;
    MPI_Send(&ask, 1, MPI_INT, 0, kRequest, MPI_COMM_WORLD);
    for (;;) {
      int unit = 0;
      MPI_Recv(&unit, 1, MPI_INT, 0, kAssign, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      if (unit < 0) return;
      MPI_Send(&ask, 1, MPI_INT, 0, kRequest, MPI_COMM_WORLD);
      const UnitResult r = timed_render(render, unit);
      const Header h{unit, r.image.width(), r.image.height(), r.seconds};
      MPI_Send(&h, sizeof h, MPI_BYTE, 0, kHeader, MPI_COMM_WORLD);
      MPI_Send(r.image.pixels().data(), int(r.image.pixels().size() * 3), MPI_FLOAT, 0, kPixels, MPI_COMM_WORLD);
    }
  } catch (const std::exception& e) {
    abort_job(e.what());
  }
}

// Rows [y0, y1) of `image` composited with `other` (the same rows, from row 0) by "over", the result in `image`:
// `image` in front when `in_front`, else behind.
void composite_rows(ImageRGBA& image, int y0, int y1, const std::vector<float>& other, bool in_front) {
  const auto width = size_t(image.width());
  for (int y = y0; y < y1; ++y)
    for (size_t x = 0; x < width; ++x) {
      glm::vec4& mine = image.row(y)[x];
      const float* o = &other[4 * (size_t(y - y0) * width + x)];
      const glm::vec4 theirs(o[0], o[1], o[2], o[3]);
      const glm::vec4& front = in_front ? mine : theirs;
      const glm::vec4& back = in_front ? theirs : mine;
      mine = front + (1 - front.w) * back;
    }
}

float* rows_of(ImageRGBA& image, int y) { return &image.row(y)->x; }
int floats(const ImageRGBA& image, int y0, int y1) { return (y1 - y0) * image.width() * 4; }

}  // namespace

Session::Session() {
  int provided = 0;
  MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

Session::~Session() { MPI_Finalize(); }

ImageRGBA composite_layers(const Session& session, ImageRGBA layer, const std::vector<int>& front_to_back) {
  const int ranks = session.size();
  if (int(front_to_back.size()) != ranks) throw InvalidInput("composite_layers: the order must list every rank once");
  const int position =
      int(std::find(front_to_back.begin(), front_to_back.end(), session.rank()) - front_to_back.begin());
  int power = 1;
  while (power * 2 <= ranks) power *= 2;
  const int extra = ranks - power;
  const int height = layer.height();
  std::vector<float> received;
  // Fold: positions 2i + 1 (i < extra) hand their layer to 2i, in front of them.
  if (position < 2 * extra) {
    if (position % 2 == 1) {
      MPI_Send(rows_of(layer, 0), floats(layer, 0, height), MPI_FLOAT, front_to_back[size_t(position) - 1], kPixels,
               MPI_COMM_WORLD);
      return {};
    }
    received.resize(size_t(floats(layer, 0, height)));
    MPI_Recv(received.data(), int(received.size()), MPI_FLOAT, front_to_back[size_t(position) + 1], kPixels,
             MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    composite_rows(layer, 0, height, received, true);
  }
  // The 2^k participants, in visibility order, and this rank's index among them.
  const auto participant = [&](int v) { return front_to_back[size_t(v < extra ? 2 * v : v + extra)]; };
  const int v = position < 2 * extra ? position / 2 : position - extra;
  int y0 = 0, y1 = height;
  for (int bit = 1; bit < power; bit *= 2) {
    const int partner = v ^ bit;
    const int mid = y0 + (y1 - y0) / 2;
    const bool front = v < partner;  // the lower index holds the nearer group of parts
    const int keep0 = front ? y0 : mid, keep1 = front ? mid : y1;
    const int give0 = front ? mid : y0, give1 = front ? y1 : mid;
    received.resize(size_t(floats(layer, keep0, keep1)));
    MPI_Sendrecv(rows_of(layer, give0), floats(layer, give0, give1), MPI_FLOAT, participant(partner), kPixels,
                 received.data(), int(received.size()), MPI_FLOAT, participant(partner), kPixels, MPI_COMM_WORLD,
                 MPI_STATUS_IGNORE);
    composite_rows(layer, keep0, keep1, received, front);
    y0 = keep0, y1 = keep1;
  }
  // Gather: every participant's rows to rank 0.
  if (session.rank() != 0) {
    const int range[2] = {y0, y1};
    MPI_Send(range, 2, MPI_INT, 0, kHeader, MPI_COMM_WORLD);
    MPI_Send(rows_of(layer, y0), floats(layer, y0, y1), MPI_FLOAT, 0, kPixels, MPI_COMM_WORLD);
    return {};
  }
  ImageRGBA whole(layer.width(), height, glm::vec4(0.0f));
  const auto place = [&](int from, int to, const float* data) {
    std::copy_n(data, size_t(floats(whole, from, to)), rows_of(whole, from));
  };
  const bool root_participates = position >= 2 * extra || position % 2 == 0;
  if (root_participates) place(y0, y1, rows_of(layer, y0));
  for (int i = 0; i < power - (root_participates ? 1 : 0); ++i) {
    int range[2];
    MPI_Status status;
    MPI_Recv(range, 2, MPI_INT, MPI_ANY_SOURCE, kHeader, MPI_COMM_WORLD, &status);
    received.resize(size_t(floats(whole, range[0], range[1])));
    MPI_Recv(received.data(), int(received.size()), MPI_FLOAT, status.MPI_SOURCE, kPixels, MPI_COMM_WORLD,
             MPI_STATUS_IGNORE);
    place(range[0], range[1], received.data());
  }
  return whole;
}

std::vector<std::string> gather(const Session& session, const std::string& mine) {
  if (mine.size() > size_t(INT_MAX)) throw InvalidInput("MPI: a rank's part is over 2 GiB");
  const int size = int(mine.size());
  std::vector<int> sizes(size_t(session.size())), offsets(size_t(session.size()) + 1, 0);
  MPI_Gather(&size, 1, MPI_INT, sizes.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  std::string all;
  if (session.rank() == 0) {
    for (size_t r = 0; r < sizes.size(); ++r) {
      if (int64_t(offsets[r]) + sizes[r] > INT_MAX) throw InvalidInput("MPI: the parts together are over 2 GiB");
      offsets[r + 1] = offsets[r] + sizes[r];
    }
    all.resize(size_t(offsets.back()));
  }
  MPI_Gatherv(mine.data(), size, MPI_BYTE, all.data(), sizes.data(), offsets.data(), MPI_BYTE, 0, MPI_COMM_WORLD);
  std::vector<std::string> parts;
  if (session.rank() == 0)
    for (size_t r = 0; r < sizes.size(); ++r) parts.push_back(all.substr(size_t(offsets[r]), size_t(sizes[r])));
  return parts;
}

void broadcast(const Session&, std::vector<int>& values) {
  int size = int(values.size());
  MPI_Bcast(&size, 1, MPI_INT, 0, MPI_COMM_WORLD);
  values.resize(size_t(size));
  MPI_Bcast(values.data(), size, MPI_INT, 0, MPI_COMM_WORLD);
}

void farm_units(const Session& session, int count, const std::function<ImageRGB(int)>& render,
                const std::function<void(UnitResult&&)>& deliver) {
  if (session.rank() == 0)
    serve(session, count, render, deliver);
  else
    work(render);
  MPI_Barrier(MPI_COMM_WORLD);
}

#else

Session::Session() {
  throw InvalidInput(
      "--mpi: this Tessera was built without MPI (install Open MPI, Debian libopenmpi-dev, and build "
      "again)");
}

Session::~Session() = default;

void broadcast(const Session&, std::vector<int>&) { throw InvalidInput("MPI: this Tessera was built without MPI"); }

std::vector<std::string> gather(const Session&, const std::string&) {
  throw InvalidInput("MPI: this Tessera was built without MPI");
}

ImageRGBA composite_layers(const Session&, ImageRGBA, const std::vector<int>&) {
  throw InvalidInput("MPI: this Tessera was built without MPI");
}

void farm_units(const Session&, int, const std::function<ImageRGB(int)>&, const std::function<void(UnitResult&&)>&) {
  throw InvalidInput("MPI: this Tessera was built without MPI");
}

#endif

}  // namespace tessera::mpi
