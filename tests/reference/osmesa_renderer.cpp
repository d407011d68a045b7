#include "osmesa_renderer.hpp"

#include <algorithm>
#include <cstdlib>
#include <mutex>
#include <string>

#define GL_GLEXT_PROTOTYPES  // glStencilFuncSeparate, glStencilOpSeparate, glStencilMaskSeparate (OpenGL 2.0)
#include <GL/osmesa.h>
#include <fmt/format.h>

#include <glm/gtc/type_ptr.hpp>

#include "tessera/core/error.hpp"

namespace tessera::reference {

GlMesh::GlMesh(const TriMesh& mesh) : indices(mesh.indices) {
  const auto to_floats = [](const std::vector<Vec3>& v) {
    std::vector<float> out;
    out.reserve(v.size() * 3);
    for (const Vec3& p : v) out.insert(out.end(), {float(p.x), float(p.y), float(p.z)});
    return out;
  };
  positions = to_floats(mesh.positions);
  normals = to_floats(mesh.normals);
  colors = to_floats(mesh.colors);
  for (const Vec2& t : mesh.uvs) texcoords.insert(texcoords.end(), {float(t.x), float(t.y)});
}

namespace {

// LP_NUM_THREADS as it was when the first context was created (llvmpipe creates one screen per process then).
std::once_flag g_first_context;
int g_rasterizer_threads = -1;

void load_matrix(GLenum mode, const Mat4f& m) {
  glMatrixMode(mode);
  glLoadMatrixf(glm::value_ptr(m));
}

GLenum gl_compare(GlCompare f) {
  switch (f) {
    case GlCompare::never:
      return GL_NEVER;
    case GlCompare::less:
      return GL_LESS;
    case GlCompare::equal:
      return GL_EQUAL;
    case GlCompare::lequal:
      return GL_LEQUAL;
    case GlCompare::greater:
      return GL_GREATER;
    case GlCompare::notequal:
      return GL_NOTEQUAL;
    case GlCompare::gequal:
      return GL_GEQUAL;
    case GlCompare::always:
      return GL_ALWAYS;
  }
  return GL_ALWAYS;
}

GLenum gl_stencil_op(GlStencilOp op) {
  switch (op) {
    case GlStencilOp::keep:
      return GL_KEEP;
    case GlStencilOp::zero:
      return GL_ZERO;
    case GlStencilOp::replace:
      return GL_REPLACE;
    case GlStencilOp::incr:
      return GL_INCR;
    case GlStencilOp::incr_wrap:
      return GL_INCR_WRAP;
    case GlStencilOp::decr:
      return GL_DECR;
    case GlStencilOp::decr_wrap:
      return GL_DECR_WRAP;
    case GlStencilOp::invert:
      return GL_INVERT;
  }
  return GL_KEEP;
}

void stencil_face(GLenum face, const GlStencilFace& f) {
  glStencilFuncSeparate(face, gl_compare(f.func), GLint(f.ref), GLuint(f.mask));
  glStencilOpSeparate(face, gl_stencil_op(f.fail), gl_stencil_op(f.zfail), gl_stencil_op(f.zpass));
  glStencilMaskSeparate(face, GLuint(f.write_mask));
}

}  // namespace

struct OsmesaContext::Impl {
  OSMesaContext context = nullptr;
  GLuint texture = 0;
};

OsmesaContext::OsmesaContext(int width, int height, int rasterizer_threads)
    : width_(width), height_(height), buffer_(size_t(width) * size_t(height) * 4), impl_(std::make_unique<Impl>()) {
  if (width <= 0 || height <= 0) throw InvalidInput(fmt::format("OSMesa: bad size {}x{}", width, height));
  std::call_once(g_first_context, [&] {
    if (rasterizer_threads >= 0) setenv("LP_NUM_THREADS", std::to_string(rasterizer_threads).c_str(), 1);
    const char* env = std::getenv("LP_NUM_THREADS");
    g_rasterizer_threads = env != nullptr ? std::atoi(env) : -1;
  });
  // RGBA, 24-bit depth, 8-bit stencil, no accumulation buffer.
  impl_->context = OSMesaCreateContextExt(OSMESA_RGBA, 24, 8, 0, nullptr);
  if (impl_->context == nullptr) throw Error("OSMesa: OSMesaCreateContextExt failed");
  if (!OSMesaMakeCurrent(impl_->context, buffer_.data(), GL_UNSIGNED_BYTE, width, height)) {
    OSMesaDestroyContext(impl_->context);
    throw Error("OSMesa: OSMesaMakeCurrent failed");
  }
  GLint depth_bits = 0, stencil_bits = 0;
  glGetIntegerv(GL_DEPTH_BITS, &depth_bits);
  glGetIntegerv(GL_STENCIL_BITS, &stencil_bits);
  if (depth_bits != 24 || stencil_bits != 8) {
    OSMesaDestroyContext(impl_->context);
    throw Error(fmt::format("OSMesa: expected a 24-bit depth and an 8-bit stencil buffer, got {} and {} bits",
                            depth_bits, stencil_bits));
  }
  glViewport(0, 0, width, height);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
}

OsmesaContext::~OsmesaContext() {
  if (impl_->texture != 0) glDeleteTextures(1, &impl_->texture);
  OSMesaDestroyContext(impl_->context);
}

int OsmesaContext::rasterizer_threads() { return g_rasterizer_threads; }

void OsmesaContext::begin(const GlState& s) {
  load_matrix(GL_PROJECTION, s.projection);
  // The light is placed in eye space: glLightfv(GL_POSITION) transforms by the model-view in force.
  load_matrix(GL_MODELVIEW, Mat4f(1.0f));
  if (s.lighting) {
    glEnable(GL_LIGHTING);
    glEnable(GL_LIGHT0);
    glLightfv(GL_LIGHT0, GL_POSITION, glm::value_ptr(s.light.position));
    glLightfv(GL_LIGHT0, GL_AMBIENT, glm::value_ptr(s.light.ambient));
    glLightfv(GL_LIGHT0, GL_DIFFUSE, glm::value_ptr(s.light.diffuse));
    glLightfv(GL_LIGHT0, GL_SPECULAR, glm::value_ptr(s.light.specular));
    glMaterialfv(GL_FRONT_AND_BACK, GL_AMBIENT, glm::value_ptr(s.material.ambient));
    glMaterialfv(GL_FRONT_AND_BACK, GL_DIFFUSE, glm::value_ptr(s.material.diffuse));
    glMaterialfv(GL_FRONT_AND_BACK, GL_SPECULAR, glm::value_ptr(s.material.specular));
    glMaterialfv(GL_FRONT_AND_BACK, GL_EMISSION, glm::value_ptr(s.material.emission));
    glMaterialf(GL_FRONT_AND_BACK, GL_SHININESS, s.material.shininess);
    glEnable(GL_NORMALIZE);  // normals renormalized after the normal matrix (the conventions' rule 1)
  } else {
    glDisable(GL_LIGHTING);
  }
  load_matrix(GL_MODELVIEW, s.modelview);
  glShadeModel(s.smooth ? GL_SMOOTH : GL_FLAT);
  if (s.cull_back) {
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glFrontFace(GL_CCW);
  } else {
    glDisable(GL_CULL_FACE);
  }
  if (s.depth_test) {
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(gl_compare(s.depth_func));
  } else {
    glDisable(GL_DEPTH_TEST);
  }
  if (s.stencil_test) {
    glEnable(GL_STENCIL_TEST);
  } else {
    glDisable(GL_STENCIL_TEST);
  }
  stencil_face(GL_FRONT, s.stencil_front);
  stencil_face(GL_BACK, s.stencil_back);
  glColor4f(s.color.x, s.color.y, s.color.z, s.alpha);
  if (s.blend) {
    static constexpr GLenum kFactors[] = {GL_ZERO,      GL_ONE,
                                          GL_SRC_COLOR, GL_ONE_MINUS_SRC_COLOR,
                                          GL_DST_COLOR, GL_ONE_MINUS_DST_COLOR,
                                          GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA,
                                          GL_DST_ALPHA, GL_ONE_MINUS_DST_ALPHA};
    static constexpr GLenum kEquations[] = {GL_FUNC_ADD, GL_FUNC_SUBTRACT, GL_FUNC_REVERSE_SUBTRACT, GL_MIN, GL_MAX};
    glEnable(GL_BLEND);
    glBlendFunc(kFactors[int(s.blend_src)], kFactors[int(s.blend_dst)]);
    glBlendEquation(kEquations[int(s.blend_equation)]);
  } else {
    glDisable(GL_BLEND);
  }
  if (s.texture != nullptr) {
    const GlTexture& t = *s.texture;
    if (impl_->texture == 0) glGenTextures(1, &impl_->texture);
    glBindTexture(GL_TEXTURE_2D, impl_->texture);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
    const bool mipmaps = t.filter == GlFilter::linear_mipmap_linear;
    glTexParameteri(GL_TEXTURE_2D, GL_GENERATE_MIPMAP, mipmaps ? GL_TRUE : GL_FALSE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER,
                    t.filter == GlFilter::nearest ? GL_NEAREST
                    : mipmaps                     ? GL_LINEAR_MIPMAP_LINEAR
                                                  : GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, t.filter == GlFilter::nearest ? GL_NEAREST : GL_LINEAR);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, t.width, t.height, 0, GL_RGBA, GL_UNSIGNED_BYTE, t.rgba.data());
    glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
    glEnable(GL_TEXTURE_2D);
  } else {
    glDisable(GL_TEXTURE_2D);
  }
  if (s.clear) {  // glClear obeys the write masks: all on for it
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthMask(GL_TRUE);
    glStencilMask(0xff);
    glClearColor(s.background.x, s.background.y, s.background.z, 1.0f);
    glClearDepth(1.0);
    glClearStencil(GLint(s.clear_stencil));
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
    glStencilMaskSeparate(GL_FRONT, GLuint(s.stencil_front.write_mask));
    glStencilMaskSeparate(GL_BACK, GLuint(s.stencil_back.write_mask));
  }
  const GLboolean color_write = s.color_write ? GL_TRUE : GL_FALSE;
  glColorMask(color_write, color_write, color_write, color_write);
  glDepthMask(s.depth_write ? GL_TRUE : GL_FALSE);
}

