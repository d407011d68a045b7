#include "tessera/core/atomic_file.hpp"

#include <atomic>
#include <cerrno>
#include <cstring>
#include <system_error>

#include <unistd.h>

#include "tessera/core/error.hpp"

namespace tessera {
namespace {
std::filesystem::path temp_name(const std::filesystem::path& target) {
  static std::atomic<unsigned> counter{0};
  auto name = target.filename().string() + fmt::format(".tmp-{}-{}", ::getpid(), counter++);
  return target.parent_path() / name;
}
}  // namespace

AtomicFile::AtomicFile(std::filesystem::path target, bool binary)
    : target_(std::move(target)), temp_(temp_name(target_)) {
  out_.open(temp_, binary ? std::ios::binary | std::ios::out | std::ios::trunc : std::ios::out | std::ios::trunc);
  if (!out_) throw IoError(fmt::format("cannot create '{}': {}", target_.string(), std::strerror(errno)));
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    out_.close();
    std::error_code ec;
    std::filesystem::remove(temp_, ec);
  }
}

void AtomicFile::commit() {
  out_.flush();
  if (!out_) throw IoError(fmt::format("cannot write '{}'", target_.string()));
  out_.close();
  std::error_code ec;
  std::filesystem::rename(temp_, target_, ec);
  if (ec) throw IoError(fmt::format("cannot write '{}': {}", target_.string(), ec.message()));
  committed_ = true;
}

void write_file_atomic(const std::filesystem::path& target, const std::function<void(std::ostream&)>& write,
                       bool binary) {
  AtomicFile file(target, binary);
  write(file.stream());
  file.commit();
}

void write_file_atomic(const std::filesystem::path& target, std::string_view bytes) {
  write_file_atomic(target, [&](std::ostream& out) { out.write(bytes.data(), std::streamsize(bytes.size())); });
}

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(fmt::format("cannot open '{}': {}", path.string(), std::strerror(errno)));
  std::string data;
  in.seekg(0, std::ios::end);
  const auto size = in.tellg();
  if (size < 0) throw IoError(fmt::format("cannot read '{}'", path.string()));
  data.resize(static_cast<size_t>(size));
  in.seekg(0);
  in.read(data.data(), size);
  if (!in) throw IoError(fmt::format("cannot read '{}'", path.string()));
  return data;
}

}  // namespace tessera
