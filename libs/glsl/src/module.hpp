#pragma once
// What Program holds: the two compiled stages and the tables that connect them to uniforms, attributes and textures.
#include <array>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "ir.hpp"
#include "tessera/glsl/program.hpp"

namespace tessera::glsl {

/// Where a uniform's value lives: `components` 32-bit words of ProgramModule::uniform_words from `word` (floats or
/// ints as `is_float` says; a bool is 0 or 1 there and the compiler turns it into a mask).
struct UniformSlot {
  std::string name;  // "gl_LightSource[0].position", "weights[2]", "material.color"
  BasicType type;
  int components;
  uint32_t word;
  bool is_float;
  bool builtin;  // a gl_ built-in (set by set_fixed_function)
};

/// A sampler the stages read: the uniform word holding its texture unit, and its kind.
struct SamplerSlot {
  uint32_t word;
  bool cube;
};

/// A vertex shader input: an attribute of `components` floats whose component k lands in vertex input slot
/// `first_slot + k` (ir::Stage::inputs).
struct AttributeSlot {
  enum class Source { position, normal, color, tex_coord0, user };
  std::string name;
  Source source;
  int components;
  uint32_t first_slot;
};

/// A compiled program.
struct ProgramModule {
  ir::Stage vertex, fragment;
  std::vector<uint32_t> uniform_words;
  std::vector<UniformSlot> uniforms;  // every uniform scalarized to basic types, built-ins included
  std::vector<UniformInfo> user_uniforms;
  std::set<std::string> declared_uniforms;  // the user uniforms the sources declare, active or not
  std::vector<SamplerSlot> samplers;        // indexed by ir::Instr::unit
  std::vector<AttributeSlot> attributes;
  int varying_count = 0;  // floats passed from the vertex to the fragment stage
  std::array<std::shared_ptr<const Texture2D>, 16> textures;
  std::array<std::shared_ptr<const CubeMap>, 16> cube_maps;
  FixedFunctionState fixed;  // the built-ins' values and the current attributes (set_fixed_function)
};

/// Compiles and links the two sources into a module (compile.cpp). Throws CompileError.
std::unique_ptr<ProgramModule> compile_module(const ShaderSource& vertex, const ShaderSource& fragment);

}  // namespace tessera::glsl
