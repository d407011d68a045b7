#include "osmesa_glsl.hpp"

#include <algorithm>
#include <chrono>
#include <map>
#include <string_view>

#define GL_GLEXT_PROTOTYPES  // OpenGL 2.0+ entry points: libOSMesa exports them
#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/osmesa.h>
#include <fmt/format.h>

#include <glm/gtc/type_ptr.hpp>

#include "tessera/core/error.hpp"

namespace tessera::reference {

namespace {

void load_matrix(GLenum mode, const Mat4f& m) {
  glMatrixMode(mode);
  glLoadMatrixf(glm::value_ptr(m));
}

void check_gl(const char* what) {
  if (const GLenum error = glGetError(); error != GL_NO_ERROR)
    throw Error(fmt::format("OpenGL error 0x{:x} {}", error, what));
}

GLuint compile_shader(GLenum kind, const std::string& source) {
  const GLuint shader = glCreateShader(kind);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE, length = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok == GL_TRUE) return shader;
  glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
  std::string log(size_t(std::max(length, 1)), '\0');
  glGetShaderInfoLog(shader, GLsizei(log.size()), nullptr, log.data());
  glDeleteShader(shader);
  log.resize(log.find('\0') == std::string::npos ? log.size() : log.find('\0'));
  throw InvalidInput(fmt::format("Mesa GLSL: the {} shader does not compile:\n{}",
                                 kind == GL_VERTEX_SHADER ? "vertex" : "fragment", log));
}

enum class UniformKind { floats, matrix, ints, bools, other };

// How many scalars one element of an active uniform's type holds, and how its values are set.
std::pair<UniformKind, int> uniform_kind(GLenum type) {
  switch (type) {
    case GL_FLOAT:
      return {UniformKind::floats, 1};
    case GL_FLOAT_VEC2:
      return {UniformKind::floats, 2};
    case GL_FLOAT_VEC3:
      return {UniformKind::floats, 3};
    case GL_FLOAT_VEC4:
      return {UniformKind::floats, 4};
    case GL_FLOAT_MAT2:
      return {UniformKind::matrix, 4};
    case GL_FLOAT_MAT3:
      return {UniformKind::matrix, 9};
    case GL_FLOAT_MAT4:
      return {UniformKind::matrix, 16};
    case GL_FLOAT_MAT2x3:
    case GL_FLOAT_MAT3x2:
      return {UniformKind::matrix, 6};
    case GL_FLOAT_MAT2x4:
    case GL_FLOAT_MAT4x2:
      return {UniformKind::matrix, 8};
    case GL_FLOAT_MAT3x4:
    case GL_FLOAT_MAT4x3:
      return {UniformKind::matrix, 12};
    case GL_INT:
    case GL_UNSIGNED_INT:
    case GL_SAMPLER_1D:
    case GL_SAMPLER_2D:
    case GL_SAMPLER_3D:
    case GL_SAMPLER_CUBE:
    case GL_SAMPLER_2D_SHADOW:
      return {UniformKind::ints, 1};
    case GL_INT_VEC2:
      return {UniformKind::ints, 2};
    case GL_INT_VEC3:
      return {UniformKind::ints, 3};
    case GL_INT_VEC4:
      return {UniformKind::ints, 4};
    case GL_BOOL:
      return {UniformKind::bools, 1};
    case GL_BOOL_VEC2:
      return {UniformKind::bools, 2};
    case GL_BOOL_VEC3:
      return {UniformKind::bools, 3};
    case GL_BOOL_VEC4:
      return {UniformKind::bools, 4};
    default:
      return {UniformKind::other, 0};
  }
}

void set_float_uniform(GLint location, GLenum type, int components, const std::vector<float>& v) {
  const auto count = GLsizei(v.size() / size_t(components));
  const float* p = v.data();
  switch (type) {
    case GL_FLOAT_MAT2:
      return glUniformMatrix2fv(location, count, GL_FALSE, p);
    case GL_FLOAT_MAT3:
      return glUniformMatrix3fv(location, count, GL_FALSE, p);
    case GL_FLOAT_MAT4:
      return glUniformMatrix4fv(location, count, GL_FALSE, p);
    case GL_FLOAT_MAT2x3:
      return glUniformMatrix2x3fv(location, count, GL_FALSE, p);
    case GL_FLOAT_MAT3x2:
      return glUniformMatrix3x2fv(location, count, GL_FALSE, p);
    case GL_FLOAT_MAT2x4:
      return glUniformMatrix2x4fv(location, count, GL_FALSE, p);
    case GL_FLOAT_MAT4x2:
      return glUniformMatrix4x2fv(location, count, GL_FALSE, p);
    case GL_FLOAT_MAT3x4:
      return glUniformMatrix3x4fv(location, count, GL_FALSE, p);
    case GL_FLOAT_MAT4x3:
      return glUniformMatrix4x3fv(location, count, GL_FALSE, p);
    default:
      break;
  }
  switch (components) {  // float and bool vectors
    case 1:
      return glUniform1fv(location, count, p);
    case 2:
      return glUniform2fv(location, count, p);
    case 3:
      return glUniform3fv(location, count, p);
    default:
      return glUniform4fv(location, count, p);
  }
}

void set_int_uniform(GLint location, int components, const std::vector<int>& v) {
  const auto count = GLsizei(v.size() / size_t(components));
  switch (components) {
    case 1:
      return glUniform1iv(location, count, v.data());
    case 2:
      return glUniform2iv(location, count, v.data());
    case 3:
      return glUniform3iv(location, count, v.data());
    default:
      return glUniform4iv(location, count, v.data());
  }
}

GLint min_filter(GlFilter f) {
  switch (f) {
    case GlFilter::nearest:
      return GL_NEAREST;
    case GlFilter::linear:
      return GL_LINEAR;
    case GlFilter::linear_mipmap_linear:
      return GL_LINEAR_MIPMAP_LINEAR;
  }
  return GL_LINEAR;
}

GLint mag_filter(GlFilter f) { return f == GlFilter::nearest ? GL_NEAREST : GL_LINEAR; }

}  // namespace

