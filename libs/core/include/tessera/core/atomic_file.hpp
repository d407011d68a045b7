#pragma once
// Atomic file output: write to a temporary file beside the target, rename over it on success.
// A failure (an exception, a crash, SIGINT/SIGTERM/SIGHUP) never leaves a partial file under the target's name, and
// the temporary itself is removed on failure and on those signals.
#include <filesystem>
#include <functional>
#include <memory>
#include <ostream>
#include <string>
#include <string_view>

namespace tessera {

/// A file being written. Data goes to "<target>.tmp-<16 random hex digits>", created exclusively (O_EXCL) without
/// following links, so a symlink planted at a guessable name can never redirect the write; commit() flushes and
/// renames it to the target. Destroying an uncommitted AtomicFile removes the temporary, and so does SIGINT, SIGTERM
/// or SIGHUP (a handler installed on first use where the signal has its default action unlinks every registered
/// temporary, then re-raises the signal so the exit status still reports it). Throws IoError when the file cannot
/// be created.
class AtomicFile {
 public:
  explicit AtomicFile(std::filesystem::path target);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  /// The stream to write to.
  std::ostream& stream();
  /// Flushes, checks the stream and renames the temporary to the target. Throws IoError on any failure.
  void commit();
  /// The temporary's path (for tests and messages).
  const std::filesystem::path& temporary() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

/// Writes a file atomically through a callback that fills the stream. Throws IoError (or what write throws).
void write_file_atomic(const std::filesystem::path& target, const std::function<void(std::ostream&)>& write);

/// Writes bytes atomically.
void write_file_atomic(const std::filesystem::path& target, std::string_view bytes);

/// Reads a whole file (regular files, pipes and devices). Throws IoError naming the file when it cannot be read,
/// and "'<path>': is a directory, expected a file" for a folder.
std::string read_file(const std::filesystem::path& path);

}  // namespace tessera