void OsmesaContext::draw(const GlMesh& mesh, GlSubmit submit) {
  const bool normals = !mesh.normals.empty(), colors = !mesh.colors.empty(), texcoords = !mesh.texcoords.empty();
  if (submit == GlSubmit::immediate) {
    const float* p = mesh.positions.data();
    const float* n = mesh.normals.data();
    const float* c = mesh.colors.data();
    const float* t = mesh.texcoords.data();
    glBegin(GL_TRIANGLES);
    for (const uint32_t i : mesh.indices) {
      if (normals) glNormal3fv(n + 3 * size_t(i));
      if (colors && mesh.color_size == 4) glColor4fv(c + 4 * size_t(i));
      if (colors && mesh.color_size == 3) glColor3fv(c + 3 * size_t(i));
      if (texcoords) glTexCoord2fv(t + 2 * size_t(i));
      glVertex3fv(p + 3 * size_t(i));
    }
    glEnd();
    return;
  }
  glEnableClientState(GL_VERTEX_ARRAY);
  glVertexPointer(3, GL_FLOAT, 0, mesh.positions.data());
  if (normals) {
    glEnableClientState(GL_NORMAL_ARRAY);
    glNormalPointer(GL_FLOAT, 0, mesh.normals.data());
  }
  if (colors) {
    glEnableClientState(GL_COLOR_ARRAY);
    glColorPointer(mesh.color_size, GL_FLOAT, 0, mesh.colors.data());
  }
  if (texcoords) {
    glEnableClientState(GL_TEXTURE_COORD_ARRAY);
    glTexCoordPointer(2, GL_FLOAT, 0, mesh.texcoords.data());
  }
  glDrawElements(GL_TRIANGLES, GLsizei(mesh.indices.size()), GL_UNSIGNED_INT, mesh.indices.data());
  glDisableClientState(GL_VERTEX_ARRAY);
  glDisableClientState(GL_NORMAL_ARRAY);
  glDisableClientState(GL_COLOR_ARRAY);
  glDisableClientState(GL_TEXTURE_COORD_ARRAY);
}

