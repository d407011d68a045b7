#pragma once
// Rendering across the ranks of an MPI job (Open MPI's mpirun; docs/farm.md): dynamic assignment of work units to
// every rank, rank 0 included, and the results gathered on rank 0. Tessera is built with it when Open MPI
// (libopenmpi-dev) is found; elsewhere Session refuses to start.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "tessera/image/image.hpp"

namespace tessera::mpi {

/// True when this Tessera was built with MPI.
bool available();

/// MPI for the life of the object (MPI_Init_thread with MPI_THREAD_FUNNELED, then MPI_Finalize): one per process.
/// Throws InvalidInput when Tessera was built without MPI, naming the package to build with.
class Session {
 public:
  Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;
  ~Session();

  /// This process's rank in MPI_COMM_WORLD.
  int rank() const { return rank_; }
  /// The number of ranks.
  int size() const { return size_; }

 private:
  int rank_ = 0, size_ = 1;
};

/// Rank 0's `values` on every rank (MPI_Bcast of the size, then the values).
void broadcast(const Session& session, std::vector<int>& values);

/// Every rank's `mine`, in rank order, on rank 0 (MPI_Gather of the sizes, then MPI_Gatherv); empty on the others.
std::vector<std::string> gather(const Session& session, const std::string& mine);

/// One finished unit: its index, its pixels and the seconds render() took.
struct UnitResult {
  int unit = 0;
  ImageRGB image;
  double seconds = 0;
};

/// Works through units 0..count-1 on every rank. Each rank, rank 0 too (on a second thread, while its main thread
/// serves the others), takes the next unit when it is free (dynamic assignment: slow units balance; ranks 1.. ask for
/// their next unit as they start one, so none waits for an answer) and runs render(unit); rank 0's `deliver` receives
/// every unit's result, on rank 0's main thread, in the order they finish. Returns on every rank once all units are
/// delivered. An exception from render() or deliver() on any rank prints its message and aborts the whole job
/// (MPI_Abort with exit code 1), as one failed rank cannot finish the work.
void farm_units(const Session& session, int count, const std::function<ImageRGB(int unit)>& render,
                const std::function<void(UnitResult&& result)>& deliver);

/// Sort-last compositing: each rank's `layer` is what its part of the scene adds to each pixel (color premultiplied
/// by opacity, and opacity; all the same size), and `front_to_back` lists the ranks in visibility order (for parts
/// that are slabs of a volume, nearest the eye first; a part a pixel's ray does not cross adds nothing there, so
/// any order consistent along every ray will do). Binary swap (Ma et al. 1994): the first ranks in a count that is
/// not a power of two fold into their neighbours in the order, then the remaining 2^k ranks halve the picture and
/// trade halves k times, compositing with "over" in the order, and each sends its 1/2^k of the rows to rank 0.
/// Returns the whole composited layer on rank 0, an empty image on the others.
ImageRGBA composite_layers(const Session& session, ImageRGBA layer, const std::vector<int>& front_to_back);

}  // namespace tessera::mpi
