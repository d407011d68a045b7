// ProgramFiles: a program that follows its files (live editing): an edit recompiles, an error keeps the last good
// program and says why, fixing the error recovers.
#include "tessera/glsl/program_files.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "glsl_test_util.hpp"

namespace tessera::glsl {
namespace {

struct Files {
  // A folder of the test's own: ctest runs the tests of this file at once.
  std::filesystem::path dir =
      std::filesystem::path(::testing::TempDir()) /
      (std::string("program_files_") + ::testing::UnitTest::GetInstance()->current_test_info()->name());
  std::filesystem::path vertex = dir / "a.vert", fragment = dir / "a.frag";
  int edits = 0;

  Files() {
    std::filesystem::create_directories(dir);
    std::ofstream(vertex) << testing::kFullScreenVertex;
    write_fragment("uniform float level; void main() { gl_FragColor = vec4(level, 0.0, 0.0, 1.0); }");
  }
  // Writes the fragment shader with a modification time of its own (a second later than the last edit's), as an
  // editor's save would give.
  void write_fragment(const std::string& text) {
    std::ofstream(fragment) << text;
    std::filesystem::last_write_time(fragment,
                                     std::filesystem::file_time_type::clock::now() + std::chrono::seconds(++edits));
  }
};

float red_of(const Program& p) { return testing::pixel(testing::full_screen(p, 8), 4, 4).x; }

TEST(GlslProgramFiles, EditsRecompileAndErrorsKeepTheLastGoodProgram) {
  Files files;
  ProgramFiles program(files.vertex, files.fragment, [](Program& p) { p.set_uniform_assignment("level=0.5"); });
  EXPECT_NEAR(red_of(*program.program()), 0.5f, 1.0f / 255);
  EXPECT_FALSE(program.reload());  // nothing changed

  files.write_fragment("uniform float level; void main() { gl_FragColor = vec4(level * 2.0, 0.0, 0.0, 1.0); }");
  EXPECT_TRUE(program.reload());
  EXPECT_NEAR(red_of(*program.program()), 1.0f, 1.0f / 255);  // the new source, configured again
  EXPECT_TRUE(program.error().empty());

  files.write_fragment("void main() {\n  gl_FragColor = 1.0;\n}\n");
  EXPECT_TRUE(program.reload());
  EXPECT_NE(program.error().find("a.frag:2:"), std::string::npos) << program.error();
  EXPECT_NEAR(red_of(*program.program()), 1.0f, 1.0f / 255);  // still the last good program

  // (The configured uniform must stay declared: setting one the sources do not declare is an error.)
  files.write_fragment("uniform float level; void main() { gl_FragColor = vec4(0.25, 0.0, 0.0, 1.0); }");
  EXPECT_TRUE(program.reload());
  EXPECT_TRUE(program.error().empty());
  EXPECT_NEAR(red_of(*program.program()), 0.25f, 1.0f / 255);
}

TEST(GlslProgramFiles, TheFirstCompileMustSucceed) {
  Files files;
  files.write_fragment("void main() { gl_FragColor = 1.0; }");
  EXPECT_THROW(ProgramFiles(files.vertex, files.fragment), CompileError);
  EXPECT_THROW(ProgramFiles(files.vertex, files.dir / "missing.frag"), IoError);
}

}  // namespace
}  // namespace tessera::glsl
