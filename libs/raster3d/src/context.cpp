#include "tessera/raster3d/context.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <memory>

#include "tessera/math/transform.hpp"

namespace tessera::raster3d {
namespace {

template <class T>
std::vector<T> to_float_array(const auto& values, size_t expected, const char* what) {
  if (!values.empty() && values.size() != expected)
    throw InvalidInput(fmt::format("mesh has {} {} for {} positions", values.size(), what, expected));
  return std::vector<T>(values.begin(), values.end());
}

enum class PrimitiveClass { triangles, lines, points };

PrimitiveClass primitive_class(Primitive kind) {
  switch (kind) {
    case Primitive::points:
      return PrimitiveClass::points;
    case Primitive::lines:
    case Primitive::line_strip:
    case Primitive::line_loop:
      return PrimitiveClass::lines;
    default:
      return PrimitiveClass::triangles;
  }
}

}  // namespace

VertexArrays VertexArrays::from_mesh(const TriMesh& mesh) {
  VertexArrays a;
  const size_t n = mesh.positions.size();
  a.positions.assign(mesh.positions.begin(), mesh.positions.end());
  a.normals = to_float_array<Vec3f>(mesh.normals, n, "normals");
  a.colors = to_float_array<Vec3f>(mesh.colors, n, "colors");
  a.uvs = to_float_array<Vec2f>(mesh.uvs, n, "uvs");
  a.indices = mesh.indices;
  return a;
}

VertexAttributes VertexArrays::attributes() const {
  return {positions.data(), normals.empty() ? nullptr : normals.data(), colors.empty() ? nullptr : colors.data(),
          uvs.empty() ? nullptr : uvs.data()};
}

void sort_back_to_front(VertexArrays& arrays, const Mat4& model_view) {
  const size_t n = arrays.indices.size() / 3;
  std::vector<std::pair<double, size_t>> order(n);
  for (size_t t = 0; t < n; ++t) {
    const uint32_t* v = &arrays.indices[3 * t];
    const Vec3 centroid =
        (Vec3(arrays.positions[v[0]]) + Vec3(arrays.positions[v[1]]) + Vec3(arrays.positions[v[2]])) / 3.0;
    order[t] = {(model_view * Vec4(centroid, 1)).z, t};  // the eye looks down -z: the most negative is the farthest
  }
  std::stable_sort(order.begin(), order.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<uint32_t> sorted;
  sorted.reserve(arrays.indices.size());
  for (const auto& [z, t] : order) sorted.insert(sorted.end(), &arrays.indices[3 * t], &arrays.indices[3 * t + 3]);
  arrays.indices = std::move(sorted);
}

Context::Context(int width, int height) : framebuffer_(width, height) { initialize(width, height); }

void Context::initialize(int width, int height) {
  framebuffer_ = Framebuffer(width, height);
  projection_ = MatrixStack3();
  model_view_ = MatrixStack3();
  matrix_mode_ = MatrixMode::model_view;
  current_color_ = Vec3f(1, 1, 1);
  current_normal_ = Vec3f(0, 0, 1);
  current_uv_ = Vec2f(0, 0);
  state_ = RasterState();
  shading_ = ShadingModel::unlit;
  alpha_ = 1;
  program_ = nullptr;
  hidden_surface_ = HiddenSurface::zbuffer;
  lighting_ = Lighting();
  // OpenGL's defaults: GL_LIGHT0 is white, the other lights are black; all point down -z from the viewer.
  lights_.fill(Light{{0, 0, 1, 0}, Vec3f(0), Vec3f(0), Vec3f(0)});
  lights_[0] = Light();
  light_on_.fill(false);
  light_on_[0] = true;
  stats_ = DrawStats();
  in_shape_ = false;
  shape_vertices_.clear();
  shape_target_ = &shape_vertices_;
  shape_begin_ = 0;
  batch_references_ = 0;
  vertex_cache_.assign(size_t(1) << kVertexCacheBits, CachedVertex{});
  cache_epoch_ = 1;
  batch_ = VertexArrays();
  batch_lines_.clear();
  batch_points_.clear();
}

// What a draw's raster jobs read after the draw has returned: the uniforms as they were at the draw, and the fragment
// shaders that refer to them. The jobs hold it until they are done.
struct Context::DrawShaders {
  FixedFunctionUniforms uniforms;
  ColorFragmentShader color;
  Translucent<ColorFragmentShader> translucent_color;  // alpha set by the draw (Context::alpha)
};

Framebuffer& Context::framebuffer() {
  flush();
  return framebuffer_;
}

void Context::submit_batch() {
  if (in_shape_) throw InvalidInput("state change or flush between begin and end (missing end)");
  draw_batch();
}

void Context::flush() {
  submit_batch();
  stats_.rasterized += detail::collect_raster(framebuffer_.scratch());  // the raster jobs' share of the setup
}

void Context::draw_batch() {
  batch_references_ = 0;
  new_cache_epoch();  // the cache's entries refer to the batch drawn now
  if (batch_.positions.empty()) return;
  const VertexAttributes attributes = batch_.attributes();
  const auto count = uint32_t(batch_.positions.size());
  draw_triangle_arrays(attributes, count, batch_.indices);
  draw_line_arrays(attributes, count, batch_lines_);
  draw_point_arrays(attributes, count, batch_points_);
  batch_.positions.clear();
  batch_.normals.clear();
  batch_.colors.clear();
  batch_.uvs.clear();
  batch_.indices.clear();
  batch_lines_.clear();
  batch_points_.clear();
}

void Context::swap_buffers() {
  flush();
  framebuffer_.swap();
}

void Context::clear(const Vec3f& color) {
  flush();
  framebuffer_.clear(color);
}

// ---- Matrices ----

MatrixStack3& Context::current_stack() {
  submit_batch();  // the pending batch was specified under the old matrices
  return matrix_mode_ == MatrixMode::projection ? projection_ : model_view_;
}

void Context::matrix_mode(MatrixMode mode) { matrix_mode_ = mode; }
void Context::push_matrix() { current_stack().push(); }
void Context::pop_matrix() { current_stack().pop(); }
void Context::load_identity() { current_stack().load_identity(); }
void Context::load_matrix(const Mat4& m) { current_stack().load(m); }
void Context::mult_matrix(const Mat4& m) { current_stack().multiply(m); }
void Context::translate(double x, double y, double z) { mult_matrix(tessera::translate(x, y, z)); }
void Context::scale(double x, double y, double z) { mult_matrix(tessera::scale(x, y, z)); }
void Context::rotate_x(double angle) { mult_matrix(tessera::rotate_x(angle)); }
void Context::rotate_y(double angle) { mult_matrix(tessera::rotate_y(angle)); }
void Context::rotate_z(double angle) { mult_matrix(tessera::rotate_z(angle)); }
void Context::rotate(double angle, const Vec3& axis) { mult_matrix(tessera::rotate(angle, axis)); }

void Context::look_at(const Vec3& eye, const Vec3& center, const Vec3& up) {
  submit_batch();
  model_view_.multiply(tessera::look_at(eye, center, up));
}

void Context::ortho(double l, double r, double b, double t, double n, double f) {
  submit_batch();
  projection_.load(tessera::ortho(l, r, b, t, n, f));
}

void Context::perspective(double fovy, double n, double f, double aspect) {
  submit_batch();
  if (aspect <= 0) {
    const bool whole = state_.viewport.width <= 0 || state_.viewport.height <= 0;
    aspect = whole ? double(framebuffer_.width()) / framebuffer_.height()
                   : double(state_.viewport.width) / state_.viewport.height;
  }
  projection_.load(tessera::perspective(fovy, aspect, n, f));
}

// ---- State ----

void Context::viewport(int x, int y, int width, int height) {
  submit_batch();
  state_.viewport = {x, y, width, height};
}
void Context::depth_test(bool on) {
  submit_batch();
  state_.depth_test = on;
}
void Context::depth_func(DepthFunc func) {
  submit_batch();
  state_.depth_func = func;
}
void Context::depth_write(bool on) {
  submit_batch();
  state_.depth_write = on;
}
void Context::cull(CullMode mode) {
  submit_batch();
  state_.cull = mode;
}
void Context::color_write(bool on) {
  submit_batch();
  state_.color_write = on;
}
void Context::stencil_test(bool on) {
  submit_batch();
  state_.stencil_test = on;
}
void Context::stencil(const StencilFace& front, const StencilFace& back) {
  submit_batch();
  state_.stencil_front = front;
  state_.stencil_back = back;
}
void Context::blend(bool on) {
  submit_batch();
  state_.blend = on;
}
void Context::blend_function(const BlendFunction& f) {
  submit_batch();
  state_.blend_function = f;
}
void Context::alpha(float a) {
  submit_batch();
  alpha_ = a;
}
void Context::clear_stencil(uint8_t value) {
  flush();
  framebuffer_.clear_stencil(value);
}
void Context::shading(ShadingModel model) {
  submit_batch();
  shading_ = model;
}
void Context::hidden_surface(HiddenSurface method) {
  submit_batch();
  hidden_surface_ = method;
}
void Context::material(const Material& m) {
  submit_batch();
  lighting_.material = m;
}
void Context::specular_model(SpecularModel model) {
  submit_batch();
  lighting_.specular_model = model;
}
void Context::light_model_ambient(const Vec3f& ambient) {
  submit_batch();
  lighting_.model_ambient = ambient;
}
void Context::color_material(bool on) {
  submit_batch();
  lighting_.color_material = on;
}

static void check_light_index(int i) {
  if (i < 0 || i >= kMaxLights) throw InvalidInput(fmt::format("light {} is outside [0, {})", i, kMaxLights));
}

void Context::light(int i, const Light& light) {
  check_light_index(i);
  submit_batch();
  Light eye = light;
  eye.position = Vec4f(model_view() * Vec4(light.position));  // glLight stores the position in eye space
  lights_[size_t(i)] = eye;
}

void Context::enable_light(int i, bool on) {
  check_light_index(i);
  submit_batch();
  light_on_[size_t(i)] = on;
}

// ---- Immediate mode ----

void Context::begin(Primitive kind) {
  if (in_shape_) throw InvalidInput("begin while a primitive is open (missing end)");
  // Keep submission order: a batch holds one class of primitives.
  const bool pending_other = (!batch_.indices.empty() && primitive_class(kind) != PrimitiveClass::triangles) ||
                             (!batch_lines_.empty() && primitive_class(kind) != PrimitiveClass::lines) ||
                             (!batch_points_.empty() && primitive_class(kind) != PrimitiveClass::points);
  if (pending_other || batch_references_ >= kBatchVertices) submit_batch();
  in_shape_ = true;
  shape_kind_ = kind;
  shape_vertices_.clear();
  // Independent triangles go straight to the batch's index list; assemble_shape drops an incomplete last one.
  shape_target_ = kind == Primitive::triangles ? &batch_.indices : &shape_vertices_;
  shape_begin_ = shape_target_->size();
}

// Vertices per primitive of the kinds whose long shapes can be cut between primitives, else 0.
static uint32_t independent_primitive_size(Primitive kind) {
  switch (kind) {
    case Primitive::points:
      return 1;
    case Primitive::lines:
      return 2;
    case Primitive::triangles:
      return 3;
    case Primitive::quads:
      return 4;
    default:
      return 0;
  }
}

void Context::vertex_slow_path(double x, double y, double z) {
  if (!in_shape_) throw InvalidInput("vertex outside begin/end");
  const uint32_t cut = independent_primitive_size(shape_kind_);
  if (cut && batch_references_ >= kBatchVertices && (shape_target_->size() - shape_begin_) % cut == 0) {
    // A long shape of independent primitives: draw what is complete, so the batch stays cache-sized.
    assemble_shape();
    draw_batch();
    shape_begin_ = 0;  // both targets are empty now
  }
  shape_target_->push_back(batch_vertex(Vec3f(x, y, z)));
  ++batch_references_;
}

void Context::new_cache_epoch() {
  if (++cache_epoch_ == 0) {  // wrapped: forget every entry rather than let an old epoch match again
    vertex_cache_.assign(vertex_cache_.size(), CachedVertex{});
    cache_epoch_ = 1;
  }
}

uint32_t Context::add_batch_vertex(const Vec3f& position, uint32_t slot) {
  const auto index = uint32_t(batch_.positions.size());
  batch_.positions.push_back(position);
  batch_.normals.push_back(current_normal_);
  batch_.colors.push_back(current_color_);
  batch_.uvs.push_back(current_uv_);
  if (index <= 0xFFFF) vertex_cache_[slot] = CachedVertex{uint16_t(index), cache_epoch_};
  return index;
}

void Context::end() {
  if (!in_shape_) throw InvalidInput("end without begin");
  in_shape_ = false;
  assemble_shape();
}

void Context::assemble_shape() {
  if (shape_kind_ == Primitive::triangles) {  // the vertices are in place: whole triangles only
    const size_t n = batch_.indices.size() - shape_begin_;
    batch_.indices.resize(batch_.indices.size() - n % 3);
    return;
  }
  const std::vector<uint32_t>& v = shape_vertices_;
  const auto n = uint32_t(v.size());
  auto& tris = batch_.indices;
  auto tri = [&](uint32_t a, uint32_t b, uint32_t c) {
    tris.push_back(v[a]);
    tris.push_back(v[b]);
    tris.push_back(v[c]);
  };
  auto line = [&](uint32_t a, uint32_t b) {
    batch_lines_.push_back(v[a]);
    batch_lines_.push_back(v[b]);
  };
  switch (shape_kind_) {
    case Primitive::points:
      batch_points_.insert(batch_points_.end(), v.begin(), v.end());
      break;
    case Primitive::lines:
      for (uint32_t i = 0; i + 1 < n; i += 2) line(i, i + 1);
      break;
    case Primitive::line_strip:
    case Primitive::line_loop:
      for (uint32_t i = 0; i + 1 < n; ++i) line(i, i + 1);
      if (shape_kind_ == Primitive::line_loop && n > 2) line(n - 1, 0);
      break;
    case Primitive::triangles:  // handled above
      break;
    case Primitive::triangle_strip:  // every triangle keeps the strip's winding; the provoking vertex is i + 2
      for (uint32_t i = 0; i + 2 < n; ++i) (i % 2 == 0) ? tri(i, i + 1, i + 2) : tri(i + 1, i, i + 2);
      break;
    case Primitive::triangle_fan:
      for (uint32_t i = 1; i + 1 < n; ++i) tri(0, i, i + 1);
      break;
    case Primitive::quads:  // split as Mesa: (0, 1, 3), (1, 2, 3), the provoking fourth vertex last in both
      for (uint32_t i = 0; i + 3 < n; i += 4) {
        tri(i, i + 1, i + 3);
        tri(i + 1, i + 2, i + 3);
      }
      break;
    case Primitive::polygon:  // a fan whose provoking vertex is the first (OpenGL's rule for polygons)
      for (uint32_t i = 1; i + 1 < n; ++i) tri(i, i + 1, 0);
      break;
  }
  shape_vertices_.clear();
}

// ---- Batched ----

void Context::draw(const TriMesh& mesh) { draw(VertexArrays::from_mesh(mesh)); }

void Context::draw(const VertexArrays& arrays) {
  submit_batch();
  draw_triangle_arrays(arrays.attributes(), uint32_t(arrays.positions.size()), arrays.indices);
}

void Context::draw_lines(const VertexArrays& arrays, std::span<const uint32_t> lines) {
  submit_batch();
  draw_line_arrays(arrays.attributes(), uint32_t(arrays.positions.size()), lines);
}

void Context::draw_wireframe(const TriMesh& mesh) {
  std::vector<std::pair<uint32_t, uint32_t>> edges;
  edges.reserve(mesh.indices.size());
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = mesh.indices[t + size_t(k)], b = mesh.indices[t + size_t(k + 1) % 3];
      edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  std::vector<uint32_t> lines;
  lines.reserve(2 * edges.size());
  for (const auto& [a, b] : edges) lines.insert(lines.end(), {a, b});
  draw_lines(VertexArrays::from_mesh(mesh), lines);
}

FixedFunctionUniforms Context::uniforms() const {
  FixedFunctionUniforms u;
  u.model_view_projection = gl_matrix_product(Mat4f(projection()), Mat4f(model_view()));
  u.model_view = Mat4f(model_view());
  u.normal_matrix = Mat3f(normal_matrix(model_view()));
  Lighting lighting = lighting_;
  lighting.light_count = 0;
  for (int i = 0; i < kMaxLights; ++i)
    if (light_on_[size_t(i)]) lighting.lights[size_t(lighting.light_count++)] = lights_[size_t(i)];
  u.lighting = PreparedLighting(lighting);
  u.lit = shading_ != ShadingModel::unlit;
  u.color = current_color_;
  u.normal = current_normal_;
  return u;
}

RasterState Context::raster_state() const {
  RasterState s = state_;
  s.flat = shading_ == ShadingModel::flat;
  s.painter = hidden_surface_ == HiddenSurface::painter;
  return s;
}

static void add_stats(DrawStats& total, const DrawStats& d) {
  total.primitives += d.primitives;
  total.rasterized += d.rasterized;
}

void Context::use_program(std::shared_ptr<ContextProgram> program) {
  submit_batch();  // the shapes before the switch are drawn as they were specified
  program_ = std::move(program);
}

void Context::draw_triangle_arrays(const VertexAttributes& attributes, uint32_t vertex_count,
                                   std::span<const uint32_t> indices) {
  if (indices.empty()) return;
  if (program_) {
    ProgramState p;
    p.model_view = Mat4f(model_view());
    p.projection = Mat4f(projection());
    p.lighting = lighting_;
    p.lighting.lights = lights_;
    p.light_on = light_on_;
    p.color = current_color_;
    p.normal = current_normal_;
    p.uv = current_uv_;
    p.alpha = alpha_;
    add_stats(stats_, program_->draw_arrays(framebuffer_, raster_state(), p, attributes, vertex_count, indices));
    return;
  }
  // The vertex stage reads `attributes` before the call returns; the rasterization of the last pass goes on on the
  // framebuffer's raster thread with the shaders kept alive in `shaders`.
  const auto shaders = std::make_shared<DrawShaders>();
  shaders->uniforms = uniforms();
  const FixedFunctionUniforms* u = &shaders->uniforms;
  const RasterState s = raster_state();
  const auto draw = [&](const auto& vertex_shader, const auto& fragment_shader) {
    add_stats(stats_, detail::draw_triangles_async(framebuffer_, s, vertex_count, indices, vertex_shader,
                                                   fragment_shader, shaders));
  };
  // Opaque draws keep the plain shaders (and their fast paths: the RGB shaders' alpha is 1).
  shaders->translucent_color.alpha = alpha_;
  if (shading_ == ShadingModel::phong) {
    // Per pixel: the lane shader on the quad stage, which holds the uniforms until its jobs are done.
    struct Phong final : lanes::QuadShader<PhongVaryings, PhongLaneShader> {
      Phong(std::shared_ptr<const DrawShaders> s, float alpha)
          : QuadShader(PhongLaneShader{&s->uniforms, alpha}), shaders(std::move(s)) {}
      std::shared_ptr<const DrawShaders> shaders;
    };
    add_stats(stats_, detail::draw_quads_async(framebuffer_, s, vertex_count, indices, PhongVertexShader{attributes, u},
                                               std::make_shared<Phong>(shaders, alpha_)));
  } else {
    if (alpha_ == 1)
      draw(FixedFunctionVertexShader{attributes, u}, shaders->color);
    else
      draw(FixedFunctionVertexShader{attributes, u}, shaders->translucent_color);
  }
}

void Context::draw_line_arrays(const VertexAttributes& attributes, uint32_t vertex_count,
                               std::span<const uint32_t> indices) {
  if (indices.empty()) return;
  const FixedFunctionUniforms u = uniforms();
  const Translucent<ColorFragmentShader> color{{}, alpha_};
  add_stats(stats_, raster3d::draw_lines(framebuffer_, raster_state(), vertex_count, indices,
                                         FixedFunctionVertexShader{attributes, &u}, color));
}

void Context::draw_point_arrays(const VertexAttributes& attributes, uint32_t vertex_count,
                                std::span<const uint32_t> indices) {
  if (indices.empty()) return;
  const FixedFunctionUniforms u = uniforms();
  const Translucent<ColorFragmentShader> color{{}, alpha_};
  add_stats(stats_, draw_points(framebuffer_, raster_state(), vertex_count, indices,
                                FixedFunctionVertexShader{attributes, &u}, color));
}

}  // namespace tessera::raster3d