struct GlslRenderer::Impl {
  int width = 0, height = 0;
  std::vector<uint8_t> buffer;  // OSMesa's RGBA color buffer
  GlslDraw draw;                // the client arrays point into it
  OSMesaContext context = nullptr;
  GLuint program = 0;
  std::vector<GLuint> textures;
  std::vector<std::string> active_uniforms;
  std::map<std::string, std::pair<GLenum, GLint>, std::less<>> uniform_types;  // name -> (type, array size)

  ~Impl() {
    if (context != nullptr) OSMesaDestroyContext(context);  // its shaders, program and textures with it
  }

  void make_current() {
    if (!OSMesaMakeCurrent(context, buffer.data(), GL_UNSIGNED_BYTE, width, height))
      throw Error("OSMesa: OSMesaMakeCurrent failed");
  }

  void create_context() {
    // Compatibility profile, no version asked: Mesa gives its highest (4.5 compatibility on llvmpipe 22.3).
    const int attributes[] = {OSMESA_FORMAT,
                              OSMESA_RGBA,
                              OSMESA_DEPTH_BITS,
                              24,
                              OSMESA_STENCIL_BITS,
                              8,
                              OSMESA_ACCUM_BITS,
                              0,
                              OSMESA_PROFILE,
                              OSMESA_COMPAT_PROFILE,
                              0};
    context = OSMesaCreateContextAttribs(attributes, nullptr);
    if (context == nullptr) throw Error("OSMesa: OSMesaCreateContextAttribs (compatibility profile) failed");
    make_current();
    GLint depth_bits = 0, stencil_bits = 0;
    glGetIntegerv(GL_DEPTH_BITS, &depth_bits);
    glGetIntegerv(GL_STENCIL_BITS, &stencil_bits);
    if (depth_bits != 24 || stencil_bits != 8)
      throw Error(fmt::format("OSMesa: expected a 24-bit depth and an 8-bit stencil buffer, got {} and {} bits",
                              depth_bits, stencil_bits));
    glViewport(0, 0, width, height);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  }

