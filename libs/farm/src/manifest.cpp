#include "tessera/farm/manifest.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/file.h>
#include <unistd.h>
#include <zlib.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>

#include "tessera/core/atomic_file.hpp"
#include "tessera/core/error.hpp"
#include "tessera/core/parse.hpp"

namespace tessera {

namespace fs = std::filesystem;
using Json = nlohmann::json;

namespace {

// An exclusive flock on a file, held for the object's life.
class FileLock {
 public:
  explicit FileLock(const fs::path& path) : fd_(::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644)) {
    if (fd_ < 0 || ::flock(fd_, LOCK_EX) != 0)
      throw IoError(fmt::format("'{}': cannot lock: {}", printable(path.string(), 1024), std::strerror(errno)));
  }
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;
  ~FileLock() {
    if (fd_ >= 0) ::close(fd_);  // closing releases the lock
  }

 private:
  int fd_;
};

Json to_json(const ManifestEntry& e) {
  Json j = {{"frame", e.frame},
            {"crc32", fmt::format("{:08x}", e.crc32)},
            {"bytes", e.bytes},
            {"seconds", e.seconds},
            {"host", e.host}};
  if (e.tile >= 0) j["tile"] = {e.tile, e.tiles};
  if (!e.settings.empty()) j["settings"] = e.settings;
  return j;
}

ManifestEntry from_json(const Json& j, const std::string& where) {
  try {
    ManifestEntry e;
    e.frame = j.at("frame").get<int>();
    e.crc32 = uint32_t(std::stoul(j.at("crc32").get<std::string>(), nullptr, 16));
    e.bytes = j.at("bytes").get<uint64_t>();
    e.seconds = j.at("seconds").get<double>();
    e.host = j.value("host", "");
    e.settings = j.value("settings", "");
    if (j.contains("tile")) {
      e.tile = j["tile"].at(0).get<int>();
      e.tiles = j["tile"].at(1).get<int>();
    }
    return e;
  } catch (const std::exception& error) {
    throw InvalidInput(
        fmt::format("{}: expected frame, crc32 (hex), bytes, seconds and host: {}", where, printable(error.what())));
  }
}

}  // namespace

fs::path Manifest::path_in(const fs::path& folder) { return folder / "frames.json"; }

Manifest Manifest::read(const fs::path& folder) {
  Manifest m;
  const fs::path path = path_in(folder);
  if (!fs::exists(path)) return m;
  const std::string text = read_file(path);
  const Json doc = Json::parse(text, nullptr, false);
  if (doc.is_discarded() || !doc.is_object() || !doc.contains("files") || !doc["files"].is_object())
    throw InvalidInput(fmt::format("'{}': expected a JSON object with \"files\" (a Tessera frames manifest)",
                                   printable(path.string(), 1024)));
  for (const auto& [file, entry] : doc["files"].items())
    m.entries_[file] = from_json(entry, fmt::format("'{}': files.{}", printable(path.string(), 1024), printable(file)));
  return m;
}

void Manifest::record(const fs::path& folder, const std::string& file, const ManifestEntry& entry) {
  const FileLock lock(path_in(folder).string() + ".lock");
  Manifest m = read(folder);
  m.entries_[file] = entry;
  Json files = Json::object();
  for (const auto& [name, e] : m.entries_) files[name] = to_json(e);
  write_file_atomic(path_in(folder), Json{{"version", 1}, {"files", files}}.dump(1) + "\n");
}

const ManifestEntry* Manifest::find(const std::string& file) const {
  const auto it = entries_.find(file);
  return it == entries_.end() ? nullptr : &it->second;
}

bool Manifest::verified(const fs::path& folder, const std::string& file) const {
  const ManifestEntry* e = find(file);
  std::error_code ec;
  const fs::path path = folder / file;
  if (!e || !fs::is_regular_file(path, ec) || fs::file_size(path, ec) != e->bytes) return false;
  return file_crc32(path) == e->crc32;
}

uint32_t file_crc32(const fs::path& path) { return crc32_of(read_file(path)); }

uint32_t crc32_of(std::string_view bytes) {
  uLong crc = crc32(0L, Z_NULL, 0);
  for (size_t at = 0; at < bytes.size(); at += 1u << 30) {
    const size_t n = std::min(bytes.size() - at, size_t(1) << 30);
    crc = crc32(crc, reinterpret_cast<const Bytef*>(bytes.data() + at), uInt(n));
  }
  return uint32_t(crc);
}

std::string host_name() {
  char name[256] = {};
  if (::gethostname(name, sizeof name - 1) != 0) return "unknown";
  return name;
}

}  // namespace tessera
