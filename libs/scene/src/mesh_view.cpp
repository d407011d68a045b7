// The one renderer of a mesh: preparation (normals, winding, triangles, facets, arrays, edges) once, then the
// fixed-function pipeline or the per-pixel surface shaders for each camera; and the helpers it shares with the scene
// rasterizer.
#include "tessera/scene/mesh_view.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>

#include "tessera/core/error.hpp"
#include "tessera/core/memory_budget.hpp"
#include "tessera/core/parallel.hpp"
#include "tessera/core/progress.hpp"
#include "tessera/math/transform.hpp"
#include "tessera/mesh/convert.hpp"
#include "tessera/mesh/normals.hpp"
#include "tessera/mesh/topology.hpp"
#include "tessera/mesh/triangulate.hpp"
#include "tessera/raster3d/shadow_volume.hpp"
#include "tessera/raster3d/surface_shader.hpp"
#include "tessera/raytrace/sampling.hpp"

namespace tessera {

TriMesh split_faceted(const TriMesh& mesh) {
  TriMesh out;
  out.positions.reserve(mesh.indices.size());
  out.normals.reserve(mesh.indices.size());
  out.indices.reserve(mesh.indices.size());
  for (size_t t = 0; t < mesh.triangle_count(); ++t) {
    const uint32_t* v = &mesh.indices[3 * t];
    const Vec3 a = mesh.positions[v[0]], b = mesh.positions[v[1]], c = mesh.positions[v[2]];
    const Vec3 cross = glm::cross(b - a, c - a);
    const double length = glm::length(cross);
    const Vec3 n = length > 0 ? cross / length : Vec3(0, 0, 1);
    for (int k = 0; k < 3; ++k) {
      out.indices.push_back(uint32_t(out.positions.size()));
      out.positions.push_back(mesh.positions[v[k]]);
      out.normals.push_back(n);
      if (!mesh.colors.empty()) out.colors.push_back(mesh.colors[v[k]]);
      if (!mesh.uvs.empty()) out.uvs.push_back(mesh.uvs[v[k]]);
    }
  }
  return out;
}

std::vector<std::pair<uint32_t, uint32_t>> polygon_edges(const PolyMesh& mesh) {
  // The edge table's undirected edges: (lower, higher) vertex, sorted by that key.
  const EdgeTable table = build_edge_table(mesh);
  std::vector<std::pair<uint32_t, uint32_t>> edges;
  edges.reserve(table.size());
  for (const auto& [a, b] : table.vertices) edges.emplace_back(a, b);
  return edges;
}

double sphere_fit_distance(double radius, double half_angle, double margin) {
  return margin * radius / std::sin(half_angle);
}

Camera frame_sphere(Camera camera, const Vec3& center, double radius, const Vec3& direction, double margin) {
  const double distance = sphere_fit_distance(radius, camera.fovy / 2, margin);
  camera.center = center;
  camera.eye = center + distance * glm::normalize(direction);
  camera.near = std::max(distance - 1.5 * radius, 1e-3 * distance);
  camera.far = distance + 1.5 * radius;
  return camera;
}

raster3d::ShadowMap fitted_shadow_map(const Vec3& light, bool point, const Vec3& lo, const Vec3& hi, int size) {
  if (point) return raster3d::ShadowMap::point(size, light, lo, hi);
  return raster3d::ShadowMap(size, raster3d::ShadowMap::directional(light, lo, hi));
}

Vec2 pixel_sample(int s, int n, uint32_t pattern) {
  if (n == 1) return {0.5, 0.5};
  return Vec2(stratified_sample(uint32_t(s), uint32_t(n), pattern));
}

Mat4 jittered_projection(const Mat4& projection, const Vec2& sample, int width, int height) {
  // The pipeline samples GL pixel (i, j) at its center; the picture must move by (0.5 - sample) pixels for the center
  // to see what lies at the sample. GL's y runs up the image, the sample's down.
  return translate((1 - 2 * sample.x) / width, -(1 - 2 * sample.y) / height, 0) * projection;
}

ImageRGB downsample(const ImageRGB& image, int s) {
  if (s == 1) return image;
  ImageRGB out(image.width() / s, image.height() / s);
  for (int y = 0; y < out.height(); ++y)
    for (int x = 0; x < out.width(); ++x) {
      Vec3f sum(0.0f);
      for (int dy = 0; dy < s; ++dy)
        for (int dx = 0; dx < s; ++dx) sum += image(x * s + dx, y * s + dy);
      out(x, y) = sum / float(s * s);
    }
  return out;
}

namespace {

/// Whether the faces wind inward (an inside-out mesh: lit from behind, black but for the ambient term, and culled
/// whole by back-face culling): a closed, consistently oriented mesh with a negative volume. Open meshes are left as
/// they are: their volume depends on the origin.
bool winds_inward(const PolyMesh& mesh) {
  if (signed_volume(mesh) >= 0) return false;
  const EdgeTable edges = build_edge_table(mesh);
  for (size_t e = 0; e < edges.size(); ++e)
    if (edges.valence(e) != 2) return false;
  return is_consistently_oriented(mesh, edges);
}

/// Reverses every face's winding, with its corner attributes.
void reverse_faces(PolyMesh& mesh) {
  for (size_t f = 0; f < mesh.face_count(); ++f) {
    const uint32_t begin = mesh.face_offsets[f], end = mesh.face_offsets[f + 1];
    std::reverse(mesh.face_vertices.begin() + begin, mesh.face_vertices.begin() + end);
    if (!mesh.corner_uvs.empty()) std::reverse(mesh.corner_uvs.begin() + begin, mesh.corner_uvs.begin() + end);
    if (!mesh.corner_normals.empty())
      std::reverse(mesh.corner_normals.begin() + begin, mesh.corner_normals.begin() + end);
  }
}

/// Every polygon triangulated (triangulate_polygon) with its own corners: the polygon's unit normal on each (`facets`)
/// or the mesh's corner or vertex normals; the polygon's color from `face_colors` (`color` beyond its end), or without
/// face colors the mesh's vertex colors; and the mesh's uvs.
raster3d::VertexArrays polygon_corners(const PolyMesh& mesh, bool facets, const std::vector<Vec3f>& face_colors,
                                       const Vec3f& color) {
  raster3d::VertexArrays out;
  std::vector<Vec3> points;
  for (size_t f = 0; f < mesh.face_count(); ++f) {
    const auto face = mesh.face(f);
    const uint32_t base = mesh.face_offsets[f];
    points.clear();
    for (const uint32_t v : face) points.push_back(mesh.positions[v]);
    const Vec3f face_n(facets ? face_normal(mesh, f) : Vec3(0.0));
    for (const auto& triangle : triangulate_polygon(points))
      for (const uint32_t corner : triangle) {
        const uint32_t v = face[corner];
        out.indices.push_back(uint32_t(out.positions.size()));
        out.positions.push_back(Vec3f(mesh.positions[v]));
        if (facets)
          out.normals.push_back(face_n);
        else if (!mesh.corner_normals.empty())
          out.normals.push_back(Vec3f(mesh.corner_normals[base + corner]));
        else if (!mesh.normals.empty())
          out.normals.push_back(Vec3f(mesh.normals[v]));
        if (!face_colors.empty())
          out.colors.push_back(f < face_colors.size() ? face_colors[f] : color);
        else if (!mesh.colors.empty())
          out.colors.push_back(Vec3f(mesh.colors[v]));
        if (!mesh.corner_uvs.empty())
          out.uvs.push_back(Vec2f(mesh.corner_uvs[base + corner]));
        else if (!mesh.uvs.empty())
          out.uvs.push_back(Vec2f(mesh.uvs[v]));
      }
  }
  return out;
}

/// The pictures of a pixel's samples averaged (the accumulation buffer's anti-aliasing, one jittered frame a sample),
/// the nearest of their depths, and the pixels any sample covered.
class SampleResolve {
 public:
  /// For `samples` frames of width x height; with `direct` (one sample, no supersampling), the frame's 8-bit colors
  /// go straight into *direct (of that size) and no picture is taken.
  SampleResolve(int width, int height, int samples, ImageRGBA8* direct = nullptr)
      : width_(width), height_(height), samples_(samples), direct_(direct) {}

