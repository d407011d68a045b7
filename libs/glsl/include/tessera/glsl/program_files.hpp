#pragma once
// A GLSL program read from two shader files and compiled again when either changes on disk: live editing in the
// viewer (`tessera view MESH --vertex-shader a.vert --fragment-shader a.frag`) and in sketches.
#include <filesystem>
#include <functional>
#include <memory>
#include <string>

#include "tessera/glsl/program.hpp"

namespace tessera::glsl {

class ProgramFiles {
 public:
  /// Reads and compiles the two files, then calls `configure` on the program (its uniforms and textures; again after
  /// every recompile). Throws as read_shader and Program::compile, and what `configure` throws.
  ProgramFiles(std::filesystem::path vertex, std::filesystem::path fragment,
               std::function<void(Program&)> configure = {});

  /// Compiles again when a file's modification time differs from the last attempt's. Returns true when the program
  /// or the error changed (what is drawn or said should be updated). A failed compile, or a file that cannot be read,
  /// keeps the previous program and sets error() until a compile succeeds.
  bool reload();

  /// The current program (a new one after each successful reload: share it with what draws it).
  const std::shared_ptr<Program>& program() const { return program_; }
  /// Why the last reload failed ("a.frag:3: ..."), or empty.
  const std::string& error() const { return error_; }
  /// The fragment shader's file name, for messages.
  std::string name() const { return fragment_.filename().string(); }

 private:
  std::shared_ptr<Program> compile() const;

  std::filesystem::path vertex_, fragment_;
  std::function<void(Program&)> configure_;
  std::filesystem::file_time_type vertex_time_, fragment_time_;
  std::shared_ptr<Program> program_;
  std::string error_;
};

}  // namespace tessera::glsl
