// Example 29: the notes' four GLSL programs from their source (examples/shaders/notes_*, embedded at build time),
// compiled by glslang and run by Tessera's GLSL executor on the quad fragment stage: the diffuse program (red times
// N . L per pixel, a point light just above the front of a torus), the twisting vertex program (a finely divided
// square, its vertices rotated more the farther they lie from the notes' center), the texture program (a checkered
// square in perspective, trilinear MIPmaps) and the two-texture program (one disc sampled 0.2 to either side: the
// notes' Venn diagram). The glsl tests draw the same scenes with Mesa and compare; docs/gallery/
// 29_glsl_programs_mesa.png is Mesa's picture.
#include "gallery.hpp"
#include "glsl_notes_scenes.hpp"
#include "notes_shader_sources.hpp"
#include "tessera/image/image_io.hpp"

TESSERA_EXAMPLE(ex29_glsl_programs, "29_glsl_programs", "The notes' GLSL programs, run as written") {
  using namespace tessera;
  const std::map<std::string, std::pair<const char*, const char*>> sources = {
      {"notes_diffuse", {examples::kNotesDiffuseVert, examples::kNotesDiffuseFrag}},
      {"notes_twist", {examples::kNotesTwistVert, examples::kNotesTwistFrag}},
      {"notes_texture", {examples::kNotesTextureVert, examples::kNotesTextureFrag}},
      {"notes_two_textures", {examples::kNotesTwoTexturesVert, examples::kNotesTwoTexturesFrag}}};
  std::vector<ImageRGB> panels;
  for (const examples::NotesScene& scene : examples::notes_scenes()) {
    const auto& [vertex, fragment] = sources.at(scene.program);
    panels.push_back(to_rgb(to_float(examples::draw_with_tessera(scene, vertex, fragment))));
  }
  gallery.add("29_glsl_programs.png", examples::side_by_side(panels),
              "The notes' GLSL programs from their source, on Tessera's CPU pipeline: diffuse, twisting, texture and "
              "two textures (the Venn diagram).");
}