  /// Adds one sample's frame; `painter`: coverage from the stencil buffer (the painter's algorithm keeps no depth).
  /// A lone sample's frame is read when the picture is taken (it must stay unchanged until then); the first of several
  /// is kept as it is (0 + c is c).
  void add(const raster3d::Framebuffer& fb, bool painter) {
    painter_ = painter;
    if (direct_) {
      // Alpha 255 as raster3d::to_color8 gives it (blending leaves the frame's alpha below 1), or-ed into whole pixels
      // as 32-bit words (a loop GCC vectorizes, where per-channel stores it does not).
      const auto alpha = std::bit_cast<uint32_t>(glm::u8vec4(0, 0, 0, 255));
      parallel_for(0, height_, 16, [&](int64_t y0, int64_t y1) {
        for (int y = int(y0); y < int(y1); ++y) {
          const glm::u8vec4* in = fb.color().row(y);
          glm::u8vec4* o = direct_->row(y);
          for (int x = 0; x < width_; ++x) o[x] = std::bit_cast<glm::u8vec4>(std::bit_cast<uint32_t>(in[x]) | alpha);
        }
      });
      return;
    }
    if (samples_ == 1) {
      only_ = &fb;
      return;
    }
    if (count_++ == 0) {
      sum_ = fb.color_rgb();
      depth_ = Image<uint32_t>(width_, height_, raster3d::kDepthMax);
    } else {
      const ImageRGB color = fb.color_rgb();
      for (size_t i = 0; i < color.pixels().size(); ++i) sum_.pixels()[i] += color.pixels()[i];
    }
    for (size_t i = 0; i < depth_.pixels().size(); ++i) depth_.pixels()[i] = std::min(depth_.pixels()[i], depth(fb, i));
  }