  void link_program() {
    const GLuint vs = compile_shader(GL_VERTEX_SHADER, draw.vertex_source);
    GLuint fs = 0;
    try {
      fs = compile_shader(GL_FRAGMENT_SHADER, draw.fragment_source);
    } catch (...) {
      glDeleteShader(vs);
      throw;
    }
    program = glCreateProgram();
    glAttachShader(program, vs);
    glAttachShader(program, fs);
    glLinkProgram(program);
    glDeleteShader(vs);  // flagged: freed with the program
    glDeleteShader(fs);
    GLint ok = GL_FALSE, length = 0;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (ok != GL_TRUE) {
      glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
      std::string log(size_t(std::max(length, 1)), '\0');
      glGetProgramInfoLog(program, GLsizei(log.size()), nullptr, log.data());
      log.resize(log.find('\0') == std::string::npos ? log.size() : log.find('\0'));
      throw InvalidInput(fmt::format("Mesa GLSL: the program does not link:\n{}", log));
    }
    glUseProgram(program);
    GLint count = 0, max_length = 0;
    glGetProgramiv(program, GL_ACTIVE_UNIFORMS, &count);
    glGetProgramiv(program, GL_ACTIVE_UNIFORM_MAX_LENGTH, &max_length);
    std::vector<char> name(size_t(std::max(max_length, 1)));
    for (GLint i = 0; i < count; ++i) {
      GLsizei length_out = 0;
      GLint size = 0;
      GLenum type = 0;
      glGetActiveUniform(program, GLuint(i), GLsizei(name.size()), &length_out, &size, &type, name.data());
      std::string n(name.data(), size_t(length_out));
      uniform_types[n] = {type, size};
      active_uniforms.push_back(std::move(n));
    }
  }

  // The active uniform's type that `name` sets: itself, or its array's ("a" and "a[2]" are elements of "a[0]").
  const std::pair<GLenum, GLint>* find_uniform(const std::string& name) const {
    if (auto it = uniform_types.find(name); it != uniform_types.end()) return &it->second;
    const std::string base = name.back() == ']' ? name.substr(0, name.rfind('[')) : name;
    if (auto it = uniform_types.find(base + "[0]"); it != uniform_types.end()) return &it->second;
    return nullptr;
  }

  void set_uniforms() {
    for (const GlslUniform& u : draw.uniforms) {
      if (u.name.empty()) throw InvalidInput("Mesa GLSL: a uniform without a name");
      if (!u.floats.empty() && !u.ints.empty())
        throw InvalidInput(fmt::format("Mesa GLSL: uniform {} has both floats and ints", u.name));
      const auto* found = find_uniform(u.name);
      const GLint location = glGetUniformLocation(program, u.name.c_str());
      if (found == nullptr || location < 0) continue;  // not active: OpenGL ignores location -1
      const GLenum type = found->first;
      const auto [kind, components] = uniform_kind(type);
      if (kind == UniformKind::other)
        throw InvalidInput(
            fmt::format("Mesa GLSL: uniform {} has a type (0x{:x}) this renderer does not set", u.name, type));
      const size_t n = u.floats.empty() ? u.ints.size() : u.floats.size();
      if (n == 0 || n % size_t(components) != 0)
        throw InvalidInput(
            fmt::format("Mesa GLSL: uniform {} takes a multiple of {} values, got {}", u.name, components, n));
      if (!u.floats.empty()) {
        if (kind == UniformKind::ints)
          throw InvalidInput(fmt::format("Mesa GLSL: uniform {} is an int or sampler: give ints", u.name));
        set_float_uniform(location, type, components, u.floats);
      } else {
        if (kind == UniformKind::floats || kind == UniformKind::matrix)
          throw InvalidInput(fmt::format("Mesa GLSL: uniform {} is a float type: give floats", u.name));
        set_int_uniform(location, components, u.ints);
      }
      check_gl(fmt::format("setting uniform {}", u.name).c_str());
    }
  }

