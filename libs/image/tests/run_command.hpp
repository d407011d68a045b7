#pragma once
// The image tests' way to reach their independent references (python3 with PIL or zlib, ffmpeg): a shell command's
// output.
#include <cstdio>
#include <optional>
#include <string>

namespace tessera::image_test {

/// Runs `command` through the shell, its stderr discarded: its stdout, or nullopt when it cannot start or fails.
inline std::optional<std::string> run(const std::string& command) {
  FILE* pipe = ::popen((command + " 2>/dev/null").c_str(), "r");
  if (!pipe) return std::nullopt;
  std::string out;
  char buffer[4096];
  size_t n;
  while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) out.append(buffer, n);
  if (::pclose(pipe) != 0) return std::nullopt;
  return out;
}

}  // namespace tessera::image_test
