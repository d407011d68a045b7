#pragma once
// frames.json: what a farm's tasks have written into an output folder, with checksums and render times, so that a
// resubmission skips finished work and `tessera assemble` trusts what it stitches (docs/farm.md).
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>

namespace tessera {

/// One rendered file.
struct ManifestEntry {
  int frame = 0;
  int tile = -1, tiles = 1;  ///< tile index and count; -1 and 1 for a whole frame
  uint32_t crc32 = 0;        ///< zlib's CRC-32 of the file's bytes
  uint64_t bytes = 0;        ///< the file's size
  double seconds = 0;        ///< render time (not reading or writing)
  std::string host;          ///< the machine that rendered it
  /// What made it, as the writer describes it (the scene's checksum and the render options), so that a rerun with
  /// other settings does not take the file for its own; empty when not recorded.
  std::string settings;
};

/// The manifest of one folder: file name (relative to the folder) -> entry.
class Manifest {
 public:
  /// "<folder>/frames.json".
  static std::filesystem::path path_in(const std::filesystem::path& folder);
  /// Reads the folder's manifest; empty when there is none. Throws InvalidInput naming the file for a malformed one.
  static Manifest read(const std::filesystem::path& folder);
  /// Adds or replaces the entry of `file` (a name in `folder`) in the folder's manifest: read, changed and renamed
  /// into place under an exclusive lock on "<folder>/frames.json.lock" (flock, which NFS v4 and local file systems
  /// honour), so that tasks finishing at once keep each other's entries. Throws IoError when the lock or the write
  /// fails.
  static void record(const std::filesystem::path& folder, const std::string& file, const ManifestEntry& entry);

  /// The entry of `file`, or nullptr.
  const ManifestEntry* find(const std::string& file) const;
  /// Every entry, by file name.
  const std::map<std::string, ManifestEntry>& entries() const { return entries_; }
  /// True when `file` exists in `folder`, has an entry, and its size and CRC-32 match it: finished, whole work.
  bool verified(const std::filesystem::path& folder, const std::string& file) const;

 private:
  std::map<std::string, ManifestEntry> entries_;
};

/// zlib's CRC-32 of a file's bytes. Throws IoError when it cannot be read.
uint32_t file_crc32(const std::filesystem::path& path);
/// zlib's CRC-32 of bytes.
uint32_t crc32_of(std::string_view bytes);

/// This machine's host name (for manifest entries).
std::string host_name();

}  // namespace tessera