  void set_fixed_function() {
    if (draw.lights.size() > 8) throw InvalidInput("Mesa GLSL: at most 8 lights");
    // The lights are placed in eye space: glLightfv(GL_POSITION) transforms by the model-view in force.
    load_matrix(GL_MODELVIEW, Mat4f(1.0f));
    for (size_t i = 0; i < draw.lights.size(); ++i) {
      const GLenum light = GL_LIGHT0 + GLenum(i);
      const GlLight& l = draw.lights[i];
      glLightfv(light, GL_POSITION, glm::value_ptr(l.position));
      glLightfv(light, GL_AMBIENT, glm::value_ptr(l.ambient));
      glLightfv(light, GL_DIFFUSE, glm::value_ptr(l.diffuse));
      glLightfv(light, GL_SPECULAR, glm::value_ptr(l.specular));
    }
    const GlMaterial& m = draw.material;
    glMaterialfv(GL_FRONT_AND_BACK, GL_AMBIENT, glm::value_ptr(m.ambient));
    glMaterialfv(GL_FRONT_AND_BACK, GL_DIFFUSE, glm::value_ptr(m.diffuse));
    glMaterialfv(GL_FRONT_AND_BACK, GL_SPECULAR, glm::value_ptr(m.specular));
    glMaterialfv(GL_FRONT_AND_BACK, GL_EMISSION, glm::value_ptr(m.emission));
    glMaterialf(GL_FRONT_AND_BACK, GL_SHININESS, m.shininess);
    load_matrix(GL_PROJECTION, draw.projection);
    load_matrix(GL_MODELVIEW, draw.model_view);
    glColor4fv(glm::value_ptr(draw.current_color));
    if (draw.depth_test) {
      glEnable(GL_DEPTH_TEST);
      glDepthFunc(GL_LESS);
    } else {
      glDisable(GL_DEPTH_TEST);
    }
    if (draw.cull_back) {
      glEnable(GL_CULL_FACE);
      glCullFace(GL_BACK);
      glFrontFace(GL_CCW);
    } else {
      glDisable(GL_CULL_FACE);
    }
    if (draw.seamless_cube_maps) glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    glClearColor(draw.clear_color.x, draw.clear_color.y, draw.clear_color.z, draw.clear_color.w);
    glClearDepth(1.0);
    check_gl("setting the fixed-function state");
  }

