#pragma once
// Runs tests/mc_reference.py (scikit-image, VTK) on a field; tests skip when /usr/bin/python3 or the package is
// missing.
#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string>

#include "tessera/volume/volume.hpp"

namespace tessera::testing {

/// The output of a reference run as key=value pairs, or nullopt when the reference is not available (exit 77).
inline std::optional<std::string> run_reference(const std::string& args) {
  const std::string script = std::string(TESSERA_SOURCE_DIR) + "/libs/volume/tests/mc_reference.py";
  if (!std::filesystem::exists("/usr/bin/python3")) return std::nullopt;
  FILE* pipe = popen(fmt::format("/usr/bin/python3 {} {} 2>/dev/null", script, args).c_str(), "r");
  if (!pipe) return std::nullopt;
  std::string out;
  char buffer[4096];
  while (size_t n = fread(buffer, 1, sizeof buffer, pipe)) out.append(buffer, n);
  const int status = pclose(pipe);
  if (status != 0) return std::nullopt;
  return out;
}

/// Writes a float field as little-endian float32 raw into the temp folder; returns its path.
inline std::filesystem::path write_temp_field(const Volume<float>& v, const std::string& name) {
  const auto path =
      std::filesystem::temp_directory_path() / fmt::format("tessera_volume_test_{}_{}.raw", name, ::getpid());
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(v.voxels().data()), std::streamsize(v.voxel_count() * sizeof(float)));
  return path;
}

/// Parses "key=value" tokens.
inline std::map<std::string, double> parse_key_values(const std::string& text) {
  std::map<std::string, double> kv;
  std::istringstream in(text);
  std::string token;
  while (in >> token) {
    const auto eq = token.find('=');
    if (eq != std::string::npos) kv[token.substr(0, eq)] = std::stod(token.substr(eq + 1));
  }
  return kv;
}

}  // namespace tessera::testing
