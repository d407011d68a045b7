#pragma once
// Atomic file output: write to a temporary file beside the target, rename over it on success.
// A failure (an exception, a crash) never leaves a partial file under the target's name.
#include <filesystem>
#include <fstream>
#include <functional>
#include <string_view>

namespace tessera {

/// A file being written. Data goes to "<target>.tmp-<unique>"; commit() flushes and renames it to the target.
/// Destroying an uncommitted AtomicFile removes the temporary. Throws IoError when the file cannot be created.
class AtomicFile {
 public:
  explicit AtomicFile(std::filesystem::path target, bool binary = true);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  /// The stream to write to.
  std::ofstream& stream() { return out_; }
  /// Flushes, checks the stream and renames the temporary to the target. Throws IoError on any failure.
  void commit();

 private:
  std::filesystem::path target_;
  std::filesystem::path temp_;
  std::ofstream out_;
  bool committed_ = false;
};

/// Writes a file atomically through a callback that fills the stream. Throws IoError (or what write throws).
void write_file_atomic(const std::filesystem::path& target, const std::function<void(std::ostream&)>& write,
                       bool binary = true);

/// Writes bytes atomically.
void write_file_atomic(const std::filesystem::path& target, std::string_view bytes);

/// Reads a whole file. Throws IoError naming the file when it cannot be read.
std::string read_file(const std::filesystem::path& path);

}  // namespace tessera
