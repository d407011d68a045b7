// The preview renderer: project vertices with the camera's view and projection matrices, fill each polygon as a fan
// of triangles with edge functions (pixel centers, z-buffer), shade each face flat by its normal, then draw the edges
// as depth-tested lines. Rendered at 2x2 samples per pixel and box-filtered down.
#include "preview.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "tessera/mesh/measure.hpp"
#include "tessera/mesh/normals.hpp"

namespace tessera::examples {
namespace {

constexpr int kSamples = 2;              // supersampling per axis
constexpr float kWireDepthBias = 2e-3f;  // lines win over the surface they lie on (normalized device depth)

/// A camera looking at the mesh's bounding sphere from direction (1, 0.8, 1.6), the sphere filling the view.
Camera frame_mesh(const PolyMesh& mesh) {
  const Bounds3 box = bounding_box(mesh);
  Camera camera;
  if (box.empty()) return camera;
  const Vec3 center = 0.5 * (box.lo + box.hi);
  double radius = 0;
  for (const Vec3& p : mesh.positions) radius = std::max(radius, glm::distance(p, center));
  radius = std::max(radius, 1e-9);
  const double distance = 1.08 * radius / std::sin(camera.fovy / 2);
  camera.center = center;
  camera.eye = center + distance * glm::normalize(Vec3(1, 0.8, 1.6));
  camera.near = std::max(distance - 1.5 * radius, 1e-3 * distance);
  camera.far = distance + 1.5 * radius;
  return camera;
}

/// A vertex in screen space: pixel coordinates (row 0 at the top) and normalized device depth.
struct ScreenVertex {
  float x, y, z;
  bool visible;  // in front of the eye and between the near and far planes
};

/// The signed doubled area of (a, b, p): the edge function of edge a->b at p.
float edge(const ScreenVertex& a, const ScreenVertex& b, float px, float py) {
  return (b.x - a.x) * (py - a.y) - (b.y - a.y) * (px - a.x);
}

class Target {
 public:
  Target(int width, int height, const Vec3f& background)
      : width_(width),
        height_(height),
        color_(size_t(width) * height, background),
        depth_(size_t(width) * height, std::numeric_limits<float>::infinity()) {}

  /// Fills the triangle with a constant color where it is nearer than the z-buffer (either winding).
  void fill_triangle(const ScreenVertex& a, const ScreenVertex& b, const ScreenVertex& c, const Vec3f& color) {
    const float area = edge(a, b, c.x, c.y);
    if (area == 0 || !std::isfinite(area)) return;
    const int x0 = std::max(0, int(std::floor(std::min({a.x, b.x, c.x}))));
    const int x1 = std::min(width_ - 1, int(std::ceil(std::max({a.x, b.x, c.x}))));
    const int y0 = std::max(0, int(std::floor(std::min({a.y, b.y, c.y}))));
    const int y1 = std::min(height_ - 1, int(std::ceil(std::max({a.y, b.y, c.y}))));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const float px = float(x) + 0.5f, py = float(y) + 0.5f;
        // Barycentric weights: each edge function over the whole area (all >= 0 inside for either winding).
        const float wa = edge(b, c, px, py) / area, wb = edge(c, a, px, py) / area, wc = edge(a, b, px, py) / area;
        if (wa < 0 || wb < 0 || wc < 0) continue;
        plot(x, y, wa * a.z + wb * b.z + wc * c.z, color, 0.0f);
      }
  }

  /// Draws a line kSamples pixels wide, depth-tested with a small bias toward the viewer.
  void line(const ScreenVertex& a, const ScreenVertex& b, const Vec3f& color) {
    const float steps = std::ceil(std::max(std::abs(b.x - a.x), std::abs(b.y - a.y)));
    if (!std::isfinite(steps) || steps > 1e5f) return;
    for (float i = 0; i <= steps; ++i) {
      const float t = steps > 0 ? i / steps : 0.0f;
      const float x = a.x + t * (b.x - a.x) - 0.5f * kSamples, y = a.y + t * (b.y - a.y) - 0.5f * kSamples;
      const float z = a.z + t * (b.z - a.z);
      for (int dy = 0; dy < kSamples; ++dy)
        for (int dx = 0; dx < kSamples; ++dx)
          plot(int(std::lround(x)) + dx, int(std::lround(y)) + dy, z, color, kWireDepthBias);
    }
  }

