// The viewer's surfaces: a mesh with its subdivision levels, and Bezier patches at a tessellation density.
#include <fmt/format.h>

#include <vector>

#include "mesh_display.hpp"
#include "tessera/core/error.hpp"
#include "tessera/curves/bezier_patch.hpp"
#include "tessera/mesh/convert.hpp"
#include "tessera/mesh/measure.hpp"
#include "tessera/subdiv/subdivide.hpp"
#include "view_mode.hpp"

namespace tessera::detail {

OrbitControl frame_box(const Vec3& lo, const Vec3& hi, double aspect, int up_axis) {
  const Vec3 center = 0.5 * (lo + hi);
  const double radius = std::max(0.5 * glm::length(hi - lo), 1e-9);
  // Seen from 30 degrees to the right of the front and 20 degrees above, the sphere filling 1/1.1 of the view.
  const double right = std::sin(radians(30)) * std::cos(radians(20)), up = std::sin(radians(20)),
               front = std::cos(radians(30)) * std::cos(radians(20));
  const bool z_up = up_axis == 2;
  const Vec3 direction = z_up ? Vec3(right, -front, up) : Vec3(right, up, front);
  Camera camera;
  camera.aspect = aspect;
  camera.up = z_up ? Vec3(0, 0, 1) : Vec3(0, 1, 0);
  return OrbitControl(frame_sphere(camera, center, radius, direction, 1.1), center, radius);
}

namespace {

/// A mesh and its subdivision levels: Catmull-Clark, or Loop for a triangle mesh, creases kept (subdivide carries
/// them), each level made from the one below when first asked for.
class MeshMode final : public ViewMode {
 public:
  MeshMode(const Viewable& v, const ViewerOptions& o) : display_(o), name_(file_name(v.name)), up_axis_(o.up_axis) {
    levels_.push_back(v.mesh);
    box_ = bounding_box(v.mesh);
    scheme_ = v.mesh.is_triangle_mesh() ? SubdivisionScheme::loop : SubdivisionScheme::catmull_clark;
    display_.set_mesh(levels_[0]);
  }
  OrbitControl home(double aspect) const override { return frame_box(box_.lo, box_.hi, aspect, up_axis_); }
  void render(const Camera& camera, bool, ImageRGBA8& out) override { display_.render(camera, out); }
  bool key(int key, int) override {
    note_.clear();
    if (key == '+' || key == '=') return step(level_ + 1);
    if (key == '-') return step(level_ - 1);
    return display_.key(key);
  }
  std::string describe() const override {
    const PolyMesh& m = levels_[size_t(level_)];
    return fmt::format("{}: {} faces, {}, {} level {}{}", name_, m.face_count(), display_.describe(),
                       scheme_ == SubdivisionScheme::loop ? "Loop" : "Catmull-Clark", level_,
                       note_.empty() ? "" : fmt::format(" [{}]", note_));
  }
  size_t triangles() const override { return display_.triangles(); }
  bool poll() override { return display_.poll(); }

 private:
  /// The most faces a level may have (a 69k-triangle bunny reaches 4.4 million at level 3).
  static constexpr size_t kMaxFaces = size_t(5) << 20;

  bool step(int level) {
    if (level < 0) return false;
    if (level >= int(levels_.size())) {
      const PolyMesh& top = levels_.back();
      // Loop splits a triangle in 4, Catmull-Clark an n-gon into n quads.
      const size_t faces = scheme_ == SubdivisionScheme::loop ? 4 * top.face_count() : top.face_vertices.size();
      if (faces > kMaxFaces) {
        note_ = fmt::format("level {} would have {} faces", level, faces);
        return true;
      }
      try {
        levels_.push_back(subdivide(top, SubdivisionOptions{.scheme = scheme_, .levels = 1}));
      } catch (const Error& e) {  // a non-manifold mesh: say so and keep showing the level there is
        note_ = fmt::format("cannot subdivide: {}", e.what());
        return true;
      }
    }
    level_ = level;
    display_.set_mesh(levels_[size_t(level)]);
    return true;
  }

  MeshDisplay display_;
  std::string name_, note_;
  std::vector<PolyMesh> levels_;
  Bounds3 box_;
  SubdivisionScheme scheme_;
  int up_axis_, level_ = 0;
};

/// Bezier patches tessellated on a uniform grid of steps x steps per patch; + and - double and halve the steps.
class PatchMode final : public ViewMode {
 public:
  PatchMode(const Viewable& v, const ViewerOptions& o)
      : display_(o), name_(file_name(v.name)), patches_(v.patches), up_axis_(o.up_axis) {
    const PolyMesh net = control_net(patches_);  // the patches lie in their control points' convex hull
    box_ = bounding_box(net);
    tessellate_now();
  }
  OrbitControl home(double aspect) const override { return frame_box(box_.lo, box_.hi, aspect, up_axis_); }
  void render(const Camera& camera, bool, ImageRGBA8& out) override { display_.render(camera, out); }
  bool key(int key, int) override {
    if ((key == '+' || key == '=') && steps_ < kMaxSteps) {
      steps_ *= 2;
    } else if (key == '-' && steps_ > 1) {
      steps_ /= 2;
    } else {
      return display_.key(key);
    }
    tessellate_now();
    return true;
  }
  std::string describe() const override {
    return fmt::format("{}: {} patches, {}x{} steps each, {}", name_, patches_.size(), steps_, steps_,
                       display_.describe());
  }
  size_t triangles() const override { return display_.triangles(); }
  bool poll() override { return display_.poll(); }

 private:
  static constexpr int kMaxSteps = 128;
  void tessellate_now() {
    display_.set_mesh(to_poly_mesh(
        tessellate(patches_, PatchTessellation{.steps = steps_, .orientation = PatchOrientation::outward})));
  }

  MeshDisplay display_;
  std::string name_;
  std::vector<BezierPatch> patches_;
  Bounds3 box_;
  int up_axis_, steps_ = 8;
};

}  // namespace

std::unique_ptr<ViewMode> make_mesh_mode(const Viewable& v, const ViewerOptions& o) {
  return std::make_unique<MeshMode>(v, o);
}

std::unique_ptr<ViewMode> make_patch_mode(const Viewable& v, const ViewerOptions& o) {
  return std::make_unique<PatchMode>(v, o);
}

}  // namespace tessera::detail