  void upload_textures() {
    GLint units = 0;
    glGetIntegerv(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS, &units);
    const auto bind_unit = [&](int unit, GLenum target) {
      if (unit < 0 || unit >= units)
        throw InvalidInput(fmt::format("Mesa GLSL: texture unit {} out of range [0, {})", unit, units));
      GLuint texture = 0;
      glGenTextures(1, &texture);
      textures.push_back(texture);
      glActiveTexture(GL_TEXTURE0 + GLenum(unit));
      glBindTexture(target, texture);
    };
    for (const auto& [unit, t] : draw.textures) {
      if (t.width <= 0 || t.height <= 0 || t.rgba.size() != size_t(t.width) * size_t(t.height) * 4)
        throw InvalidInput(fmt::format("Mesa GLSL: texture at unit {} is {}x{} with {} bytes", unit, t.width, t.height,
                                       t.rgba.size()));
      bind_unit(unit, GL_TEXTURE_2D);
      const GLint wrap = t.wrap == GlslWrap::repeat ? GL_REPEAT : GL_CLAMP_TO_EDGE;
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, wrap);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, wrap);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, min_filter(t.filter));
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, mag_filter(t.filter));
      glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, t.width, t.height, 0, GL_RGBA, GL_UNSIGNED_BYTE, t.rgba.data());
      if (t.filter == GlFilter::linear_mipmap_linear) glGenerateMipmap(GL_TEXTURE_2D);
      check_gl(fmt::format("uploading the texture of unit {}", unit).c_str());
    }
    for (const auto& [unit, c] : draw.cube_maps) {
      const size_t face_bytes = size_t(c.size) * size_t(c.size) * 4;
      if (c.size <= 0 ||
          std::any_of(c.faces.begin(), c.faces.end(), [&](const auto& f) { return f.size() != face_bytes; }))
        throw InvalidInput(fmt::format("Mesa GLSL: cube map at unit {} of size {} needs 6 faces of {} bytes", unit,
                                       c.size, face_bytes));
      bind_unit(unit, GL_TEXTURE_CUBE_MAP);
      for (const GLenum p : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
        glTexParameteri(GL_TEXTURE_CUBE_MAP, p, GL_CLAMP_TO_EDGE);
      glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MIN_FILTER, min_filter(c.filter));
      glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAG_FILTER, mag_filter(c.filter));
      for (int face = 0; face < 6; ++face)
        glTexImage2D(GL_TEXTURE_CUBE_MAP_POSITIVE_X + GLenum(face), 0, GL_RGBA8, c.size, c.size, 0, GL_RGBA,
                     GL_UNSIGNED_BYTE, c.faces[size_t(face)].data());
      if (c.filter == GlFilter::linear_mipmap_linear) glGenerateMipmap(GL_TEXTURE_CUBE_MAP);
      check_gl(fmt::format("uploading the cube map of unit {}", unit).c_str());
    }
    glActiveTexture(GL_TEXTURE0);
  }

  void bind_arrays() {
    size_t vertices = draw.positions.size();
    if (draw.positions.empty() && !draw.attributes.empty() && draw.attributes.front().components > 0)
      vertices = draw.attributes.front().data.size() / size_t(draw.attributes.front().components);
    const auto check_size = [&](size_t size, const char* what) {
      if (size != 0 && size != vertices)
        throw InvalidInput(fmt::format("Mesa GLSL: {} {} for {} vertices", size, what, vertices));
    };
    check_size(draw.normals.size(), "normals");
    check_size(draw.colors.size(), "colors");
    check_size(draw.uvs.size(), "texture coordinates");
    if (draw.indices.size() % 3 != 0)
      throw InvalidInput(fmt::format("Mesa GLSL: {} indices is not whole triangles", draw.indices.size()));
    for (const uint32_t i : draw.indices)
      if (i >= vertices) throw InvalidInput(fmt::format("Mesa GLSL: index {} of {} vertices", i, vertices));
    if (!draw.positions.empty()) {
      glEnableClientState(GL_VERTEX_ARRAY);
      glVertexPointer(3, GL_FLOAT, 0, draw.positions.data());
    }
    if (!draw.normals.empty()) {
      glEnableClientState(GL_NORMAL_ARRAY);
      glNormalPointer(GL_FLOAT, 0, draw.normals.data());
    }
    if (!draw.colors.empty()) {
      glEnableClientState(GL_COLOR_ARRAY);
      glColorPointer(3, GL_FLOAT, 0, draw.colors.data());
    }
    if (!draw.uvs.empty()) {
      glClientActiveTexture(GL_TEXTURE0);
      glEnableClientState(GL_TEXTURE_COORD_ARRAY);
      glTexCoordPointer(2, GL_FLOAT, 0, draw.uvs.data());
    }
    for (const GlslAttribute& a : draw.attributes) {
      if (a.components < 1 || a.components > 4 || a.data.size() != size_t(a.components) * vertices)
        throw InvalidInput(fmt::format("Mesa GLSL: attribute {} has {} floats of {} components for {} vertices", a.name,
                                       a.data.size(), a.components, vertices));
      const GLint location = glGetAttribLocation(program, a.name.c_str());
      if (location < 0) continue;  // not an active attribute
      glEnableVertexAttribArray(GLuint(location));
      glVertexAttribPointer(GLuint(location), a.components, GL_FLOAT, GL_FALSE, 0, a.data.data());
    }
    check_gl("binding the vertex arrays");
  }

  void draw_frame() {
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
    glDrawElements(GL_TRIANGLES, GLsizei(draw.indices.size()), GL_UNSIGNED_INT, draw.indices.data());
  }
};