  /// The average color box-filtered down by s (supersampling), the nearest depth of each s x s block as window z in
  /// [0, 1], and the output pixels some sample covered. Takes the sums (called once).
  MeshPicture take_picture(int s) {
    if (only_) {
      sum_ = only_->color_rgb();
    } else if (count_ > 1) {
      for (Vec3f& c : sum_.pixels()) c /= float(count_);
    }
    MeshPicture out{s == 1 ? std::move(sum_) : downsample(sum_, s), DepthImage(width_ / s, height_ / s, 1.0f), 0};
    std::vector<size_t> covered(size_t(out.depth.height()), 0);
    parallel_for(0, out.depth.height(), 16, [&](int64_t y0, int64_t y1) {
      for (int y = int(y0); y < int(y1); ++y)
        for (int x = 0; x < out.depth.width(); ++x) {
          uint32_t nearest = raster3d::kDepthMax;
          for (int dy = 0; dy < s; ++dy)
            for (int dx = 0; dx < s; ++dx) {
              const size_t i = size_t(y * s + dy) * size_t(width_) + size_t(x * s + dx);
              nearest = std::min(nearest, only_ ? depth(*only_, i) : depth_.pixels()[i]);
            }
          out.depth(x, y) = float(double(nearest) / raster3d::kDepthMax);
          covered[size_t(y)] += nearest < raster3d::kDepthMax;
        }
    });
    for (const size_t n : covered) out.covered += n;
    return out;
  }

 private:
  /// Pixel i's depth in `fb`, 0 where the painter's algorithm covered it.
  uint32_t depth(const raster3d::Framebuffer& fb, size_t i) const {
    return painter_ && fb.stencil().pixels()[i] ? 0u : fb.depth().pixels()[i];
  }

