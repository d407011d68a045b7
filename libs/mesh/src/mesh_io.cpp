// Format dispatch by extension, and file access for the mesh readers and writers.
#include "tessera/mesh/mesh_io.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cstring>

#include "tessera/core/atomic_file.hpp"
#include "tessera/core/error.hpp"
#include "tessera/core/progress.hpp"
#include "tessera/mesh/convert.hpp"

namespace tessera {
namespace {

/// A whole file mapped read-only into memory (no zero-filled buffer, no copy); regular non-empty files only.
class MappedFile {
 public:
  explicit MappedFile(const std::filesystem::path& path) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) throw IoError(fmt::format("cannot open '{}': {}", path.string(), std::strerror(errno)));
    struct stat st {};
    if (::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0) {
      void* p = ::mmap(nullptr, size_t(st.st_size), PROT_READ, MAP_PRIVATE | MAP_POPULATE, fd, 0);
      if (p != MAP_FAILED) {
        data_ = static_cast<const char*>(p);
        size_ = size_t(st.st_size);
      }
    }
    ::close(fd);
    if (data_ == nullptr) fallback_ = read_file(path);  // empty files, pipes, file systems without mmap
  }
  ~MappedFile() {
    if (data_ != nullptr) ::munmap(const_cast<char*>(data_), size_);
  }
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;

  std::string_view view() const {
    return data_ != nullptr ? std::string_view(data_, size_) : std::string_view(fallback_);
  }

 private:
  const char* data_ = nullptr;
  size_t size_ = 0;
  std::string fallback_;
};

}  // namespace

MeshFormat mesh_format_from_path(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  static constexpr std::array<std::pair<std::string_view, MeshFormat>, 4> kFormats{
      {{".obj", MeshFormat::obj}, {".ply", MeshFormat::ply}, {".off", MeshFormat::off}, {".stl", MeshFormat::stl}}};
  for (const auto& [e, format] : kFormats)
    if (e == ext) return format;
  throw InvalidInput(fmt::format("'{}': unknown mesh format (expected .obj, .ply, .off or .stl)", path.string()));
}

PolyMesh read_mesh(std::string_view data, MeshFormat format, const std::string& name, Progress* progress) {
  switch (format) {
    case MeshFormat::obj:
      return read_obj(data, name, progress);
    case MeshFormat::ply:
      return read_ply(data, name, progress);
    case MeshFormat::off:
      return read_off(data, name, progress);
    case MeshFormat::stl:
      return read_stl(data, name, progress);
  }
  throw InvalidInput(fmt::format("{}: unknown mesh format", name));
}

PolyMesh read_mesh(const std::filesystem::path& path, Progress* progress) {
  const MeshFormat format = mesh_format_from_path(path);
  const MappedFile file(path);
  return read_mesh(file.view(), format, path.string(), progress);
}

PolyMesh read_mesh_with_progress(const std::filesystem::path& path) {
  const MeshFormat format = mesh_format_from_path(path);
  const MappedFile file(path);
  Progress progress("read " + path.filename().string(), int64_t(file.view().size()));
  PolyMesh mesh = read_mesh(file.view(), format, path.string(), &progress);
  progress.done();
  return mesh;
}

std::vector<std::string> unsupported_properties(const PolyMesh& mesh, MeshFormat format) {
  std::vector<std::string> lost;
  if (format == MeshFormat::obj) return lost;
  if (format == MeshFormat::stl) {
    if (!mesh.uvs.empty() || !mesh.corner_uvs.empty()) lost.emplace_back("texture coordinates");
    if (!mesh.normals.empty() || !mesh.corner_normals.empty()) lost.emplace_back("normals");
    if (!mesh.colors.empty()) lost.emplace_back("vertex colors");
  }
  if (!mesh.creases.empty()) lost.emplace_back("creases");
  if (!mesh.corners.empty()) lost.emplace_back("corners");
  return lost;
}

void write_mesh(std::ostream& out, const PolyMesh& mesh, MeshFormat format, const MeshWriteOptions& options) {
  switch (format) {
    case MeshFormat::obj:
      write_obj(out, mesh);
      return;
    case MeshFormat::ply:
      write_ply(out, split_seams(mesh), options);
      return;
    case MeshFormat::off:
      write_off(out, split_seams(mesh));
      return;
    case MeshFormat::stl:
      write_stl(out, mesh, options.binary);
      return;
  }
}

void write_mesh(const std::filesystem::path& path, const PolyMesh& mesh, const MeshWriteOptions& options) {
  const MeshFormat format = mesh_format_from_path(path);
  write_file_atomic(path, [&](std::ostream& out) { write_mesh(out, mesh, format, options); });
}

}  // namespace tessera
