#include "mesh_display.hpp"

#include <fmt/format.h>

#include "view_mode.hpp"

namespace tessera::detail {
namespace {

/// A checkerboard of 8 x 8 cells over the unit square of uvs (what `t` shows without a texture image).
std::shared_ptr<const Texture2D> checkerboard() {
  constexpr int kSize = 256, kCell = kSize / 8;
  ImageRGBA8 image(kSize, kSize);
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x)
      image(x, y) = ((x / kCell + y / kCell) % 2) ? glm::u8vec4(235, 225, 200, 255) : glm::u8vec4(60, 90, 160, 255);
  return std::make_shared<const Texture2D>(std::move(image), Sampler{.filter = Filter::trilinear});
}

}  // namespace

MeshDisplay::MeshDisplay(const ViewerOptions& o)
    : shading_(o.shading), texture_path_(o.texture), up_axis_(o.up_axis), watch_(o.watch_shaders) {
  if (o.vertex_shader.empty() != o.fragment_shader.empty())
    throw InvalidInput("a GLSL program needs a vertex and a fragment shader");
  if (o.vertex_shader.empty()) return;
  const std::vector<std::string> uniforms = o.uniforms;
  const std::string texture = o.texture;
  program_ =
      std::make_unique<glsl::ProgramFiles>(o.vertex_shader, o.fragment_shader, [uniforms, texture](glsl::Program& p) {
        for (const std::string& u : uniforms) p.set_uniform_assignment(u);
        if (!texture.empty())
          p.bind_texture(
              0, std::make_shared<const Texture2D>(load_texture(texture, Sampler{.filter = Filter::trilinear})));
      });
}

void MeshDisplay::set_mesh(PolyMesh mesh) {
  has_uvs_ = !mesh.uvs.empty() || !mesh.corner_uvs.empty();
  if (!has_uvs_) textured_ = false;
  view_.emplace(std::move(mesh), options());
}

MeshViewOptions MeshDisplay::options() const {
  MeshViewOptions o;
  o.background = kBackground;
  switch (shading_) {
    case ViewShading::unlit:
      o.shading = MeshShading::unlit;
      break;
    case ViewShading::flat:
      o.shading = MeshShading::flat;
      break;
    case ViewShading::gouraud:
    case ViewShading::wireframe:
      o.shading = MeshShading::gouraud;
      break;
    case ViewShading::phong:
      o.shading = MeshShading::phong;
      break;
    case ViewShading::normals:
      o.shading = MeshShading::normals;
      break;
  }
  o.wireframe = shading_ == ViewShading::wireframe ? MeshWireframe::alone
                : edges_                           ? MeshWireframe::over
                                                   : MeshWireframe::none;
  o.up_axis = up_axis_;
  if (program_) {  // the program shades: no maps
    o.program = program_->program();
    return o;
  }
  o.shadows = o.floor = shadows_;
  if (textured_) {
    if (!texture_)
      texture_ =
          texture_path_.empty() ? checkerboard() : std::make_shared<const Texture2D>(load_texture(texture_path_));
    o.texture = texture_;
  }
  return o;
}

void MeshDisplay::render(const Camera& camera, ImageRGBA8& out) const { view_->render_into(camera, out); }

bool MeshDisplay::key(int key) {
  note_.clear();
  if (key >= '1' && key <= '6') {
    shading_ = ViewShading(key - '1');
  } else if (key == 'w') {
    edges_ = !edges_;
  } else if ((key == 'd' || key == 't') && program_) {
    note_ = "the program shades the surface";
    return true;
  } else if (key == 'd') {
    shadows_ = !shadows_;
  } else if (key == 't') {
    if (!has_uvs_) {
      note_ = "no texture coordinates";
      return true;
    }
    textured_ = !textured_;
  } else {
    return false;
  }
  view_->set_options(options());
  return true;
}

bool MeshDisplay::poll() {
  if (!program_ || !watch_ || !program_->reload()) return false;
  if (program_->error().empty()) {
    view_->set_options(options());
    note_ = "reloaded";
  }
  return true;
}

std::string MeshDisplay::describe() const {
  if (program_) {
    std::string s = "program " + program_->name();
    if (edges_) s += ", edges";
    // The compile error's first line: the rest of the message is the same error's context.
    const std::string& error = program_->error();
    if (!error.empty()) s += fmt::format(" [{}]", error.substr(0, error.find('\n')));
    if (!note_.empty()) s += fmt::format(" [{}]", note_);
    return s;
  }
  std::string s(shading_name(shading_));
  if (const MeshViewOptions o = view_->options(); o.maps() && shading_ != ViewShading::phong)
    s += " (per pixel with maps)";
  if (edges_ && shading_ != ViewShading::wireframe) s += ", edges";
  if (shadows_) s += ", shadows";
  if (textured_) s += ", texture";
  if (!note_.empty()) s += fmt::format(" [{}]", note_);
  return s;
}

}  // namespace tessera::detail
