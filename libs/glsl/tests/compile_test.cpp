// Compiling: glslang's messages reach the user with the file and line; the uniform table; uniform setting errors.
#include <gtest/gtest.h>

#include "glsl_test_util.hpp"

namespace tessera::glsl {
namespace {

using testing::compile;

std::string compile_error(const std::string& fragment, const std::string& vertex = testing::kFullScreenVertex) {
  try {
    compile(fragment, vertex);
  } catch (const CompileError& e) {
    return e.what();
  }
  return "";
}

TEST(GlslCompile, SyntaxErrorNamesFileAndLine) {
  const std::string message = compile_error("void main() {\n  gl_FragColor = vec4(1.0);\n  float x = ;\n}\n");
  EXPECT_NE(message.find("test.frag:3:"), std::string::npos) << message;
}

TEST(GlslCompile, TypeErrorNamesFileAndLine) {
  const std::string message = compile_error("uniform vec3 c;\nvoid main() {\n  gl_FragColor = c;\n}\n");
  EXPECT_NE(message.find("test.frag:3:"), std::string::npos) << message;
}

TEST(GlslCompile, VertexShaderMustWritePosition) {
  const std::string message = compile_error("void main() { gl_FragColor = vec4(1.0); }", "void main() {}");
  EXPECT_NE(message.find("gl_Position"), std::string::npos) << message;
}

TEST(GlslCompile, ListsUserUniformsFlattened) {
  Program p = compile(R"(
    struct Light { vec3 color; float power; };
    uniform Light light;
    uniform float weights[3];
    uniform sampler2D image;
    uniform mat3 m;
    void main() {
      vec3 c = light.color * light.power * (weights[0] + weights[1] + weights[2]);
      gl_FragColor = vec4(m * c, 1.0) + texture2D(image, gl_TexCoord[0].st);
    })");
  std::vector<std::string> names;
  for (const UniformInfo& u : p.uniforms()) names.push_back(u.name);
  for (const char* expected : {"light.color", "light.power", "weights[0]", "weights[2]", "image", "m"})
    EXPECT_NE(std::find(names.begin(), names.end(), expected), names.end()) << expected;
  EXPECT_TRUE(p.has_uniform("weights"));
  EXPECT_FALSE(p.has_uniform("gl_ModelViewMatrix"));  // built-ins are set_fixed_function's
  EXPECT_FALSE(p.discards());
}

TEST(GlslCompile, UniformSettingErrors) {
  Program p = compile("uniform vec3 c; uniform int n; void main() { gl_FragColor = vec4(c * float(n), 1.0); }");
  const float three[3] = {1, 2, 3}, four[4] = {1, 2, 3, 4};
  const int one[1] = {1};
  EXPECT_NO_THROW(p.set_uniform("c", three));
  EXPECT_THROW(p.set_uniform("c", four), InvalidInput);  // too many values
  EXPECT_THROW(p.set_uniform("nothing", three), InvalidInput);
  EXPECT_THROW(p.set_uniform("c", one), InvalidInput);    // ints to a float uniform
  EXPECT_THROW(p.set_uniform("n", three), InvalidInput);  // floats to an int uniform
  EXPECT_NO_THROW(p.set_uniform_text("n", "4"));
  EXPECT_THROW(p.set_uniform_text("n", "4.5"), InvalidInput);
  EXPECT_THROW(p.set_uniform_text("c", "1,x,3"), InvalidInput);
}

TEST(GlslCompile, ModernDialect) {
  EXPECT_NO_THROW(Program::compile({R"(#version 330
    layout(location = 0) in vec3 position;
    out vec3 p;
    void main() { p = position; gl_Position = vec4(position, 1.0); })",
                                    "a.vert"},
                                   {R"(#version 330
    in vec3 p;
    out vec4 frag_color;
    void main() { frag_color = vec4(abs(p), 1.0); })",
                                    "a.frag"}));
}

}  // namespace
}  // namespace tessera::glsl