void OsmesaContext::finish() { glFinish(); }

GlFrame OsmesaContext::read() const {
  glFinish();
  GlFrame frame;
  frame.width = width_;
  frame.height = height_;
  const size_t w = size_t(width_), h = size_t(height_);
  std::vector<uint8_t> rgb(w * h * 3), alpha(w * h);
  std::vector<uint32_t> depth(w * h);
  std::vector<uint8_t> stencil(w * h);
  glReadPixels(0, 0, width_, height_, GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
  glReadPixels(0, 0, width_, height_, GL_ALPHA, GL_UNSIGNED_BYTE, alpha.data());
  glReadPixels(0, 0, width_, height_, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, depth.data());
  glReadPixels(0, 0, width_, height_, GL_STENCIL_INDEX, GL_UNSIGNED_BYTE, stencil.data());
  if (const GLenum error = glGetError(); error != GL_NO_ERROR) throw Error(fmt::format("OpenGL error 0x{:x}", error));
  frame.rgb.resize(rgb.size());
  frame.depth.resize(depth.size());
  frame.stencil.resize(stencil.size());
  frame.alpha.resize(alpha.size());
  for (size_t row = 0; row < h; ++row) {  // GL row 0 is the bottom
    const size_t gl_row = h - 1 - row;
    std::copy_n(rgb.begin() + std::ptrdiff_t(gl_row * w * 3), w * 3, frame.rgb.begin() + std::ptrdiff_t(row * w * 3));
    std::copy_n(stencil.begin() + std::ptrdiff_t(gl_row * w), w, frame.stencil.begin() + std::ptrdiff_t(row * w));
    std::copy_n(alpha.begin() + std::ptrdiff_t(gl_row * w), w, frame.alpha.begin() + std::ptrdiff_t(row * w));
    // GL_UNSIGNED_INT scales depth to 32 bits; the top 24 are the stored value.
    for (size_t x = 0; x < w; ++x) frame.depth[row * w + x] = depth[gl_row * w + x] >> 8;
  }
  return frame;
}

GlFrame render_osmesa(const TriMesh& mesh, int width, int height, const GlState& state, GlSubmit submit) {
  OsmesaContext context(width, height);
  context.begin(state);
  context.draw(GlMesh(mesh), submit);
  return context.read();
}

}  // namespace tessera::reference