GlslRenderer::GlslRenderer(const GlslDraw& draw, int width, int height) : impl_(std::make_unique<Impl>()) {
  if (width <= 0 || height <= 0) throw InvalidInput(fmt::format("OSMesa: bad size {}x{}", width, height));
  Impl& s = *impl_;
  s.width = width;
  s.height = height;
  s.buffer.resize(size_t(width) * size_t(height) * 4);
  s.draw = draw;
  s.create_context();
  s.link_program();
  s.set_uniforms();
  s.set_fixed_function();
  s.upload_textures();
  s.bind_arrays();
}

GlslRenderer::~GlslRenderer() = default;
GlslRenderer::GlslRenderer(GlslRenderer&&) noexcept = default;
GlslRenderer& GlslRenderer::operator=(GlslRenderer&&) noexcept = default;

int GlslRenderer::width() const { return impl_->width; }
int GlslRenderer::height() const { return impl_->height; }
const std::vector<std::string>& GlslRenderer::active_uniforms() const { return impl_->active_uniforms; }

std::vector<uint8_t> GlslRenderer::render() {
  Impl& s = *impl_;
  s.make_current();
  s.draw_frame();
  glFinish();
  const size_t w = size_t(s.width), h = size_t(s.height), row_bytes = w * 4;
  std::vector<uint8_t> gl_rows(w * h * 4), image(w * h * 4);
  glReadPixels(0, 0, s.width, s.height, GL_RGBA, GL_UNSIGNED_BYTE, gl_rows.data());
  check_gl("drawing");
  for (size_t row = 0; row < h; ++row)  // GL row 0 is the bottom
    std::copy_n(gl_rows.begin() + std::ptrdiff_t((h - 1 - row) * row_bytes), row_bytes,
                image.begin() + std::ptrdiff_t(row * row_bytes));
  return image;
}

std::vector<float> GlslRenderer::depth() {
  Impl& s = *impl_;
  s.make_current();
  const size_t w = size_t(s.width), h = size_t(s.height);
  std::vector<float> gl_rows(w * h), out(w * h);
  glReadPixels(0, 0, s.width, s.height, GL_DEPTH_COMPONENT, GL_FLOAT, gl_rows.data());
  check_gl("reading the depth buffer");
  for (size_t row = 0; row < h; ++row)  // GL row 0 is the bottom
    std::copy_n(gl_rows.begin() + std::ptrdiff_t((h - 1 - row) * w), w, out.begin() + std::ptrdiff_t(row * w));
  return out;
}

double GlslRenderer::time_draws(int repeat) {
  Impl& s = *impl_;
  s.make_current();
  s.draw_frame();  // warm-up: llvmpipe compiles the shader variant on the first draw
  glFinish();
  check_gl("drawing");
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < repeat; ++i) {
    s.draw_frame();
    glFinish();
  }
  const auto stop = std::chrono::steady_clock::now();
  check_gl("drawing");
  return std::chrono::duration<double, std::milli>(stop - start).count();
}

std::vector<uint8_t> render_glsl(const GlslDraw& draw, int width, int height) {
  return GlslRenderer(draw, width, height).render();
}

double time_glsl(const GlslDraw& draw, int width, int height, int repeat) {
  return GlslRenderer(draw, width, height).time_draws(repeat);
}

}  // namespace tessera::reference