  int width_, height_, samples_;
  ImageRGBA8* direct_;
  bool painter_ = false;
  const raster3d::Framebuffer* only_ = nullptr;
  ImageRGB sum_;
  Image<uint32_t> depth_;
  int count_ = 0;
};

raster3d::ShadingModel shading_model(MeshShading shading) {
  switch (shading) {
    case MeshShading::flat:
      return raster3d::ShadingModel::flat;
    case MeshShading::gouraud:
      return raster3d::ShadingModel::gouraud;
    case MeshShading::phong:
      return raster3d::ShadingModel::phong;
    default:
      return raster3d::ShadingModel::unlit;
  }
}

/// The default light's direction in eye space: over the viewer's upper-left shoulder.
const Vec3 kViewerLight(-0.4, 0.6, 1.0);

/// A floor under the box [lo, hi] along the model's up axis k: a square at lo[k], three times the box's larger
/// horizontal size.
raster3d::VertexArrays floor_under(const Bounds3& box, int k) {
  // Corners in the horizontal axes (a, b), e_a x e_b = -e_k: (x, z) for y up.
  const int a = (k + 2) % 3, b = (k + 1) % 3;
  const Vec3 mid = 0.5 * (box.lo + box.hi);
  const float half = float(1.5 * std::max({box.hi[a] - box.lo[a], box.hi[b] - box.lo[b], 1e-6}));
  const auto corner = [&](float da, float db) {
    Vec3f p;
    p[k] = float(box.lo[k]);
    p[a] = float(mid[a]) + da;
    p[b] = float(mid[b]) + db;
    return p;
  };
  raster3d::VertexArrays arrays;
  arrays.positions = {corner(-half, -half), corner(half, -half), corner(half, half), corner(-half, half)};
  Vec3f up(0);
  up[k] = 1;
  arrays.normals.assign(4, up);
  arrays.indices = {0, 2, 1, 0, 3, 2};  // counterclockwise seen from above
  return arrays;
}

/// What one render reads: the prepared mesh and the picture's size (supersampled).
struct Frame {
  const MeshViewOptions& o;
  const raster3d::VertexArrays& arrays;
  const raster3d::VertexArrays& edge_vertices;
  const std::vector<uint32_t>& edge_lines;
  const Bounds3& box;
  int width, height, supersample;
  Progress* progress;
};

/// The mesh through the fixed-function pipeline (shading, wireframe, culling, two-sided lighting, painter, opacity) in
/// `ctx` (of the frame's size; every state it reads is set here), each jittered sample into `resolve`.
void draw_fixed_function(const Frame& f, const Camera& camera, raster3d::Context& ctx, SampleResolve& resolve) {
  const MeshViewOptions& o = f.o;
  const bool painter = o.hidden_surface == raster3d::HiddenSurface::painter;
  const bool colored = !o.face_colors.empty() || o.shading == MeshShading::normals;
  const bool blended = o.opacity < 1;
  ctx.matrix_mode(raster3d::MatrixMode::model_view);
  ctx.load_identity();
  // The light: over the viewer's shoulder in eye space, or a direction or a point in world space (set under the view
  // matrix, as glLight).
  const Vec3f diffuse(o.light.diffuse);
  if (o.light.kind == MeshLightKind::viewer)
    ctx.light(0, {.position = Vec4f(glm::normalize(Vec3f(kViewerLight)), 0), .diffuse = diffuse});
  ctx.look_at(camera.eye, camera.center, camera.up);
  if (o.light.kind == MeshLightKind::directional)
    ctx.light(0, {.position = Vec4f(Vec3f(glm::normalize(o.light.vector)), 0), .diffuse = diffuse});
  if (o.light.kind == MeshLightKind::point)
    ctx.light(0, {.position = Vec4f(Vec3f(o.light.vector), 1), .diffuse = diffuse});
  const raster3d::Material material =
      o.material.value_or(raster3d::Material::plastic(o.color, o.shininess, o.specular));
  ctx.material(material);
  ctx.color_material(colored && !o.material);  // the face colors are the surface
  ctx.specular_model(o.specular_model);
  ctx.color(o.color);
  ctx.shading(shading_model(o.shading));
  ctx.cull(o.two_sided ? raster3d::CullMode::back : o.cull);
  ctx.hidden_surface(o.hidden_surface);
  ctx.stencil_test(painter);
  ctx.blend(blended);
  ctx.depth_func(blended ? raster3d::DepthFunc::lequal : raster3d::DepthFunc::less);
  ctx.alpha(blended ? float(o.opacity) : 1.0f);
  ctx.use_program(o.program);
  if (painter) {
    // The painter's algorithm keeps no depth: the stencil buffer records which pixels the mesh covers.
    const raster3d::StencilFace mark{.ref = 1, .zpass = raster3d::StencilOp::replace};
    ctx.stencil(mark, mark);
  }
  raster3d::VertexArrays sorted;
  if (blended) {
    // Transparency: "over" blending of the triangles sorted far to near, the z-buffer still on (for the depth and the
    // pixel count) and passing them in that order.
    sorted = f.arrays;
    raster3d::sort_back_to_front(sorted, look_at(camera.eye, camera.center, camera.up));
    ctx.blend_function({raster3d::BlendFactor::src_alpha, raster3d::BlendFactor::one_minus_src_alpha});
  }
  const raster3d::VertexArrays& front = blended ? sorted : f.arrays;
  // Two-sided lighting: the back faces with flipped normals and darker colors, drawn with the front ones culled.
  raster3d::VertexArrays back;
  raster3d::Material back_material = material;
  if (o.two_sided) {
    back = front;
    for (Vec3f& n : back.normals) n = -n;
    for (Vec3f& c : back.colors) c *= o.back_shade;
    back_material.ambient *= o.back_shade;
    back_material.diffuse *= o.back_shade;
  }
  // Edges dark on a light background, light on a dark one.
  const Vec3f& bg = o.background;
  const Vec3f wire_color =
      o.wire_color.value_or((bg.x + bg.y + bg.z) > 1.5f ? Vec3f(0.1f, 0.1f, 0.15f) : Vec3f(0.9f, 0.9f, 0.8f));
  const int s = f.supersample;
  for (int sample = 0; sample < o.samples; ++sample) {
    const Mat4 projection =
        jittered_projection(camera.projection(), pixel_sample(sample, o.samples, kSamplePattern), f.width, f.height);
    ctx.matrix_mode(raster3d::MatrixMode::projection);
    ctx.load_matrix(projection);
    ctx.matrix_mode(raster3d::MatrixMode::model_view);
    ctx.clear(o.background);
    if (painter) ctx.clear_stencil(0);
    if (o.wireframe != MeshWireframe::alone) ctx.draw(front);
    if (o.two_sided && o.wireframe != MeshWireframe::alone) {
      ctx.material(back_material);
      ctx.cull(raster3d::CullMode::front);
      ctx.color(o.back_shade * o.color);
      ctx.draw(back);
      ctx.material(material);
      ctx.cull(raster3d::CullMode::back);
      ctx.color(o.color);
    }
    if (o.wireframe != MeshWireframe::none) {
      // Edges pulled toward the eye by a tiny depth offset (z_clip -= offset w, like glPolygonOffset) so that the
      // surface under them does not hide them; supersampled, drawn at s x s one-pixel offsets to stay a pixel wide.
      const raster3d::ShadingModel saved = ctx.shading();
      const raster3d::CullMode saved_cull = o.two_sided ? raster3d::CullMode::back : o.cull;
      ctx.shading(raster3d::ShadingModel::unlit);
      ctx.cull(raster3d::CullMode::none);
      ctx.color(wire_color);
      ctx.alpha(1);
      ctx.matrix_mode(raster3d::MatrixMode::projection);
      ctx.push_matrix();
      for (int dy = 0; dy < s; ++dy)
        for (int dx = 0; dx < s; ++dx) {
          ctx.load_matrix(translate(2.0 * dx / f.width, 2.0 * dy / f.height, -o.wire_depth_offset) * projection);
          ctx.draw_lines(f.edge_vertices, f.edge_lines);
        }
      ctx.pop_matrix();
      ctx.matrix_mode(raster3d::MatrixMode::model_view);
      ctx.shading(saved);
      ctx.cull(saved_cull);
      ctx.color(o.color);
      ctx.alpha(blended ? float(o.opacity) : 1.0f);
    }
    ctx.flush();
    if (f.progress) f.progress->advance();
    resolve.add(ctx.framebuffer(), painter);
  }
}

/// The mesh drawn per pixel with the maps of the options (texture, bump, environment, shadows, floor) into `fb` (of
/// the frame's size), each jittered sample into `resolve`.
void draw_with_maps(const Frame& f, const Camera& camera, raster3d::Framebuffer& fb, SampleResolve& resolve) {
  const MeshViewOptions& o = f.o;
  const Bounds3& box = f.box;
  raster3d::VertexArrays floor;
  if (o.floor) floor = floor_under(box, o.up_axis);
  if (o.env_cube && !o.environment && !o.floor)
    throw InvalidInput("mesh view: env_cube has nothing around the mesh to reflect (no environment or floor)");
  // z-fail shadow volumes need the far cap at infinity inside the view volume: a far plane at infinity.
  const bool volumes = o.shadows && o.shadow_method != ShadowMethod::map;
  const bool zfail = volumes && o.shadow_method == ShadowMethod::zfail;
  if (zfail && camera.orthographic)
    throw InvalidInput("mesh view: z-fail shadow volumes need a perspective camera (their far plane at infinity)");
  const Mat4 view = camera.view(),
             projection = zfail ? infinite_perspective(camera.fovy, camera.aspect, camera.near) : camera.projection();
  // The light, as in the fixed-function path: a direction or a point in world space, else over the viewer's
  // upper-left shoulder (fixed in eye space). `lighting_under(v)` places it in the eye space of view v.
  const bool point_light = o.light.kind == MeshLightKind::point;
  const Vec3 light = point_light ? o.light.vector
                     : o.light.kind == MeshLightKind::directional
                         ? glm::normalize(o.light.vector)
                         : glm::transpose(Mat3(view)) * glm::normalize(kViewerLight);
  const Vec3f surface = o.color;
  const auto lighting_under = [&](const Mat4& v) {
    raster3d::Lighting lighting;
    lighting.material = raster3d::Material::plastic(surface, o.shininess, o.specular);
    lighting.color_material = true;  // the (textured) surface color is C_r
    lighting.specular_model = o.specular_model;
    lighting.lights[0].diffuse = Vec3f(o.light.diffuse);
    lighting.lights[0].position =
        point_light ? Vec4f(Vec3f(v * glm::dvec4(light, 1)), 1) : Vec4f(Vec3f(Mat3(v) * light), 0);
    return raster3d::PreparedLighting(lighting);
  };
  // The map is fitted to the mesh, the only caster: the floor beyond it is shadowed all the same.
  std::optional<raster3d::ShadowMap> shadow;
  if (o.shadows && !volumes) shadow.emplace(fitted_shadow_map(light, point_light, box.lo, box.hi, o.shadow_size));

  raster3d::SurfaceUniforms u;
  u.lighting = lighting_under(view);
  u.color = surface;
  u.maps.shadows[0] = shadow ? &*shadow : nullptr;
  raster3d::SurfaceUniforms floor_uniforms = u;  // the floor: light gray, shadows only (set_camera: per sample)
  floor_uniforms.color = Vec3f(0.85f);
  u.maps.texture = o.texture.get();
  u.maps.bump = o.bump.get();
  u.maps.bump_scale = float(o.bump_scale * glm::length(box.hi - box.lo));
  u.maps.environment = o.environment.get();
  u.maps.reflectivity = float(o.reflect);

  const raster3d::VertexArrays& arrays = f.arrays;
  // Shadow volumes: the mesh's own, the only caster (the floor only receives).
  std::vector<raster3d::ShadowVolume> shadow_volumes;
  if (volumes)
    shadow_volumes.push_back(
        raster3d::shadow_volume(arrays.positions, arrays.indices, Vec4f(Vec3f(light), point_light ? 1.0f : 0.0f)));
  const raster3d::UvTangents tangents =
      o.bump ? raster3d::uv_tangents(arrays.positions, arrays.uvs, arrays.indices) : raster3d::UvTangents{};
  // env_cube: what surrounds the mesh (the floor, the environment) seen from its center, the notes' "render scene 6
  // times, eye at center of cube".
  const auto draw_surroundings = [&](raster3d::Framebuffer& face, const Mat4& p, const Mat4& v) {
    if (o.floor) {
      raster3d::SurfaceUniforms fl = floor_uniforms;
      fl.set_camera(p, v);
      fl.lighting = lighting_under(v);
      raster3d::draw_surface(face, raster3d::RasterState{}, floor, fl);
    }
    if (o.environment) raster3d::fill_background(face, *o.environment, p * v);
  };
  if (shadow) shadow->draw(arrays);
  std::optional<CubeMap> cube;
  if (o.env_cube) {
    const Vec3 center = 0.5 * (box.lo + box.hi);
    cube.emplace(
        raster3d::render_cube_map(center, 256, draw_surroundings, 1e-3 * glm::length(box.hi - box.lo), camera.far));
    u.maps.cube = &*cube;
  }
  for (int sample = 0; sample < o.samples; ++sample) {
    const Mat4 jittered =
        jittered_projection(projection, pixel_sample(sample, o.samples, kSamplePattern), f.width, f.height);
    u.set_camera(jittered, view);
    floor_uniforms.set_camera(jittered, view);
    fb.clear(o.background);
    // Light 0 off (0) or on (1), as the shadow volumes' passes ask; without them, on.
    const auto draw_scene = [&](const raster3d::RasterState& pass, float light0) {
      raster3d::RasterState mesh_state = pass;
      mesh_state.cull = o.cull;
      raster3d::SurfaceUniforms mesh_uniforms = u, fl = floor_uniforms;
      mesh_uniforms.light0 = fl.light0 = light0;
      raster3d::draw_surface(fb, mesh_state, arrays, mesh_uniforms, o.bump ? &tangents : nullptr);
      if (o.floor) raster3d::draw_surface(fb, pass, floor, fl);
    };
    if (volumes)
      raster3d::draw_with_shadow_volumes(fb, shadow_volumes, Mat4f(jittered * view),
                                         zfail ? raster3d::ShadowCount::zfail : raster3d::ShadowCount::zpass,
                                         draw_scene);
    else
      draw_scene(raster3d::RasterState{}, 1.0f);
    if (f.progress) f.progress->advance();
    if (o.environment) raster3d::fill_background(fb, *o.environment, jittered * view);
    resolve.add(fb, false);
  }
}

}  // namespace

namespace {

/// Throws InvalidInput when `options` put a texture or bump map on a mesh without uvs, or combine a program with the
/// maps.
void check_uvs(const PolyMesh& mesh, const MeshViewOptions& options) {
  if ((options.texture || options.bump) && mesh.uvs.empty() && mesh.corner_uvs.empty())
    throw InvalidInput("mesh view: a texture or bump map needs texture coordinates, and the mesh has none");
  if (options.program && options.maps())
    throw InvalidInput(
        "mesh view: a program draws the surface itself; the maps, shadows and floor do not combine with it");
}

}  // namespace

MeshView::MeshView(PolyMesh mesh, MeshViewOptions options) : source_(std::move(mesh)), options_(std::move(options)) {
  check_uvs(source_, options_);
  prepare();
}

void MeshView::set_options(MeshViewOptions options) {
  check_uvs(source_, options);  // before anything changes
  const MeshViewOptions& old = options_;
  const auto faceted = [](const MeshViewOptions& o) { return o.shading == MeshShading::flat; };
  const auto false_colors = [](const MeshViewOptions& o) { return o.shading == MeshShading::normals; };
  const bool again = faceted(old) != faceted(options) || false_colors(old) != false_colors(options) ||
                     old.face_colors != options.face_colors || old.turn_outward != options.turn_outward;
  const bool edges = options.wireframe != MeshWireframe::none && edge_lines_.empty();
  options_ = std::move(options);
  if (again)
    prepare();
  else if (edges)
    prepare_edges();
}

void MeshView::prepare() {
  const MeshViewOptions& o = options_;
  mesh_ = source_;
  turned_outward_ = false;
  // Normals come from the winding when the mesh has none: an inside-out mesh is drawn turned outward.
  const bool own_normals = !mesh_.normals.empty() || !mesh_.corner_normals.empty();
  if (o.turn_outward && !own_normals && mesh_.face_count() > 0 && winds_inward(mesh_)) {
    reverse_faces(mesh_);
    turned_outward_ = true;
  }
  if (!own_normals) compute_vertex_normals(mesh_);
  bounds_ = bounding_box(mesh_);
  // Flat shading and face colors need each polygon's own corners; otherwise the welded mesh, shared corners once.
  const bool facets = o.shading == MeshShading::flat;
  if (facets || !o.face_colors.empty()) {
    arrays_ = polygon_corners(mesh_, facets, o.face_colors, o.color);
  } else {
    arrays_ = raster3d::VertexArrays::from_mesh(to_tri_mesh(mesh_));
  }
  if (o.shading == MeshShading::normals) {
    arrays_.colors.resize(arrays_.normals.size());
    for (size_t i = 0; i < arrays_.normals.size(); ++i)
      arrays_.colors[i] = 0.5f * (glm::normalize(arrays_.normals[i]) + 1.0f);
  }
  triangles_ = arrays_.indices.size() / 3;
  prepare_edges();
}

void MeshView::prepare_edges() {
  edge_vertices_ = {};
  edge_lines_.clear();
  if (options_.wireframe == MeshWireframe::none) return;
  edge_vertices_.positions.assign(mesh_.positions.begin(), mesh_.positions.end());
  for (const auto& [a, b] : polygon_edges(mesh_)) edge_lines_.insert(edge_lines_.end(), {a, b});
}

Bounds3 MeshView::scene_bounds() const {
  Bounds3 scene = bounds_;
  if (options_.floor && !bounds_.empty())
    for (const Vec3f& p : floor_under(bounds_, options_.up_axis).positions) {
      scene.lo = glm::min(scene.lo, Vec3(p));
      scene.hi = glm::max(scene.hi, Vec3(p));
    }
  return scene;
}

void check_mesh_view_memory(int width, int height, const MeshViewOptions& options) {
  const auto s = uint64_t(std::max(1, options.supersample));
  const bool shadow_map = options.shadows && options.shadow_method == ShadowMethod::map;
  const auto shadow_size = uint64_t(std::max(0, options.shadow_size));
  MemoryBudget::check(saturating_product({uint64_t(std::max(0, width)), uint64_t(std::max(0, height)), 44, s, s}) +
                          (shadow_map ? saturating_product({shadow_size, shadow_size, 6}) : 0),
                      shadow_map ? fmt::format("rasterizing {}x{} pixels with a {}x{} shadow map", width, height,
                                               shadow_size, shadow_size)
                                 : fmt::format("rasterizing {}x{} pixels", width, height));
}

MeshPicture MeshView::render(const Camera& camera, int width, int height, Progress* progress) const {
  return render_impl(camera, width, height, progress, nullptr);
}

void MeshView::render_into(const Camera& camera, ImageRGBA8& out, Progress* progress) const {
  if (options_.samples == 1 && options_.supersample <= 1 && triangles_ > 0) {
    render_impl(camera, out.width(), out.height(), progress, &out);
    return;
  }
  const ImageRGB color = render(camera, out.width(), out.height(), progress).color;
  std::transform(color.pixels().begin(), color.pixels().end(), out.pixels().begin(),
                 [](const Vec3f& c) { return raster3d::to_color8(c); });
}

MeshPicture MeshView::render_impl(const Camera& camera, int width, int height, Progress* progress,
                                  ImageRGBA8* direct) const {
  const int s = std::max(1, options_.supersample);
  if (width <= 0 || height <= 0 || options_.samples < 1)
    throw InvalidInput(
        fmt::format("mesh view: bad image size {}x{} or sample count {}", width, height, options_.samples));
  check_mesh_view_memory(width, height, options_);
  if (triangles_ == 0) return {ImageRGB(width, height, options_.background), DepthImage(width, height, 1.0f), 0};
  SampleResolve resolve(width * s, height * s, options_.samples, direct);
  const Frame frame{options_, arrays_, edge_vertices_, edge_lines_, bounds_, width * s, height * s, s, progress};
  // Both paths draw into the kept context's framebuffer (the resolve may read it when the picture is taken).
  if (!context_ || context_->framebuffer().width() != frame.width || context_->framebuffer().height() != frame.height)
    context_ = std::make_unique<raster3d::Context>(frame.width, frame.height);
  if (options_.maps())
    draw_with_maps(frame, camera, context_->framebuffer(), resolve);
  else
    draw_fixed_function(frame, camera, *context_, resolve);
  return direct ? MeshPicture{} : resolve.take_picture(s);
}

MeshPicture render_mesh(const PolyMesh& mesh, const Camera& camera, int width, int height,
                        const MeshViewOptions& options) {
  return MeshView(mesh, options).render(camera, width, height);
}

}  // namespace tessera
