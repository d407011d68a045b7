// Program::draw_triangles: the vertex stage a batch of kLanes vertices at a time (in parallel), then the fragment
// stage on raster3d's quad stage.
#include <algorithm>
#include <cstring>

#include "execute.hpp"
#include "module.hpp"
#include "tessera/core/parallel.hpp"
#include "tessera/raster3d/quad_stage.hpp"

namespace tessera::glsl {
namespace {

/// The texture each sampler reads in this draw: its uniform names a unit, the unit holds what was bound.
std::vector<BoundSampler> bound_samplers(const ProgramModule& m) {
  std::vector<BoundSampler> out;
  for (const SamplerSlot& s : m.samplers) {
    const auto unit = size_t(std::min<uint32_t>(m.uniform_words[s.word], 15));
    BoundSampler b;
    if (s.cube)
      b.cube_map = m.cube_maps[unit].get();
    else
      b.texture = m.textures[unit].get();
    out.push_back(b);
  }
  return out;
}

/// Where one attribute's values come from in a draw: an array of `stride` floats per vertex (null: the constant
/// `current`), of which `components` are given.
struct AttributeSource {
  const float* data = nullptr;
  int stride = 0, components = 0;
  Vec4f current{0, 0, 0, 1};
};

AttributeSource attribute_source(const ProgramModule& m, const AttributeSlot& a, const ProgramInputs& in) {
  AttributeSource s;
  switch (a.source) {
    case AttributeSlot::Source::position:
      s = {&in.positions.data()->x, 3, 3, {}};
      break;
    case AttributeSlot::Source::normal:
      if (in.normals.empty())
        s.current = Vec4f(m.fixed.normal, 1);
      else
        s = {&in.normals.data()->x, 3, 3, {}};
      break;
    case AttributeSlot::Source::color:
      if (in.colors.empty())
        s.current = m.fixed.color;
      else
        s = {&in.colors.data()->x, 3, 3, {}};
      break;
    case AttributeSlot::Source::tex_coord0:
      if (in.uvs.empty())
        s.current = m.fixed.tex_coord;
      else
        s = {&in.uvs.data()->x, 2, 2, {}};
      break;
    case AttributeSlot::Source::user: {
      const auto found = in.attributes.find(a.name);
      if (found != in.attributes.end() && found->second.data) {
        s = {found->second.data, found->second.components, std::min(found->second.components, a.components), {}};
        break;
      }
      // A modern shader's usual names read the mesh's arrays (ProgramInputs).
      const std::string& n = a.name;
      if ((n == "position" || n == "vertex") && !in.positions.empty())
        s = {&in.positions.data()->x, 3, 3, {}};
      else if (n == "normal" && !in.normals.empty())
        s = {&in.normals.data()->x, 3, 3, {}};
      else if (n == "color" && !in.colors.empty())
        s = {&in.colors.data()->x, 3, 3, {}};
      else if ((n == "uv" || n == "texcoord" || n == "tex_coord") && !in.uvs.empty())
        s = {&in.uvs.data()->x, 2, 2, {}};
      else
        throw InvalidInput("the vertex shader reads attribute '" + a.name + "', which the draw does not give");
      break;
    }
  }
  if (s.data) s.current = Vec4f(0, 0, 0, 1);
  return s;
}

/// The fragment stage as a quad-stage shader.
class FragmentStage : public raster3d::QuadFragmentShader {
 public:
  FragmentStage(const ProgramModule& m, std::span<const BoundSampler> samplers) : m_(m), samplers_(samplers) {}

  struct Scratch : raster3d::QuadShaderScratch {
    explicit Scratch(Registers r) : registers(std::move(r)) {}
    Registers registers;
  };

  std::unique_ptr<raster3d::QuadShaderScratch> begin() const override {
    return std::make_unique<Scratch>(Registers(m_.fragment, m_.uniform_words, samplers_, true));
  }

  void shade(raster3d::FragmentBatch& b, raster3d::QuadShaderScratch& scratch) const override {
    Registers& r = static_cast<Scratch&>(scratch).registers;
    const size_t bytes = sizeof(float) * ir::kLanes;
    for (const auto& [reg, slot] : m_.fragment.inputs) {
      if (slot >= ir::kFrontFacing)
        std::memcpy(r.lanes(reg), b.front_facing, bytes);
      else if (slot >= ir::kFragCoord)
        std::memcpy(r.lanes(reg), b.frag_coord[slot - ir::kFragCoord], bytes);
      else
        std::memcpy(r.lanes(reg), b.varyings[slot], bytes);
    }
    r.run(4 * b.quads);
    // gl_FragColor not written: undefined in GLSL; black here.
    for (int k = 0; k < 4; ++k) std::fill(std::begin(b.color[k]), std::end(b.color[k]), 0.0f);
    for (const auto& [reg, slot] : m_.fragment.outputs) std::memcpy(b.color[slot], r.lanes(reg), bytes);
    if (m_.fragment.discards) std::memcpy(b.kept, r.ulanes(m_.fragment.kept), bytes);
  }

 private:
  const ProgramModule& m_;
  std::span<const BoundSampler> samplers_;
};

}  // namespace

raster3d::DrawStats Program::draw_triangles(raster3d::Framebuffer& framebuffer, const raster3d::RasterState& state,
                                            const ProgramInputs& inputs, std::span<const uint32_t> indices) const {
  const ProgramModule& m = *module_;
  const std::vector<BoundSampler> samplers = bound_samplers(m);
  std::vector<AttributeSource> sources;
  for (const AttributeSlot& a : m.attributes) sources.push_back(attribute_source(m, a, inputs));
  const size_t count = inputs.positions.size();
  const int stride = 4 + m.varying_count;
  std::vector<float> vertices(count * size_t(stride));
  // The vertex stage: batches of kLanes vertices, one register file per task.
  parallel_for(0, int64_t((count + ir::kLanes - 1) / ir::kLanes), 4, [&](int64_t begin, int64_t end) {
    Registers r(m.vertex, m.uniform_words, samplers, false);
    for (int64_t batch = begin; batch < end; ++batch) {
      const size_t first = size_t(batch) * ir::kLanes;
      const int lanes = int(std::min<size_t>(ir::kLanes, count - first));
      for (const auto& [reg, slot] : m.vertex.inputs) {
        // The attribute whose components hold this slot.
        size_t a = 0;
        while (a + 1 < m.attributes.size() && m.attributes[a + 1].first_slot <= slot) ++a;
        const AttributeSource& s = sources[a];
        const int component = int(slot - m.attributes[a].first_slot);
        float* out = r.lanes(reg);
        if (!s.data || component >= s.components) {
          std::fill_n(out, ir::kLanes, component < 4 ? s.current[component] : 0.0f);
          continue;
        }
        for (int l = 0; l < lanes; ++l) out[l] = s.data[(first + size_t(l)) * size_t(s.stride) + size_t(component)];
      }
      r.run(lanes);
      for (const auto& [reg, slot] : m.vertex.outputs) {
        const float* in = r.lanes(reg);
        for (int l = 0; l < lanes; ++l) vertices[(first + size_t(l)) * size_t(stride) + slot] = in[l];
      }
    }
  });
  const FragmentStage fragment(m, samplers);
  return raster3d::draw_triangles_quads(framebuffer, state, vertices, m.varying_count, indices, fragment);
}

}  // namespace tessera::glsl