  /// Box-filters kSamples x kSamples blocks into the output image.
  ImageRGB resolve() const {
    ImageRGB out(width_ / kSamples, height_ / kSamples);
    for (int y = 0; y < out.height(); ++y)
      for (int x = 0; x < out.width(); ++x) {
        Vec3f sum(0.0f);
        for (int dy = 0; dy < kSamples; ++dy)
          for (int dx = 0; dx < kSamples; ++dx) sum += color_[size_t(y * kSamples + dy) * width_ + x * kSamples + dx];
        out(x, y) = sum / float(kSamples * kSamples);
      }
    return out;
  }

 private:
  void plot(int x, int y, float z, const Vec3f& color, float bias) {
    if (x < 0 || y < 0 || x >= width_ || y >= height_) return;
    float& d = depth_[size_t(y) * width_ + x];
    if (z - bias > d) return;
    d = std::min(d, z);
    color_[size_t(y) * width_ + x] = color;
  }

  int width_, height_;
  std::vector<Vec3f> color_;
  std::vector<float> depth_;
};

}  // namespace

ImageRGB render_preview(const PolyMesh& mesh, const PreviewOptions& options) {
  Camera camera = options.camera ? *options.camera : frame_mesh(mesh);
  camera.aspect = double(options.width) / options.height;
  const Mat4 clip_from_world = camera.projection() * camera.view();
  const int width = options.width * kSamples, height = options.height * kSamples;

  std::vector<ScreenVertex> screen(mesh.vertex_count());
  for (size_t v = 0; v < screen.size(); ++v) {
    const Vec4 clip = clip_from_world * Vec4(mesh.positions[v], 1.0);
    const bool visible = clip.w > 0 && std::abs(clip.z) <= clip.w;
    const Vec3 ndc = Vec3(clip) / clip.w;
    screen[v] = {float((ndc.x * 0.5 + 0.5) * width), float((0.5 - ndc.y * 0.5) * height), float(ndc.z), visible};
  }

  Target target(width, height, options.background);
  const Vec3 light = glm::normalize(options.light_dir);
  for (size_t f = 0; f < mesh.face_count(); ++f) {
    const auto face = mesh.face(f);
    if (std::any_of(face.begin(), face.end(), [&](uint32_t v) { return !screen[v].visible; })) continue;
    Vec3 normal = face_normal(mesh, f);
    // A face seen from behind is lit as if flipped and drawn darker, so open surfaces read clearly.
    const bool back = glm::dot(normal, camera.eye - mesh.positions[face[0]]) < 0;
    if (back) normal = -normal;
    const Vec3f base = f < options.face_colors.size() ? options.face_colors[f] : options.color;
    const float shade = 0.25f + 0.75f * float(std::max(0.0, glm::dot(normal, light)));
    const Vec3f color = base * shade * (back ? 0.55f : 1.0f);
    for (size_t i = 1; i + 1 < face.size(); ++i)
      target.fill_triangle(screen[face[0]], screen[face[i]], screen[face[i + 1]], color);
  }
  if (options.wireframe)
    for (size_t f = 0; f < mesh.face_count(); ++f) {
      const auto face = mesh.face(f);
      for (size_t i = 0; i < face.size(); ++i) {
        const ScreenVertex& a = screen[face[i]];
        const ScreenVertex& b = screen[face[(i + 1) % face.size()]];
        if (a.visible && b.visible) target.line(a, b, options.wire_color);
      }
    }
  return target.resolve();
}

}  // namespace tessera::examples
