#pragma once
// Lane shaders: C++ fragment shaders written in the SIMD vocabulary of lanes.hpp, run on the quad stage
// (quad_stage.hpp) eight fragments (two quads) at a time. A lane shader is any callable
// `lanes::vec4 fs(const lanes::Fragment<V>& in, lanes::Mask& kept)` (or returning lanes::vec3, alpha 1), V the vertex
// shader's varyings struct: `in(&V::member)` is that member's value interpolated on the lanes; the shader clears the
// lanes of `kept` it discards. draw_triangles (below) takes one where it takes a per-pixel shader (shaders.hpp), which
// stays the simple interface for shaders that do not need the speed.
#include <algorithm>
#include <cstring>
#include <memory>
#include <span>
#include <type_traits>

#include "tessera/raster3d/lanes.hpp"
#include "tessera/raster3d/pipeline.hpp"
#include "tessera/raster3d/quad_stage.hpp"

namespace tessera::raster3d::lanes {

// ---- Fragments -----------------------------------------------------------------------------------------------------

/// The floats in a varyings member of type T: 1 for float, T::length() for a glm vector.
template <class T>
constexpr int member_floats() {
  if constexpr (std::is_same_v<T, float>)
    return 1;
  else
    return T::length();
}

/// The lanes type of a varyings member type: float -> Float, Vec2f -> vec2, Vec3f -> vec3, Vec4f -> vec4.
template <class T>
using LanesOf = std::conditional_t<member_floats<T>() == 1, Float, Vec<std::max(member_floats<T>(), 2)>>;

/// What a lane shader reads: eight lanes of a FragmentBatch (two quads), starting at `first`.
template <class V>
class Fragment {
 public:
  Fragment(const FragmentBatch& batch, int first) : batch_(batch), first_(first) {}

  /// Member `m` of the varyings, interpolated on the lanes: `in(&V::normal)` is a vec3 for a Vec3f normal.
  template <class T>
  LanesOf<T> operator()(T V::*m) const {
    static const V probe{};  // a real object: the member's offset without offsetof on a pointer to member
    const auto first =
        size_t(reinterpret_cast<const char*>(&(probe.*m)) - reinterpret_cast<const char*>(&probe)) / sizeof(float);
    LanesOf<T> r;
    if constexpr (std::is_same_v<T, float>)
      r = varying(int(first));
    else
      for (int i = 0; i < T::length(); ++i) r[i] = varying(int(first) + i);
    return r;
  }
  /// Varying float k (the k-th float of V).
  Float varying(int k) const { return Float::load(batch_.varyings[k] + first_); }
  /// gl_FragCoord: window x and y of the pixel center, window depth, 1/w.
  vec4 frag_coord() const {
    return {Float::load(batch_.frag_coord[0] + first_), Float::load(batch_.frag_coord[1] + first_),
            Float::load(batch_.frag_coord[2] + first_), Float::load(batch_.frag_coord[3] + first_)};
  }
  /// gl_FrontFacing.
  Mask front_facing() const { return load_mask(batch_.front_facing); }
  /// The lanes that are covered and passed the tests (the others are helper lanes: computed, never written).
  Mask covered() const { return load_mask(batch_.covered); }

 private:
  Mask load_mask(const uint32_t* lanes) const {
    Mask m;
    std::memcpy(&m.q, lanes + first_, sizeof m.q);
    return m;
  }
  const FragmentBatch& batch_;
  int first_;
};

/// A lane shader over varyings V, returning RGBA (vec4) or RGB (vec3, alpha 1).
template <class FS, class V>
concept FragmentShader = requires(const FS& fs, const Fragment<V>& in, Mask& kept) {
  requires std::is_same_v<decltype(fs(in, kept)), vec4> || std::is_same_v<decltype(fs(in, kept)), vec3>;
};

/// The quad stage's shader that runs lane shader FS eight lanes at a time.
template <class V, class FS>
class QuadShader : public QuadFragmentShader {
 public:
  explicit QuadShader(FS fs) : fs_(std::move(fs)) {}
  std::unique_ptr<QuadShaderScratch> begin() const override { return std::make_unique<QuadShaderScratch>(); }
  void shade(FragmentBatch& batch, QuadShaderScratch&) const override {
    if (batch.quads % 2) copy_last_quad(batch);
    for (int first = 0; first < 4 * batch.quads; first += kWidth) {
      const Fragment<V> in(batch, first);
      Mask kept(true);
      const auto color = fs_(in, kept);
      for (int c = 0; c < 3; ++c) color[c].store(batch.color[c] + first);
      if constexpr (std::is_same_v<std::remove_cvref_t<decltype(color)>, vec4>)
        color.w.store(batch.color[3] + first);
      else
        Float(1.0f).store(batch.color[3] + first);
      std::memcpy(batch.kept + first, &kept.q, sizeof kept.q);
    }
  }

 private:
  /// The lanes past an odd batch's last quad repeat it, uncovered: the last call's second quad reads defined values.
  static void copy_last_quad(FragmentBatch& b) {
    const int from = 4 * (b.quads - 1), to = 4 * b.quads;
    const auto copy = [&](float* lanes) { std::memcpy(lanes + to, lanes + from, 4 * sizeof(float)); };
    for (int k = 0; k < b.varying_count; ++k) copy(b.varyings[k]);
    for (auto& coordinate : b.frag_coord) copy(coordinate);
    std::memcpy(b.front_facing + to, b.front_facing + from, 4 * sizeof(uint32_t));
    std::memset(b.covered + to, 0, 4 * sizeof(uint32_t));
  }
  FS fs_;
};

}  // namespace tessera::raster3d::lanes

namespace tessera::raster3d {

namespace detail {
/// The vertex stage of `vs`, then the quad stage with `fs`, returning before the raster thread has finished the last
/// pass (as draw_triangles_async; collect_raster waits): what draw_triangles with a lane shader and Context's Phong
/// draws share.
template <VertexShader VS>
DrawStats draw_quads_async(Framebuffer& framebuffer, const RasterState& state, uint32_t vertex_count,
                           std::span<const uint32_t> indices, const VS& vs,
                           std::shared_ptr<const QuadFragmentShader> fs) {
  check_draw(framebuffer, state, indices, vertex_count, 3, "triangle");
  RasterScratch& scratch = framebuffer.scratch();
  scratch.input ^= 1;  // as draw_triangles_async: the previous draw's job may still read the other input set
  run_vertex_stage(scratch, vertex_count, vs);
  return draw_staged_quads_async(framebuffer, state, vertex_count, varying_count<VaryingsOf<VS>>, indices,
                                 std::move(fs));
}
}  // namespace detail

/// draw_triangles with a lane shader (lanes::FragmentShader): the vertex stage as for any fragment shader, then the
/// quad stage (draw_triangles_quads) runs `fs` eight fragments at a time. Throws as draw_triangles_quads.
template <VertexShader VS, lanes::FragmentShader<VaryingsOf<VS>> FS>
DrawStats draw_triangles(Framebuffer& framebuffer, const RasterState& state, uint32_t vertex_count,
                         std::span<const uint32_t> indices, const VS& vs, const FS& fs) {
  DrawStats stats = detail::draw_quads_async(framebuffer, state, vertex_count, indices, vs,
                                             std::make_shared<lanes::QuadShader<VaryingsOf<VS>, FS>>(fs));
  stats.rasterized += detail::collect_raster(framebuffer.scratch());
  return stats;
}

}  // namespace tessera::raster3d
