// libFuzzer target for detached volume headers: MetaImage .mhd (read_mhd) and NRRD .nhdr (read_nrrd), the headers
// that name a separate data file. The first byte picks the format (even: .mhd, odd: .nhdr); the rest up to the first
// NUL byte is the header, written to h.mhd or h.nhdr, and what follows the NUL is written to data.raw beside it (the
// seeds' headers name data.raw). Both readers read from paths only, so the files live in a folder made once per process
// with mkdtemp and removed at exit. A header holding '/' is skipped: absolute and nested data file names would read
// files outside that folder (a character device such as /dev/zero would never end: see docs/volume.md).
// tessera::Error is the expected outcome for a bad header or data file; anything else (a crash, another exception, a
// sanitizer report) is a bug, and so is a volume that reads with dims < 1, a spacing that is not finite and positive,
// an origin or box corner that is not finite, or a float voxel that is not finite. The memory budget is 256 MiB; the
// data file holds at most what the input does, so one input stays small.
#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <variant>

#include "tessera/core/error.hpp"
#include "tessera/core/memory_budget.hpp"
#include "tessera/volume/volume_io.hpp"

namespace {

namespace fs = std::filesystem;

// The process's scratch folder, removed when the process exits normally (libFuzzer's -max_total_time and -runs do).
// Never destroyed, so that the exit handler still has it. In memory (/dev/shm) where there is one: ten times as many
// runs per second as on the disk behind /tmp.
const fs::path& scratch() {
  static const fs::path* dir = [] {
    const fs::path base = ::access("/dev/shm", W_OK) == 0 ? fs::path("/dev/shm") : fs::temp_directory_path();
    std::string pattern = (base / "tessera-fuzz-volume-header-XXXXXX").string();
    if (!::mkdtemp(pattern.data())) std::abort();
    auto* path = new fs::path(pattern);
    std::atexit([] {
      std::error_code ignored;
      fs::remove_all(scratch(), ignored);
    });
    return path;
  }();
  return *dir;
}

void write(const fs::path& path, std::string_view bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), std::streamsize(bytes.size()));
  if (!out) std::abort();
}

void check(bool ok) {
  if (!ok) __builtin_trap();
}

template <class T>
void check_volume(const tessera::Volume<T>& v) {
  const auto dims = v.dims();
  check(dims.x >= 1 && dims.y >= 1 && dims.z >= 1 && v.voxel_count() == size_t(dims.x) * dims.y * dims.z);
  for (int a = 0; a < 3; ++a) {
    check(std::isfinite(v.spacing()[a]) && v.spacing()[a] > 0 && std::isfinite(v.origin()[a]));
    check(std::isfinite(v.to_world(tessera::Vec3(dims - 1))[a]));
  }
  for (const T& x : v.voxels()) check(std::isfinite(double(x)));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  tessera::MemoryBudget::set_limit(uint64_t(256) << 20);
  const std::string_view input(reinterpret_cast<const char*>(data) + 1, size - 1);
  const size_t nul = input.find('\0');
  const std::string_view header = input.substr(0, nul);
  const std::string_view voxels = nul == std::string_view::npos ? std::string_view() : input.substr(nul + 1);
  if (header.find('/') != std::string_view::npos) return 0;
  const bool mhd = data[0] % 2 == 0;
  const fs::path header_path = scratch() / (mhd ? "h.mhd" : "h.nhdr");
  write(header_path, header);
  write(scratch() / "data.raw", voxels);
  try {
    const tessera::AnyVolume volume = mhd ? tessera::read_mhd(header_path) : tessera::read_nrrd(header_path);
    std::visit([](const auto& v) { check_volume(v); }, volume);
  } catch (const tessera::Error&) {
  }
  return 0;
}
