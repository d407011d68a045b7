// ProgramFiles: recompiling a program when its files change.
#include "tessera/glsl/program_files.hpp"

#include <system_error>

namespace tessera::glsl {
namespace {

/// The file's modification time, or the epoch when it cannot be read (a file being replaced by an editor).
std::filesystem::file_time_type modified(const std::filesystem::path& path) {
  std::error_code error;
  const auto time = std::filesystem::last_write_time(path, error);
  return error ? std::filesystem::file_time_type{} : time;
}

}  // namespace

ProgramFiles::ProgramFiles(std::filesystem::path vertex, std::filesystem::path fragment,
                           std::function<void(Program&)> configure)
    : vertex_(std::move(vertex)),
      fragment_(std::move(fragment)),
      configure_(std::move(configure)),
      vertex_time_(modified(vertex_)),
      fragment_time_(modified(fragment_)),
      program_(compile()) {}

std::shared_ptr<Program> ProgramFiles::compile() const {
  auto program =
      std::make_shared<Program>(Program::compile(read_shader(vertex_.string()), read_shader(fragment_.string())));
  if (configure_) configure_(*program);
  return program;
}

bool ProgramFiles::reload() {
  const auto vertex_time = modified(vertex_), fragment_time = modified(fragment_);
  if (vertex_time == vertex_time_ && fragment_time == fragment_time_) return false;
  vertex_time_ = vertex_time, fragment_time_ = fragment_time;
  const std::string before = error_;
  try {
    program_ = compile();
    error_.clear();
    return true;
  } catch (const Error& e) {
    error_ = e.what();
    return error_ != before;
  }
}

}  // namespace tessera::glsl
