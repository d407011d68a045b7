// GLSL to register programs: glslang parses, type-checks and links the two shaders; this walks glslang's typed syntax
// tree and emits ir::Instr (ir.hpp), scalarizing every value.
//
// Why the syntax tree and not SPIR-V: glslang makes SPIR-V only from GLSL 1.40 (Vulkan) or 3.30 (OpenGL) on and
// refuses the compatibility profile, while the notes' programs are GLSL 1.10 with the compatibility built-ins
// (gl_Vertex, gl_ModelViewMatrix, gl_LightSource[], ftransform()). The tree has them all, typed and constant-folded.
//
// Variables are bound to registers, not stored in them: an assignment rebinds the variable to the value's registers
// (no copy), so straight-line code is in SSA form and a value computed only from constants and uniforms can move to
// the prologue (once per scratch). Under an execution mask (inside an if, or a loop some lanes have left) an
// assignment binds the variable to select(mask, new, old). Loops need fixed registers for what they change: on entry
// every bound variable is copied into fresh loop registers, and the end of the body copies the new bindings back.
#include <glslang/Include/intermediate.h>
#include <glslang/MachineIndependent/localintermediate.h>
#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>

#include <algorithm>
#include <bit>
#include <cstring>
#include <map>
#include <mutex>
#include <sstream>
#include <string>
#include <vector>

#include "module.hpp"
#include "tessera/core/error.hpp"

namespace tessera::glsl {
namespace {

using glslang::TIntermAggregate;
using glslang::TIntermBinary;
using glslang::TIntermBranch;
using glslang::TIntermConstantUnion;
using glslang::TIntermLoop;

using glslang::TIntermSelection;
using glslang::TIntermSymbol;
using glslang::TIntermTyped;
using glslang::TIntermUnary;
using glslang::TType;
using ir::Op;

constexpr uint32_t kNoMask = UINT32_MAX;  // every lane executes

/// A value: its scalar registers, in GLSL's order (vectors by component, matrices by column, arrays by element,
/// structs by member).
using Regs = std::vector<uint32_t>;

enum class Scalar { f, i, b };

Scalar scalar_of(const TType& type) {
  switch (type.getBasicType()) {
    case glslang::EbtFloat:
      return Scalar::f;
    case glslang::EbtInt:
    case glslang::EbtUint:
    case glslang::EbtSampler:
      return Scalar::i;
    case glslang::EbtBool:
      return Scalar::b;
    default:
      return Scalar::f;
  }
}

/// The register of element (major, minor) of a run of `per` registers a major index (a matrix's column and row, an
/// array's element and component).
size_t element(int major, int per, int minor) { return size_t(major) * size_t(per) + size_t(minor); }

/// The number of scalar registers of a value of `type`.
int slot_count(const TType& type) {
  int elements = 1;
  if (type.isArray())
    elements = std::max(1, type.isSizedArray() ? type.getCumulativeArraySize() : type.getImplicitArraySize());
  int per = 0;
  if (type.isStruct()) {
    for (const glslang::TTypeLoc& member : *type.getStruct()) per += slot_count(*member.type);
  } else if (type.isMatrix()) {
    per = type.getMatrixCols() * type.getMatrixRows();
  } else {
    per = type.getVectorSize();
  }
  return elements * per;
}

/// A type one array level down.
TType element_type(const TType& type) { return TType(type, 0); }

/// The register offset of struct member `index`.
int member_offset(const TType& type, int index) {
  int offset = 0;
  for (int m = 0; m < index; ++m) offset += slot_count(*(*type.getStruct())[size_t(m)].type);
  return offset;
}

/// Which scalar types GLSL has at each flattened position of a type (for structs of mixed members).
void scalar_layout(const TType& type, std::vector<Scalar>& out) {
  if (type.isArray()) {
    const TType element = element_type(type);
    const int n = std::max(1, type.isSizedArray() ? type.getOuterArraySize() : type.getImplicitArraySize());
    for (int e = 0; e < n; ++e) scalar_layout(element, out);
  } else if (type.isStruct()) {
    for (const glslang::TTypeLoc& member : *type.getStruct()) scalar_layout(*member.type, out);
  } else {
    out.insert(out.end(), size_t(slot_count(type)), scalar_of(type));
  }
}

BasicType basic_type(const TType& type) {
  if (type.getBasicType() == glslang::EbtSampler)
    return type.getSampler().dim == glslang::EsdCube ? BasicType::sampler_cube : BasicType::sampler_2d;
  if (type.isMatrix()) {
    const int n = type.getMatrixCols();
    return n == 2 ? BasicType::mat2 : n == 3 ? BasicType::mat3 : BasicType::mat4;
  }
  const int n = type.getVectorSize() - 1;
  switch (scalar_of(type)) {
    case Scalar::f:
      return BasicType(int(BasicType::floating) + n);
    case Scalar::i:
      return BasicType(int(BasicType::integer) + n);
    case Scalar::b:
      return BasicType(int(BasicType::boolean) + n);
  }
  return BasicType::floating;
}

/// One instruction's register operands (the rest are numbers): which of a, b, c, d it reads.
int operand_count(Op op) {
  if (op == Op::gather) return 0;  // b is read too, handled apart
  if (op <= Op::ftanh || op == Op::ineg || op == Op::iabs || (op >= Op::itof && op <= Op::btoi) || op == Op::bnot)
    return 1;
  if (op >= Op::fclamp && op <= Op::fsmoothstep) return 3;
  if (op == Op::select) return 3;
  return 2;
}

/// Whether an instruction is a pure function of its operands, the same in every lane when they are (so that it can
/// run in the prologue).
bool hoistable(Op op) { return !(op == Op::dfdx || op == Op::dfdy || op >= Op::tex2d); }

class CompileFailure : public std::exception {
 public:
  CompileFailure(int at_line, std::string what) : line(at_line), message(std::move(what)) {}
  int line;
  std::string message;
};

/// Compiles one stage's syntax tree.
class StageCompiler {
 public:
  StageCompiler(ProgramModule& module, ir::Stage& stage, bool fragment)
      : module_(module), stage_(stage), fragment_(fragment) {}

  /// What a stage leaves for linking: the final registers of each output variable by name (vertex), the input
  /// registers of each varying by name (fragment).
  std::map<std::string, Regs> outputs, varying_inputs;
  std::map<std::string, std::vector<Scalar>> varying_layouts;

  void compile(TIntermNode* root) {
    TIntermAggregate* sequence = root->getAsAggregate();
    if (!sequence) fail(root, "empty shader");
    // Functions by name; global initializers run before main.
    std::vector<TIntermNode*> globals;
    for (TIntermNode* node : sequence->getSequence()) {
      TIntermAggregate* a = node->getAsAggregate();
      if (a && a->getOp() == glslang::EOpFunction)
        functions_[std::string(a->getName().c_str())] = a;
      else if (a && a->getOp() == glslang::EOpLinkerObjects)
        record_declared_uniforms(a);
      else
        globals.push_back(node);
    }
    for (TIntermNode* node : globals) statement(node);
    const auto main = functions_.find("main(");
    if (main == functions_.end()) fail(root, "no main() function");
    call_function(main->second, {}, nullptr);
    finish();
  }

  uint32_t kept_input = 0;

 private:
  /// The user uniforms the stage declares, used or not (setting one the program does not use does nothing, as in
  /// OpenGL, where its location is -1).
  void record_declared_uniforms(TIntermAggregate* linker_objects) {
    for (TIntermNode* node : linker_objects->getSequence())
      if (const TIntermSymbol* symbol = node->getAsSymbolNode();
          symbol && symbol->getQualifier().storage == glslang::EvqUniform &&
          symbol->getName().compare(0, 3, "gl_") != 0)
        module_.declared_uniforms.insert(symbol->getName().c_str());
  }

  [[noreturn]] void fail(const TIntermNode* node, const std::string& message) {
    throw CompileFailure(node ? node->getLoc().line : 0, message);
  }

  // ---- registers and instructions

  uint32_t fresh(int count = 1) {
    if (stage_.register_count + uint32_t(count) > ir::kMaxRegisters ||
        stage_.code.size() + stage_.prologue.size() > ir::kMaxInstructions)
      throw CompileFailure(0, "the program is too large for Tessera's executor (more than " +
                                  std::to_string(ir::kMaxRegisters) + " registers or " +
                                  std::to_string(ir::kMaxInstructions) + " instructions)");
    const uint32_t r = stage_.register_count;
    stage_.register_count += uint32_t(count);
    uniform_.resize(stage_.register_count, false);
    return r;
  }

  uint32_t constant_bits(uint32_t bits) {
    auto [it, inserted] = constants_.try_emplace(bits, 0);
    if (inserted) {
      it->second = fresh();
      uniform_[it->second] = true;
      stage_.constants.emplace_back(it->second, bits);
    }
    return it->second;
  }
  uint32_t constant(float v) { return constant_bits(std::bit_cast<uint32_t>(v)); }
  uint32_t constant_int(int32_t v) { return constant_bits(uint32_t(v)); }
  uint32_t constant_bool(bool v) { return constant_bits(v ? ~0u : 0u); }

  uint32_t emit(Op op, uint32_t a = 0, uint32_t b = 0, uint32_t c = 0, uint32_t d = 0) {
    ir::Instr instr;
    instr.op = op;
    instr.a = a, instr.b = b, instr.c = c, instr.d = d;
    const int n = operand_count(op);
    const uint32_t operands[3] = {a, b, c};
    bool all_uniform = hoistable(op) && n > 0;
    for (int k = 0; k < n && all_uniform; ++k) all_uniform = uniform_[operands[k]];
    instr.dst = fresh(op >= Op::tex2d && op <= Op::texcube_lod ? 4 : 1);
    if (all_uniform) {
      uniform_[instr.dst] = true;
      stage_.prologue.push_back(instr);
    } else {
      stage_.code.push_back(instr);
    }
    return instr.dst;
  }

  /// A copy into an existing register (loop registers, the kept register): always in the per-batch code.
  void move_into(uint32_t dst, uint32_t src) {
    if (dst == src) return;
    ir::Instr instr;
    instr.op = Op::mov;
    instr.dst = dst;
    instr.a = src;
    stage_.code.push_back(instr);
  }

  int jump(Op op, uint32_t a, int target = -1) {
    ir::Instr instr;
    instr.op = op;
    instr.a = a;
    instr.target = target;
    stage_.code.push_back(instr);
    return int(stage_.code.size()) - 1;
  }

  uint32_t band(uint32_t a, uint32_t b) {
    if (a == kNoMask) return b;
    if (b == kNoMask) return a;
    return emit(Op::band, a, b);
  }
  uint32_t bnot(uint32_t a) { return emit(Op::bnot, a); }
  uint32_t masked(uint32_t value, uint32_t old) {
    return mask_ == kNoMask ? value : emit(Op::select, mask_, value, old);
  }

  // ---- values

  Regs zeros(const TType& type) {
    std::vector<Scalar> layout;
    scalar_layout(type, layout);
    Regs out;
    for (Scalar s : layout)
      out.push_back(s == Scalar::f ? constant(0.0f) : s == Scalar::i ? constant_int(0) : constant_bool(false));
    return out;
  }

  Regs constant_union(const TIntermConstantUnion* node) {
    const glslang::TConstUnionArray& array = node->getConstArray();
    Regs out;
    for (int k = 0; k < array.size(); ++k) {
      const glslang::TConstUnion& u = array[k];
      switch (u.getType()) {
        case glslang::EbtFloat:
        case glslang::EbtDouble:
          out.push_back(constant(float(u.getDConst())));
          break;
        case glslang::EbtInt:
          out.push_back(constant_int(u.getIConst()));
          break;
        case glslang::EbtUint:
          out.push_back(constant_int(int32_t(u.getUConst())));
          break;
        case glslang::EbtBool:
          out.push_back(constant_bool(u.getBConst()));
          break;
        default:
          fail(node, "unsupported constant type");
      }
    }
    return out;
  }

  // ---- uniforms, attributes, varyings

  /// The storage of uniform `name` of `type`, flattened to basic members (declared on first use, shared by both
  /// stages): the uniform words in order.
  void declare_uniform(const std::string& name, const TType& type, bool builtin, std::vector<uint32_t>& words) {
    if (type.isArray()) {
      const TType element = element_type(type);
      const int n = std::max(1, type.isSizedArray() ? type.getOuterArraySize() : type.getImplicitArraySize());
      for (int e = 0; e < n; ++e) declare_uniform(name + "[" + std::to_string(e) + "]", element, builtin, words);
      return;
    }
    if (type.isStruct()) {
      for (const glslang::TTypeLoc& member : *type.getStruct())
        declare_uniform(name + "." + member.type->getFieldName().c_str(), *member.type, builtin, words);
      return;
    }
    const auto existing = std::find_if(module_.uniforms.begin(), module_.uniforms.end(),
                                       [&](const UniformSlot& s) { return s.name == name; });
    uint32_t word;
    if (existing != module_.uniforms.end()) {
      word = existing->word;
    } else {
      UniformSlot slot{name,
                       basic_type(type),
                       slot_count(type),
                       uint32_t(module_.uniform_words.size()),
                       scalar_of(type) == Scalar::f,
                       builtin};
      module_.uniform_words.resize(module_.uniform_words.size() + size_t(slot.components), 0);
      if (slot.type == BasicType::sampler_2d || slot.type == BasicType::sampler_cube)
        module_.samplers.push_back({slot.word, slot.type == BasicType::sampler_cube});
      if (!builtin) module_.user_uniforms.push_back({name, slot.type, slot.components});
      module_.uniforms.push_back(slot);
      word = slot.word;
    }
    for (int k = 0; k < slot_count(type); ++k) words.push_back(word + uint32_t(k));
  }

  /// A uniform's registers: contiguous (so that gather can index them), bools turned into masks.
  Regs uniform_value(const std::string& name, const TType& type, bool builtin) {
    const auto cached = uniform_values_.find(name);
    if (cached != uniform_values_.end()) return cached->second;
    std::vector<uint32_t> words;
    declare_uniform(name, type, builtin, words);
    std::vector<Scalar> layout;
    scalar_layout(type, layout);
    const uint32_t first = fresh(int(words.size()));
    Regs out;
    for (size_t k = 0; k < words.size(); ++k) {
      uniform_[first + k] = true;
      stage_.uniforms.emplace_back(first + uint32_t(k), words[k]);
      out.push_back(layout[k] == Scalar::b ? emit(Op::ine, first + uint32_t(k), constant_int(0)) : first + uint32_t(k));
    }
    uniform_values_[name] = out;
    return out;
  }

  /// The sampler index of a sampler expression (a uniform, or an element of a uniform array with a constant index).
  uint16_t sampler_index(TIntermTyped* node) {
    std::string name;
    if (TIntermSymbol* symbol = node->getAsSymbolNode()) {
      name = symbol->getName().c_str();
    } else if (TIntermBinary* index = node->getAsBinaryNode();
               index && index->getOp() == glslang::EOpIndexDirect && index->getLeft()->getAsSymbolNode()) {
      name = std::string(index->getLeft()->getAsSymbolNode()->getName().c_str()) + "[" +
             std::to_string(index->getRight()->getAsConstantUnion()->getConstArray()[0].getIConst()) + "]";
      uniform_value(index->getLeft()->getAsSymbolNode()->getName().c_str(), index->getLeft()->getType(), false);
    } else {
      fail(node, "a sampler must be a uniform (or an element of a uniform array with a constant index)");
    }
    if (node->getAsSymbolNode()) uniform_value(name, node->getType(), false);
    const auto slot = std::find_if(module_.uniforms.begin(), module_.uniforms.end(),
                                   [&](const UniformSlot& s) { return s.name == name; });
    for (size_t k = 0; k < module_.samplers.size(); ++k)
      if (module_.samplers[k].word == slot->word) return uint16_t(k);
    fail(node, "unknown sampler " + name);
  }

  /// A vertex attribute's registers (declared on first use): `components` input slots.
  Regs attribute(const std::string& name, AttributeSlot::Source source, const TType& type) {
    const auto cached = inputs_.find(name);
    if (cached != inputs_.end()) return cached->second;
    uint32_t first_slot = 0;
    for (const AttributeSlot& a : module_.attributes) first_slot += uint32_t(a.components);
    const int components = slot_count(type);
    if (type.isArray() || type.isStruct() || scalar_of(type) != Scalar::f)
      throw CompileFailure(0, "attribute " + name + " must be a float, vector or matrix");
    module_.attributes.push_back({name, source, components, first_slot});
    Regs out;
    for (int k = 0; k < components; ++k) {
      out.push_back(fresh());
      stage_.inputs.emplace_back(out.back(), first_slot + uint32_t(k));
    }
    inputs_[name] = out;
    return out;
  }

  /// A fragment input's registers: a varying (linked by name after both stages are compiled) or gl_FragCoord /
  /// gl_FrontFacing.
  Regs fragment_input(const std::string& name, const TType& type, glslang::TBuiltInVariable builtin) {
    const auto cached = inputs_.find(name);
    if (cached != inputs_.end()) return cached->second;
    Regs out;
    if (builtin == glslang::EbvFragCoord || builtin == glslang::EbvFace) {
      const uint32_t slot = builtin == glslang::EbvFragCoord ? ir::kFragCoord : ir::kFrontFacing;
      for (int k = 0; k < slot_count(type); ++k) {
        out.push_back(fresh());
        stage_.inputs.emplace_back(out.back(), slot + uint32_t(k));
      }
    } else {
      if (scalar_of(type) != Scalar::f) throw CompileFailure(0, "varying " + name + " must be of float type");
      for (int k = 0; k < slot_count(type); ++k) out.push_back(fresh());
      varying_inputs[name] = out;
      std::vector<Scalar> layout;
      scalar_layout(type, layout);
      varying_layouts[name] = layout;
    }
    inputs_[name] = out;
    return out;
  }

  /// The name a varying links by: the fragment stage's gl_Color reads the vertex stage's gl_FrontColor.
  static std::string varying_name(const TIntermSymbol* symbol) {
    switch (symbol->getQualifier().builtIn) {
      case glslang::EbvColor:
      case glslang::EbvFrontColor:
        return "gl_Color";
      case glslang::EbvSecondaryColor:
      case glslang::EbvFrontSecondaryColor:
        return "gl_SecondaryColor";
      default:
        return symbol->getName().c_str();
    }
  }

  // ---- variables

  /// Loads a symbol's value.
  Regs symbol(TIntermSymbol* node) {
    const TType& type = node->getType();
    const glslang::TQualifier& q = node->getQualifier();
    if (node->getConstArray().size() > 0) {
      Regs out;
      const glslang::TConstUnionArray& array = node->getConstArray();
      for (int k = 0; k < array.size(); ++k) {
        const glslang::TConstUnion& u = array[k];
        out.push_back(u.getType() == glslang::EbtFloat || u.getType() == glslang::EbtDouble
                          ? constant(float(u.getDConst()))
                      : u.getType() == glslang::EbtBool ? constant_bool(u.getBConst())
                      : u.getType() == glslang::EbtUint ? constant_int(int32_t(u.getUConst()))
                                                        : constant_int(u.getIConst()));
      }
      return out;
    }
    const auto bound = bindings_.find(node->getId());
    if (bound != bindings_.end()) return bound->second;
    const std::string name = node->getName().c_str();
    if (q.storage == glslang::EvqUniform) return uniform_value(name, type, name.rfind("gl_", 0) == 0);
    if (!fragment_ && (q.storage == glslang::EvqVaryingIn || q.storage == glslang::EvqIn)) {
      AttributeSlot::Source source = AttributeSlot::Source::user;
      switch (q.builtIn) {
        case glslang::EbvVertex:
          source = AttributeSlot::Source::position;
          break;
        case glslang::EbvNormal:
          source = AttributeSlot::Source::normal;
          break;
        case glslang::EbvColor:
          source = AttributeSlot::Source::color;
          break;
        case glslang::EbvMultiTexCoord0:
          source = AttributeSlot::Source::tex_coord0;
          break;
        case glslang::EbvNone:
          break;
        default:
          fail(node, "the vertex input " + name + " is not supported");
      }
      return attribute(name, source, type);
    }
    if (fragment_ && (q.storage == glslang::EvqVaryingIn || q.storage == glslang::EvqIn ||
                      q.storage == glslang::EvqFragCoord || q.storage == glslang::EvqFace))
      return fragment_input(varying_name(node), type, q.builtIn);
    // A variable read before it is written: zero (GLSL leaves it undefined).
    Regs value = zeros(type);
    bindings_[node->getId()] = value;
    symbols_[node->getId()] = node;
    return value;
  }

  void bind(TIntermSymbol* node, const Regs& value) {
    bindings_[node->getId()] = value;
    symbols_[node->getId()] = node;
  }

  /// Where an l-value writes: the root variable and the register positions within it (or a dynamic index).
  struct Place {
    TIntermSymbol* root = nullptr;
    std::vector<int> positions;  // into the root's registers
    // One dynamic index: element k of an array at positions + k * stride is written where index == k.
    uint32_t index = kNoMask;
    int elements = 0, stride = 0;
  };

  Place place(TIntermTyped* node) {
    if (TIntermSymbol* s = node->getAsSymbolNode()) {
      Place p;
      p.root = s;
      const int n = int(symbol(s).size());
      for (int k = 0; k < n; ++k) p.positions.push_back(k);
      return p;
    }
    TIntermBinary* b = node->getAsBinaryNode();
    if (!b) fail(node, "not an assignable expression");
    Place p = place(b->getLeft());
    const TType& left = b->getLeft()->getType();
    switch (b->getOp()) {
      case glslang::EOpIndexDirect:
      case glslang::EOpIndexDirectStruct: {
        const int index = b->getRight()->getAsConstantUnion()->getConstArray()[0].getIConst();
        int offset, count;
        if (b->getOp() == glslang::EOpIndexDirectStruct) {
          offset = member_offset(left, index);
          count = slot_count(*(*left.getStruct())[size_t(index)].type);
        } else {
          count = slot_count(b->getType());
          offset = index * count;
        }
        p.positions = std::vector<int>(p.positions.begin() + offset, p.positions.begin() + offset + count);
        return p;
      }
      case glslang::EOpVectorSwizzle: {
        std::vector<int> picked;
        for (TIntermNode* c : b->getRight()->getAsAggregate()->getSequence())
          picked.push_back(p.positions[size_t(c->getAsConstantUnion()->getConstArray()[0].getIConst())]);
        p.positions = picked;
        return p;
      }
      case glslang::EOpIndexIndirect: {
        if (p.index != kNoMask) fail(node, "two dynamic indices in one assignment are not supported");
        p.index = value(b->getRight())[0];
        p.stride = slot_count(b->getType());
        p.elements = int(p.positions.size()) / p.stride;
        p.positions.resize(size_t(p.stride));
        return p;
      }
      default:
        fail(node, "not an assignable expression");
    }
  }

  void store(TIntermTyped* target, const Regs& v) {
    Place p = place(target);
    Regs root = symbol(p.root);
    if (p.index == kNoMask) {
      for (size_t k = 0; k < p.positions.size(); ++k) {
        uint32_t& r = root[size_t(p.positions[k])];
        r = masked(v[k], r);
      }
    } else {
      for (int e = 0; e < p.elements; ++e) {
        const uint32_t hit = band(mask_, emit(Op::ieq, p.index, constant_int(e)));
        for (size_t k = 0; k < p.positions.size(); ++k) {
          uint32_t& r = root[size_t(p.positions[k]) + size_t(e) * size_t(p.stride)];
          r = emit(Op::select, hit, v[k], r);
        }
      }
    }
    bind(p.root, root);
  }

  // ---- expressions

  Regs value(TIntermNode* node) {
    if (TIntermConstantUnion* c = node->getAsConstantUnion()) return constant_union(c);
    if (TIntermSymbol* s = node->getAsSymbolNode()) return symbol(s);
    if (TIntermBinary* b = node->getAsBinaryNode()) return binary(b);
    if (TIntermUnary* u = node->getAsUnaryNode()) return unary(u);
    if (TIntermAggregate* a = node->getAsAggregate()) return aggregate(a);
    if (TIntermSelection* s = node->getAsSelectionNode()) {
      if (s->getBasicType() == glslang::EbtVoid) {
        statement(s);
        return {};
      }
      const uint32_t c = value(s->getCondition())[0];
      const Regs t = value(s->getTrueBlock()), f = value(s->getFalseBlock());
      Regs out;
      for (size_t k = 0; k < t.size(); ++k) out.push_back(emit(Op::select, c, t[k], f[k]));
      return out;
    }
    fail(node, "unsupported expression");
  }

  /// Component k of v, or its only component for a scalar (GLSL's scalar-vector operators).
  static uint32_t at(const Regs& v, size_t k) { return v.size() == 1 ? v[0] : v[k]; }

  Regs componentwise(Op op, const Regs& a, const Regs& b) {
    Regs out;
    for (size_t k = 0; k < std::max(a.size(), b.size()); ++k) out.push_back(emit(op, at(a, k), at(b, k)));
    return out;
  }

  static Op arithmetic(glslang::TOperator op, Scalar s) {
    const bool f = s == Scalar::f;
    switch (op) {
      case glslang::EOpAdd:
      case glslang::EOpAddAssign:
        return f ? Op::fadd : Op::iadd;
      case glslang::EOpSub:
      case glslang::EOpSubAssign:
        return f ? Op::fsub : Op::isub;
      case glslang::EOpMul:
      case glslang::EOpMulAssign:
      case glslang::EOpVectorTimesScalar:
      case glslang::EOpVectorTimesScalarAssign:
      case glslang::EOpMatrixTimesScalar:
      case glslang::EOpMatrixTimesScalarAssign:
        return f ? Op::fmul : Op::imul;
      case glslang::EOpDiv:
      case glslang::EOpDivAssign:
        return f ? Op::fdiv : Op::idiv;
      case glslang::EOpMod:
      case glslang::EOpModAssign:
        return f ? Op::fmod : Op::imod;
      case glslang::EOpAnd:
      case glslang::EOpAndAssign:
        return Op::band;
      case glslang::EOpInclusiveOr:
      case glslang::EOpInclusiveOrAssign:
        return Op::bor;
      case glslang::EOpExclusiveOr:
      case glslang::EOpExclusiveOrAssign:
        return Op::bxor;
      case glslang::EOpLeftShift:
      case glslang::EOpLeftShiftAssign:
        return Op::ishl;
      case glslang::EOpRightShift:
      case glslang::EOpRightShiftAssign:
        return Op::ishr;
      default:
        return Op::jump;  // not arithmetic
    }
  }

  /// m (cols x rows, column-major) times column vector v.
  Regs matrix_times_vector(const Regs& m, int cols, int rows, const Regs& v) {
    Regs out;
    for (int r = 0; r < rows; ++r) {
      uint32_t sum = emit(Op::fmul, m[size_t(r)], v[0]);
      for (int c = 1; c < cols; ++c) sum = emit(Op::fadd, sum, emit(Op::fmul, m[element(c, rows, r)], v[size_t(c)]));
      out.push_back(sum);
    }
    return out;
  }

  /// Row vector v times m (cols x rows): one dot product per column.
  Regs vector_times_matrix(const Regs& v, const Regs& m, int cols, int rows) {
    Regs out;
    for (int c = 0; c < cols; ++c) {
      uint32_t sum = emit(Op::fmul, v[0], m[element(c, rows, 0)]);
      for (int r = 1; r < rows; ++r) sum = emit(Op::fadd, sum, emit(Op::fmul, v[size_t(r)], m[element(c, rows, r)]));
      out.push_back(sum);
    }
    return out;
  }

  Regs matrix_times_matrix(const Regs& a, int a_cols, int a_rows, const Regs& b, int b_cols) {
    Regs out;
    for (int c = 0; c < b_cols; ++c) {
      const Regs column(b.begin() + ptrdiff_t(c) * a_cols, b.begin() + ptrdiff_t(c + 1) * a_cols);
      const Regs product = matrix_times_vector(a, a_cols, a_rows, column);
      out.insert(out.end(), product.begin(), product.end());
    }
    return out;
  }

  Regs multiply(TIntermBinary* node, const Regs& a, const Regs& b) {
    const TType& lt = node->getLeft()->getType();
    const TType& rt = node->getRight()->getType();
    switch (node->getOp()) {
      case glslang::EOpMatrixTimesVector:
        return matrix_times_vector(a, lt.getMatrixCols(), lt.getMatrixRows(), b);
      case glslang::EOpVectorTimesMatrix:
      case glslang::EOpVectorTimesMatrixAssign:
        return vector_times_matrix(a, b, rt.getMatrixCols(), rt.getMatrixRows());
      case glslang::EOpMatrixTimesMatrix:
      case glslang::EOpMatrixTimesMatrixAssign:
        return matrix_times_matrix(a, lt.getMatrixCols(), lt.getMatrixRows(), b, rt.getMatrixCols());
      default:
        return componentwise(arithmetic(node->getOp(), scalar_of(node->getType())), a, b);
    }
  }

  uint32_t all_of(const Regs& v) {
    uint32_t out = v[0];
    for (size_t k = 1; k < v.size(); ++k) out = emit(Op::band, out, v[k]);
    return out;
  }
  uint32_t any_of(const Regs& v) {
    uint32_t out = v[0];
    for (size_t k = 1; k < v.size(); ++k) out = emit(Op::bor, out, v[k]);
    return out;
  }

  Regs compare(glslang::TOperator op, Scalar s, const Regs& a, const Regs& b) {
    const bool f = s == Scalar::f;
    Op o;
    switch (op) {
      case glslang::EOpLessThan:
        o = f ? Op::flt : Op::ilt;
        break;
      case glslang::EOpLessThanEqual:
        o = f ? Op::fle : Op::ile;
        break;
      case glslang::EOpGreaterThan:
        o = f ? Op::fgt : Op::igt;
        break;
      case glslang::EOpGreaterThanEqual:
        o = f ? Op::fge : Op::ige;
        break;
      case glslang::EOpEqual:
      case glslang::EOpVectorEqual:
        o = f ? Op::feq : s == Scalar::i ? Op::ieq : Op::bxor;
        break;
      default:
        o = f ? Op::fne : s == Scalar::i ? Op::ine : Op::bxor;
        break;
    }
    Regs out = componentwise(o, a, b);
    // Bools compare by xor: equal is its complement.
    if (s == Scalar::b && (op == glslang::EOpEqual || op == glslang::EOpVectorEqual))
      for (uint32_t& r : out) r = bnot(r);
    return out;
  }

  Regs binary(TIntermBinary* node) {
    const glslang::TOperator op = node->getOp();
    switch (op) {
      case glslang::EOpAssign: {
        Regs v = value(node->getRight());
        store(node->getLeft(), v);
        return v;
      }
      case glslang::EOpIndexDirect:
      case glslang::EOpIndexDirectStruct: {
        const Regs base = value(node->getLeft());
        const int index = node->getRight()->getAsConstantUnion()->getConstArray()[0].getIConst();
        const TType& left = node->getLeft()->getType();
        int offset, count;
        if (op == glslang::EOpIndexDirectStruct) {
          offset = member_offset(left, index);
          count = slot_count(*(*left.getStruct())[size_t(index)].type);
        } else {
          count = slot_count(node->getType());
          offset = index * count;
        }
        if (offset + count > int(base.size())) fail(node, "index out of range");
        return Regs(base.begin() + offset, base.begin() + offset + count);
      }
      case glslang::EOpIndexIndirect:
        return indirect(node);
      case glslang::EOpVectorSwizzle: {
        const Regs base = value(node->getLeft());
        Regs out;
        for (TIntermNode* c : node->getRight()->getAsAggregate()->getSequence())
          out.push_back(base[size_t(c->getAsConstantUnion()->getConstArray()[0].getIConst())]);
        return out;
      }
      case glslang::EOpComma:
        value(node->getLeft());
        return value(node->getRight());
      case glslang::EOpLogicalAnd:
        return {emit(Op::band, value(node->getLeft())[0], value(node->getRight())[0])};
      case glslang::EOpLogicalOr:
        return {emit(Op::bor, value(node->getLeft())[0], value(node->getRight())[0])};
      case glslang::EOpLogicalXor:
        return {emit(Op::bxor, value(node->getLeft())[0], value(node->getRight())[0])};
      case glslang::EOpLessThan:
      case glslang::EOpGreaterThan:
      case glslang::EOpLessThanEqual:
      case glslang::EOpGreaterThanEqual:
      case glslang::EOpVectorEqual:
      case glslang::EOpVectorNotEqual:
        return compare(op, scalar_of(node->getLeft()->getType()), value(node->getLeft()), value(node->getRight()));
      case glslang::EOpEqual:
      case glslang::EOpNotEqual: {
        const Regs c =
            compare(op, scalar_of(node->getLeft()->getType()), value(node->getLeft()), value(node->getRight()));
        return {op == glslang::EOpEqual ? all_of(c) : any_of(c)};
      }
      default:
        break;
    }
    const bool assign = op >= glslang::EOpAddAssign && op <= glslang::EOpRightShiftAssign;
    const Regs a = value(node->getLeft());
    const Regs b = value(node->getRight());
    Regs result;
    // (EOpMul on two matrices is matrixCompMult: componentwise, below.)
    if (op == glslang::EOpMatrixTimesVector || op == glslang::EOpVectorTimesMatrix ||
        op == glslang::EOpMatrixTimesMatrix || op == glslang::EOpVectorTimesMatrixAssign ||
        op == glslang::EOpMatrixTimesMatrixAssign) {
      result = multiply(node, a, b);
    } else {
      const Op o = arithmetic(op, scalar_of(node->getType()));
      if (o == Op::jump) fail(node, "this operator is not supported by Tessera's GLSL executor");
      result = componentwise(o, a, b);
    }
    if (assign) store(node->getLeft(), result);
    return result;
  }

  /// A dynamically indexed element: gather from a uniform's contiguous registers, else a chain of selects.
  Regs indirect(TIntermBinary* node) {
    const Regs base = value(node->getLeft());
    const uint32_t index = value(node->getRight())[0];
    const int count = slot_count(node->getType());
    const int elements = int(base.size()) / count;
    bool contiguous = true;
    for (size_t k = 1; k < base.size() && contiguous; ++k) contiguous = base[k] == base[0] + k;
    Regs out;
    for (int k = 0; k < count; ++k) {
      if (contiguous) {
        ir::Instr instr;
        instr.op = Op::gather;
        instr.a = base[size_t(k)];
        instr.b = index;
        instr.c = uint32_t(count);
        instr.unit = uint16_t(elements);
        instr.dst = fresh();
        stage_.code.push_back(instr);
        out.push_back(instr.dst);
      } else {
        uint32_t r = base[size_t(k)];
        for (int e = 1; e < elements; ++e)
          r = emit(Op::select, emit(Op::ieq, index, constant_int(e)), base[element(e, count, k)], r);
        out.push_back(r);
      }
    }
    return out;
  }

  Regs convert(const Regs& v, Scalar from, Scalar to) {
    if (from == to) return v;
    Regs out;
    for (uint32_t r : v) {
      if (to == Scalar::f)
        out.push_back(from == Scalar::i ? emit(Op::itof, r) : emit(Op::btof, r));
      else if (to == Scalar::i)
        out.push_back(from == Scalar::f ? emit(Op::ftoi, r) : emit(Op::btoi, r));
      else
        out.push_back(from == Scalar::f ? emit(Op::fne, r, constant(0.0f)) : emit(Op::ine, r, constant_int(0)));
    }
    return out;
  }

  Regs map1(Op op, const Regs& v) {
    Regs out;
    for (uint32_t r : v) out.push_back(emit(op, r));
    return out;
  }

  uint32_t dot(const Regs& a, const Regs& b) {
    uint32_t sum = emit(Op::fmul, a[0], b[0]);
    for (size_t k = 1; k < a.size(); ++k) sum = emit(Op::fadd, sum, emit(Op::fmul, a[k], b[k]));
    return sum;
  }
  Regs scale(const Regs& v, uint32_t s) {
    Regs out;
    for (uint32_t r : v) out.push_back(emit(Op::fmul, r, s));
    return out;
  }
  Regs normalize(const Regs& v) { return scale(v, emit(Op::frsqrt, dot(v, v))); }

  Regs unary(TIntermUnary* node) {
    const glslang::TOperator op = node->getOp();
    const TType& operand_type = node->getOperand()->getType();
    const Scalar s = scalar_of(operand_type);
    switch (op) {
      case glslang::EOpPreIncrement:
      case glslang::EOpPreDecrement:
      case glslang::EOpPostIncrement:
      case glslang::EOpPostDecrement: {
        const Regs old = value(node->getOperand());
        const bool inc = op == glslang::EOpPreIncrement || op == glslang::EOpPostIncrement;
        const Regs one{s == Scalar::f ? constant(1.0f) : constant_int(1)};
        const Regs updated =
            componentwise(s == Scalar::f ? (inc ? Op::fadd : Op::fsub) : (inc ? Op::iadd : Op::isub), old, one);
        store(node->getOperand(), updated);
        return op == glslang::EOpPreIncrement || op == glslang::EOpPreDecrement ? updated : old;
      }
      default:
        break;
    }
    Regs v = value(node->getOperand());
    switch (op) {
      case glslang::EOpNegative:
        return map1(s == Scalar::f ? Op::fneg : Op::ineg, v);
      case glslang::EOpLogicalNot:
      case glslang::EOpVectorLogicalNot:
      case glslang::EOpBitwiseNot:
        return map1(Op::bnot, v);
      case glslang::EOpCopyObject:
        return v;
      case glslang::EOpConvIntToFloat:
      case glslang::EOpConvUintToFloat:
        return convert(v, Scalar::i, Scalar::f);
      case glslang::EOpConvBoolToFloat:
        return convert(v, Scalar::b, Scalar::f);
      case glslang::EOpConvFloatToInt:
      case glslang::EOpConvFloatToUint:
        return convert(v, Scalar::f, Scalar::i);
      case glslang::EOpConvBoolToInt:
      case glslang::EOpConvBoolToUint:
        return convert(v, Scalar::b, Scalar::i);
      case glslang::EOpConvFloatToBool:
        return convert(v, Scalar::f, Scalar::b);
      case glslang::EOpConvIntToBool:
      case glslang::EOpConvUintToBool:
        return convert(v, Scalar::i, Scalar::b);
      case glslang::EOpConvIntToUint:
      case glslang::EOpConvUintToInt:
        return v;
      case glslang::EOpRadians:
        return scale(v, constant(float(3.14159265358979323846 / 180.0)));
      case glslang::EOpDegrees:
        return scale(v, constant(float(180.0 / 3.14159265358979323846)));
      case glslang::EOpSin:
        return map1(Op::fsin, v);
      case glslang::EOpCos:
        return map1(Op::fcos, v);
      case glslang::EOpTan:
        return map1(Op::ftan, v);
      case glslang::EOpAsin:
        return map1(Op::fasin, v);
      case glslang::EOpAcos:
        return map1(Op::facos, v);
      case glslang::EOpAtan:
        return map1(Op::fatan, v);
      case glslang::EOpSinh:
        return map1(Op::fsinh, v);
      case glslang::EOpCosh:
        return map1(Op::fcosh, v);
      case glslang::EOpTanh:
        return map1(Op::ftanh, v);
      case glslang::EOpExp:
        return map1(Op::fexp, v);
      case glslang::EOpLog:
        return map1(Op::flog, v);
      case glslang::EOpExp2:
        return map1(Op::fexp2, v);
      case glslang::EOpLog2:
        return map1(Op::flog2, v);
      case glslang::EOpSqrt:
        return map1(Op::fsqrt, v);
      case glslang::EOpInverseSqrt:
        return map1(Op::frsqrt, v);
      case glslang::EOpAbs:
        return map1(s == Scalar::f ? Op::fabs : Op::iabs, v);
      case glslang::EOpSign:
        if (s != Scalar::f) fail(node, "sign() of an int is not supported");
        return map1(Op::fsign, v);
      case glslang::EOpFloor:
        return map1(Op::ffloor, v);
      case glslang::EOpTrunc:
        return map1(Op::ftrunc, v);
      case glslang::EOpRound:
      case glslang::EOpRoundEven:
        return map1(Op::fround, v);
      case glslang::EOpCeil:
        return map1(Op::fceil, v);
      case glslang::EOpFract:
        return map1(Op::ffract, v);
      case glslang::EOpLength:
        return {emit(Op::fsqrt, dot(v, v))};
      case glslang::EOpNormalize:
        return normalize(v);
      case glslang::EOpDPdx:
      case glslang::EOpDPdxFine:
      case glslang::EOpDPdxCoarse:
        return map1(Op::dfdx, v);
      case glslang::EOpDPdy:
      case glslang::EOpDPdyFine:
      case glslang::EOpDPdyCoarse:
        return map1(Op::dfdy, v);
      case glslang::EOpFwidth:
      case glslang::EOpFwidthFine:
      case glslang::EOpFwidthCoarse: {
        Regs out;
        for (uint32_t r : v)
          out.push_back(emit(Op::fadd, emit(Op::fabs, emit(Op::dfdx, r)), emit(Op::fabs, emit(Op::dfdy, r))));
        return out;
      }
      case glslang::EOpAny:
        return {any_of(v)};
      case glslang::EOpAll:
        return {all_of(v)};
      case glslang::EOpIsNan: {
        Regs out;
        for (uint32_t r : v) out.push_back(emit(Op::fne, r, r));
        return out;
      }
      case glslang::EOpTranspose: {
        const int cols = operand_type.getMatrixCols(), rows = operand_type.getMatrixRows();
        Regs out;
        for (int r = 0; r < rows; ++r)
          for (int c = 0; c < cols; ++c) out.push_back(v[element(c, rows, r)]);
        return out;
      }
      default:
        fail(node, "this built-in function or operator is not supported by Tessera's GLSL executor");
    }
  }

  /// A constructor: the arguments' components in order, converted, with GLSL's scalar and matrix rules.
  Regs construct(TIntermAggregate* node) {
    const TType& type = node->getType();
    const Scalar to = scalar_of(type);
    std::vector<Regs> args;
    std::vector<const TType*> types;
    for (TIntermNode* a : node->getSequence()) {
      TIntermTyped* t = a->getAsTyped();
      args.push_back(convert(value(t), scalar_of(t->getType()), to));
      types.push_back(&t->getType());
    }
    const int n = slot_count(type);
    if (node->getOp() == glslang::EOpConstructStruct || type.isArray()) {
      Regs out;
      for (const Regs& a : args) out.insert(out.end(), a.begin(), a.end());
      return out;
    }
    if (type.isMatrix()) {
      const int cols = type.getMatrixCols(), rows = type.getMatrixRows();
      const uint32_t zero = constant(0.0f), one = constant(1.0f);
      Regs out(size_t(n), zero);
      if (args.size() == 1 && args[0].size() == 1) {  // a scalar: the diagonal
        for (int k = 0; k < std::min(cols, rows); ++k) out[element(k, rows, k)] = args[0][0];
        return out;
      }
      if (args.size() == 1 && types[0]->isMatrix()) {  // a matrix: its upper-left part, identity elsewhere
        const int src_cols = types[0]->getMatrixCols(), src_rows = types[0]->getMatrixRows();
        for (int c = 0; c < cols; ++c)
          for (int r = 0; r < rows; ++r)
            out[element(c, rows, r)] =
                c < src_cols && r < src_rows ? args[0][element(c, src_rows, r)] : (c == r ? one : zero);
        return out;
      }
    }
    Regs flat;
    for (const Regs& a : args) flat.insert(flat.end(), a.begin(), a.end());
    if (flat.size() == 1 && n > 1) return Regs(size_t(n), flat[0]);
    flat.resize(size_t(n));
    return flat;
  }

  Regs texture(TIntermAggregate* node) {
    const glslang::TIntermSequence& args = node->getSequence();
    const uint16_t unit = sampler_index(args[0]->getAsTyped());
    const bool cube = args[0]->getAsTyped()->getType().getSampler().dim == glslang::EsdCube;
    Regs coord = value(args[1]);
    const glslang::TOperator op = node->getOp();
    if (op == glslang::EOpTextureProj) {  // divide by the last coordinate
      const uint32_t q = emit(Op::fdiv, constant(1.0f), coord.back());
      coord = {emit(Op::fmul, coord[0], q), emit(Op::fmul, coord[1], q)};
    }
    Op o;
    uint32_t extra = 0;
    if (op == glslang::EOpTextureLod) {
      o = cube ? Op::texcube_lod : Op::tex2d_lod;
      extra = value(args[2])[0];
    } else if ((op == glslang::EOpTexture || op == glslang::EOpTextureProj) && args.size() > 2) {
      o = cube ? Op::texcube_bias : Op::tex2d_bias;
      extra = value(args[2])[0];
    } else if (op == glslang::EOpTexture || op == glslang::EOpTextureProj) {
      o = cube ? Op::texcube : Op::tex2d;
    } else {
      fail(node, "this texture function is not supported by Tessera's GLSL executor");
    }
    if (!cube && node->getType().getVectorSize() != 4) fail(node, "shadow samplers are not supported");
    ir::Instr instr;
    instr.op = o;
    instr.unit = unit;
    instr.a = coord[0];
    instr.b = coord[1];
    instr.c = cube ? coord[2] : 0;
    instr.d = extra;
    instr.dst = fresh(4);
    stage_.code.push_back(instr);
    return {instr.dst, instr.dst + 1, instr.dst + 2, instr.dst + 3};
  }

  Regs aggregate(TIntermAggregate* node) {
    const glslang::TOperator op = node->getOp();
    if (op == glslang::EOpSequence) {
      for (TIntermNode* s : node->getSequence()) statement(s);
      return {};
    }
    if (op == glslang::EOpFunctionCall) {
      const auto f = functions_.find(node->getName().c_str());
      if (f == functions_.end()) fail(node, std::string("no definition of ") + node->getName().c_str());
      return call_function(f->second, node->getSequence(), node);
    }
    if (op > glslang::EOpConstructGuardStart && op < glslang::EOpConstructGuardEnd) return construct(node);
    if (node->isTexture()) return texture(node);
    if (op == glslang::EOpFtransform) {
      TType mat4(glslang::EbtFloat, glslang::EvqUniform, 0, 4, 4);  // a matrix has vector size 0
      TType vec4(glslang::EbtFloat, glslang::EvqVaryingIn, 4);
      const Regs mvp = uniform_value("gl_ModelViewProjectionMatrix", mat4, true);
      const Regs vertex = attribute("gl_Vertex", AttributeSlot::Source::position, vec4);
      return matrix_times_vector(mvp, 4, 4, vertex);
    }
    std::vector<Regs> a;
    std::vector<TIntermTyped*> typed;
    for (TIntermNode* n : node->getSequence()) {
      typed.push_back(n->getAsTyped());
      a.push_back(value(n));
    }
    const Scalar s = typed.empty() ? Scalar::f : scalar_of(typed[0]->getType());
    const size_t width = slot_count(node->getType());
    const auto per = [&](auto&& f) {
      Regs out;
      for (size_t k = 0; k < width; ++k) out.push_back(f(k));
      return out;
    };
    switch (op) {
      case glslang::EOpMin:
        return per([&](size_t k) { return emit(s == Scalar::f ? Op::fmin : Op::imin, at(a[0], k), at(a[1], k)); });
      case glslang::EOpMax:
        return per([&](size_t k) { return emit(s == Scalar::f ? Op::fmax : Op::imax, at(a[0], k), at(a[1], k)); });
      case glslang::EOpClamp:
        if (s != Scalar::f)
          return per([&](size_t k) { return emit(Op::imin, emit(Op::imax, at(a[0], k), at(a[1], k)), at(a[2], k)); });
        return per([&](size_t k) { return emit(Op::fclamp, at(a[0], k), at(a[1], k), at(a[2], k)); });
      case glslang::EOpMix:
        if (scalar_of(typed[2]->getType()) == Scalar::b)
          return per([&](size_t k) { return emit(Op::select, at(a[2], k), at(a[1], k), at(a[0], k)); });
        return per([&](size_t k) { return emit(Op::fmix, at(a[0], k), at(a[1], k), at(a[2], k)); });
      case glslang::EOpStep:
        return per([&](size_t k) { return emit(Op::fstep, at(a[0], k), at(a[1], k)); });
      case glslang::EOpSmoothStep:
        return per([&](size_t k) { return emit(Op::fsmoothstep, at(a[0], k), at(a[1], k), at(a[2], k)); });
      case glslang::EOpPow:
        return per([&](size_t k) { return emit(Op::fpow, at(a[0], k), at(a[1], k)); });
      case glslang::EOpAtan:
        return per([&](size_t k) { return emit(Op::fatan2, at(a[0], k), at(a[1], k)); });
      case glslang::EOpMod:
        if (s != Scalar::f) return per([&](size_t k) { return emit(Op::imod, at(a[0], k), at(a[1], k)); });
        return per([&](size_t k) { return emit(Op::fmod, at(a[0], k), at(a[1], k)); });
      case glslang::EOpDot:
        return {dot(a[0], a[1])};
      case glslang::EOpDistance: {
        const Regs d = componentwise(Op::fsub, a[0], a[1]);
        return {emit(Op::fsqrt, dot(d, d))};
      }
      case glslang::EOpCross: {
        const Regs& x = a[0];
        const Regs& y = a[1];
        const auto term = [&](size_t i, size_t j) {
          return emit(Op::fsub, emit(Op::fmul, x[i], y[j]), emit(Op::fmul, x[j], y[i]));
        };
        return {term(1, 2), term(2, 0), term(0, 1)};
      }
      case glslang::EOpReflect: {  // I - 2 dot(N, I) N
        const uint32_t d2 = emit(Op::fmul, constant(2.0f), dot(a[1], a[0]));
        return per([&](size_t k) { return emit(Op::fsub, a[0][k], emit(Op::fmul, d2, a[1][k])); });
      }
      case glslang::EOpRefract: {
        // k = 1 - eta^2 (1 - dot(N, I)^2); k < 0: 0, else eta I - (eta dot(N, I) + sqrt(k)) N
        const uint32_t eta = a[2][0];
        const uint32_t ni = dot(a[1], a[0]);
        const uint32_t one = constant(1.0f);
        const uint32_t k =
            emit(Op::fsub, one, emit(Op::fmul, emit(Op::fmul, eta, eta), emit(Op::fsub, one, emit(Op::fmul, ni, ni))));
        const uint32_t total = emit(Op::flt, k, constant(0.0f));
        const uint32_t factor =
            emit(Op::fadd, emit(Op::fmul, eta, ni), emit(Op::fsqrt, emit(Op::fmax, k, constant(0.0f))));
        return per([&](size_t c) {
          const uint32_t r = emit(Op::fsub, emit(Op::fmul, eta, a[0][c]), emit(Op::fmul, factor, a[1][c]));
          return emit(Op::select, total, constant(0.0f), r);
        });
      }
      case glslang::EOpFaceForward: {  // dot(Nref, I) < 0 ? N : -N
        const uint32_t front = emit(Op::flt, dot(a[2], a[1]), constant(0.0f));
        return per([&](size_t k) { return emit(Op::select, front, a[0][k], emit(Op::fneg, a[0][k])); });
      }
      case glslang::EOpLessThan:
      case glslang::EOpGreaterThan:
      case glslang::EOpLessThanEqual:
      case glslang::EOpGreaterThanEqual:
      case glslang::EOpVectorEqual:
      case glslang::EOpVectorNotEqual:
        return compare(op, s, a[0], a[1]);
      case glslang::EOpOuterProduct: {
        Regs out;
        for (uint32_t c : a[1])
          for (uint32_t r : a[0]) out.push_back(emit(Op::fmul, r, c));
        return out;
      }
      default:
        fail(node, "this built-in function is not supported by Tessera's GLSL executor");
    }
  }

  // ---- statements and control flow

  void statement(TIntermNode* node) {
    if (!node) return;
    if (TIntermLoop* loop = node->getAsLoopNode()) return compile_loop(loop);
    if (TIntermBranch* branch = node->getAsBranchNode()) return compile_branch(branch);
    if (TIntermSelection* s = node->getAsSelectionNode(); s && s->getBasicType() == glslang::EbtVoid)
      return compile_if(s);
    if (node->getAsSwitchNode()) fail(node, "switch is not supported by Tessera's GLSL executor yet");
    value(node);
  }

  /// The mask after an escape (break, continue, return, discard) somewhere inside a statement that began under
  /// `before`: the lanes that are still running.
  void refresh_mask(uint32_t before) {
    uint32_t m = before;
    if (!loops_.empty()) m = band(m, bindings_lm());
    if (returned_ != kNoMask) m = band(m, bnot(returned_));
    if (kept_ != kNoMask) m = band(m, kept_);
    mask_ = m;
  }

  void compile_if(TIntermSelection* node) {
    const uint32_t c = value(node->getCondition())[0];
    const uint32_t before = mask_;
    const int escapes = escapes_;
    mask_ = band(before, c);
    statement(node->getTrueBlock());
    if (node->getFalseBlock()) {
      // The else branch runs where the condition is false, minus lanes the then branch took out of the running.
      mask_ = band(before, bnot(c));
      if (escapes_ != escapes) {
        const uint32_t saved = mask_;
        refresh_mask(saved);
      }
      statement(node->getFalseBlock());
    }
    mask_ = before;
    if (escapes_ != escapes) refresh_mask(before);
  }

  struct Loop {
    long long lm_key;              // the loop mask's pseudo-variable
    uint32_t continued = kNoMask;  // lanes that took `continue` this iteration
  };

  uint32_t bindings_lm() { return bindings_[loops_.back().lm_key][0]; }

  void compile_loop(TIntermLoop* node) {
    const uint32_t before = mask_;
    const long long lm_key = -2 - (long long)(loops_.size());
    bindings_[lm_key] = {before == kNoMask ? constant_bool(true) : before};
    loops_.push_back({lm_key});
    // Every variable gets a loop register (its value at the top of an iteration).
    std::map<long long, Regs> carried;
    for (auto& [id, regs] : bindings_) {
      Regs fixed;
      for (uint32_t r : regs) {
        const uint32_t f = fresh();
        move_into(f, r);
        fixed.push_back(f);
      }
      carried[id] = fixed;
      regs = fixed;
    }
    const uint32_t kept_before = kept_;
    if (kept_ != kNoMask) {
      const uint32_t f = fresh();
      move_into(f, kept_);
      kept_ = f;
    }
    const uint32_t kept_fixed = kept_;
    const int top = int(stage_.code.size());
    std::vector<int> exits;
    if (node->testFirst() && node->getTest()) {
      mask_ = bindings_lm();
      const uint32_t c = value(node->getTest())[0];
      bindings_[lm_key] = {band(bindings_lm(), c)};
      exits.push_back(jump(Op::jump_if_none, bindings_lm()));
    }
    mask_ = bindings_lm();
    ++escapes_;  // the body's masks must include the loop mask
    const int escapes = escapes_;
    statement(node->getBody());
    (void)escapes;
    if (loops_.back().continued != kNoMask) {
      bindings_[lm_key] = {emit(Op::bor, bindings_lm(), loops_.back().continued)};
      loops_.back().continued = kNoMask;
    }
    mask_ = bindings_lm();
    if (kept_ != kNoMask) mask_ = band(mask_, kept_);
    if (node->getTerminal()) value(node->getTerminal());
    if (!node->testFirst() && node->getTest()) {
      const uint32_t c = value(node->getTest())[0];
      bindings_[lm_key] = {band(bindings_lm(), c)};
    }
    // Lanes that discarded or returned stop looping.
    uint32_t running = bindings_lm();
    if (kept_ != kNoMask) running = band(running, kept_);
    if (returned_ != kNoMask) running = band(running, bnot(returned_));
    bindings_[lm_key] = {running};
    for (auto& [id, regs] : bindings_) {
      const auto fixed = carried.find(id);
      if (fixed == carried.end()) continue;  // declared inside the loop
      for (size_t k = 0; k < regs.size(); ++k) move_into(fixed->second[k], regs[k]);
      regs = fixed->second;
    }
    if (kept_fixed != kNoMask) move_into(kept_fixed, kept_), kept_ = kept_fixed;
    jump(Op::jump_if_any, carried[lm_key][0], top);
    const int end = int(stage_.code.size());
    for (int e : exits) stage_.code[size_t(e)].target = end;
    // Variables declared inside the loop go out of scope; the others keep their loop registers.
    for (auto it = bindings_.begin(); it != bindings_.end();)
      it = carried.count(it->first) ? std::next(it) : bindings_.erase(it);
    bindings_.erase(lm_key);
    loops_.pop_back();
    (void)kept_before;
    mask_ = before;
    refresh_mask(before);
  }

  void compile_branch(TIntermBranch* node) {
    const uint32_t m = mask_ == kNoMask ? constant_bool(true) : mask_;
    switch (node->getFlowOp()) {
      case glslang::EOpKill:
      case glslang::EOpTerminateInvocation:
      case glslang::EOpDemote:
        if (!fragment_) fail(node, "discard outside a fragment shader");
        stage_.discards = true;
        kept_ = band(kept_ == kNoMask ? kept_input_reg() : kept_, bnot(m));
        break;
      case glslang::EOpBreak:
        if (loops_.empty()) fail(node, "break outside a loop");
        bindings_[loops_.back().lm_key] = {band(bindings_lm(), bnot(m))};
        break;
      case glslang::EOpContinue:
        if (loops_.empty()) fail(node, "continue outside a loop");
        loops_.back().continued = loops_.back().continued == kNoMask ? m : emit(Op::bor, loops_.back().continued, m);
        bindings_[loops_.back().lm_key] = {band(bindings_lm(), bnot(m))};
        break;
      case glslang::EOpReturn:
        if (node->getExpression()) {
          const Regs v = value(node->getExpression());
          if (return_value_.empty())
            return_value_ = v;
          else
            for (size_t k = 0; k < v.size(); ++k) return_value_[k] = masked(v[k], return_value_[k]);
        }
        returned_ = returned_ == kNoMask ? m : emit(Op::bor, returned_, m);
        break;
      default:
        fail(node, "unsupported statement");
    }
    ++escapes_;
    mask_ = constant_bool(false);  // the rest of this block runs for no lane
  }

  uint32_t kept_input_reg() {
    if (stage_.kept == 0) {
      stage_.kept = fresh();
    }
    return stage_.kept;
  }

  /// Inlines a user function (main included): parameters bound to the arguments, out parameters written back.
  Regs call_function(TIntermAggregate* function, const glslang::TIntermSequence& args, TIntermNode* call) {
    if (++depth_ > 64) fail(call, "function calls nest too deeply (recursion?)");
    TIntermAggregate* parameters = function->getSequence()[0]->getAsAggregate();
    std::vector<TIntermSymbol*> params;
    for (TIntermNode* p : parameters->getSequence()) params.push_back(p->getAsSymbolNode());
    std::vector<Regs> arg_values;
    for (size_t k = 0; k < args.size(); ++k) {
      const glslang::TStorageQualifier q = params[k]->getQualifier().storage;
      arg_values.push_back(q == glslang::EvqOut ? zeros(params[k]->getType()) : value(args[k]));
    }
    const uint32_t saved_returned = returned_;
    Regs saved_return = std::move(return_value_);
    const uint32_t saved_mask = mask_;
    returned_ = kNoMask;
    return_value_.clear();
    for (size_t k = 0; k < params.size(); ++k) bind(params[k], arg_values[k]);
    if (function->getSequence().size() > 1) statement(function->getSequence()[1]);
    Regs result = return_value_;
    if (result.empty() && function->getBasicType() != glslang::EbtVoid) result = zeros(function->getType());
    returned_ = saved_returned;
    return_value_ = std::move(saved_return);
    mask_ = saved_mask;
    for (size_t k = 0; k < args.size(); ++k) {
      const glslang::TStorageQualifier q = params[k]->getQualifier().storage;
      if (q == glslang::EvqOut || q == glslang::EvqInOut) store(args[k]->getAsTyped(), bindings_[params[k]->getId()]);
    }
    --depth_;
    return result;
  }

  /// Records the outputs: the final registers of the output variables.
  void finish() {
    for (const auto& [id, regs] : bindings_) {
      const auto s = symbols_.find(id);
      if (s == symbols_.end()) continue;
      const glslang::TQualifier& q = s->second->getQualifier();
      const bool output = q.storage == glslang::EvqVaryingOut || q.storage == glslang::EvqOut ||
                          q.storage == glslang::EvqPosition || q.storage == glslang::EvqFragColor;
      const TType& type = s->second->getType();
      if (output && type.getBasicType() == glslang::EbtBlock) {
        // An output block (GLSL 1.50 on: gl_PerVertex's gl_Position): each member links by its own name.
        int offset = 0;
        for (const glslang::TTypeLoc& member : *type.getStruct()) {
          const int count = slot_count(*member.type);
          const std::string field = member.type->getFieldName().c_str();
          outputs[member.type->getQualifier().builtIn == glslang::EbvPosition ? "gl_Position" : field] =
              Regs(regs.begin() + offset, regs.begin() + offset + count);
          offset += count;
        }
        continue;
      }
      if (output && !(q.storage == glslang::EvqOut && !s->second->getType().getQualifier().isPipeOutput())) {
        std::string name = varying_name(s->second);
        if (q.builtIn == glslang::EbvPosition) name = "gl_Position";
        if (q.builtIn == glslang::EbvFragColor || q.builtIn == glslang::EbvFragData) name = "gl_FragColor";
        if (fragment_ && q.builtIn == glslang::EbvNone && q.storage != glslang::EvqFragColor) name = "gl_FragColor";
        outputs[name] = regs;
      }
    }
    if (kept_ != kNoMask) move_into(kept_input_reg(), kept_);
  }

  ProgramModule& module_;
  ir::Stage& stage_;
  bool fragment_;
  std::vector<bool> uniform_;  // per register: the same in every lane (constants, uniforms, and what follows)
  std::map<uint32_t, uint32_t> constants_;
  std::map<std::string, Regs> uniform_values_, inputs_;
  std::map<long long, Regs> bindings_;
  std::map<long long, TIntermSymbol*> symbols_;
  std::map<std::string, TIntermAggregate*> functions_;
  uint32_t mask_ = kNoMask;
  uint32_t returned_ = kNoMask;
  uint32_t kept_ = kNoMask;
  Regs return_value_;
  std::vector<Loop> loops_;
  int escapes_ = 0;
  int depth_ = 0;
};

std::once_flag glslang_ready;

/// glslang's messages with Tessera's source names: "ERROR: 0:12: ..." becomes "a.frag:12: ...".
std::string format_log(const std::string& log, const std::string& name) {
  std::istringstream in(log);
  std::string line, out;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    for (const char* prefix : {"ERROR: ", "WARNING: "}) {
      if (line.rfind(prefix, 0) == 0) line = line.substr(std::strlen(prefix));
    }
    if (line.rfind("0:", 0) == 0) line.replace(0, 1, name);  // "0:12: ..." -> "a.frag:12: ..."
    if (line.find("compilation terminated") != std::string::npos ||
        line.find("compilation errors") != std::string::npos)
      continue;
    out += line + "\n";
  }
  if (!out.empty() && out.back() == '\n') out.pop_back();
  return out;
}

}  // namespace

std::unique_ptr<ProgramModule> compile_module(const ShaderSource& vertex, const ShaderSource& fragment) {
  std::call_once(glslang_ready, [] { glslang::InitializeProcess(); });
  const EShMessages messages = EShMsgDefault;
  glslang::TShader vs(EShLangVertex), fs(EShLangFragment);
  const ShaderSource* sources[2] = {&vertex, &fragment};
  glslang::TShader* shaders[2] = {&vs, &fs};
  for (int k = 0; k < 2; ++k) {
    const char* text = sources[k]->text.c_str();
    shaders[k]->setStrings(&text, 1);
    if (!shaders[k]->parse(GetDefaultResources(), 110, false, messages))
      throw CompileError(format_log(shaders[k]->getInfoLog(), sources[k]->name));
  }
  glslang::TProgram program;
  program.addShader(&vs);
  program.addShader(&fs);
  if (!program.link(messages))
    throw CompileError("linking " + vertex.name + " and " + fragment.name + ": " +
                       format_log(program.getInfoLog(), "program"));

  auto module = std::make_unique<ProgramModule>();
  StageCompiler vc(*module, module->vertex, false), fc(*module, module->fragment, true);
  const auto run = [&](StageCompiler& c, glslang::TShader& shader, const ShaderSource& source) {
    try {
      c.compile(program.getIntermediate(shader.getStage())->getTreeRoot());
    } catch (const CompileFailure& e) {
      throw CompileError(source.name + ":" + std::to_string(e.line) + ": " + e.message);
    }
  };
  run(vc, vs, vertex);
  run(fc, fs, fragment);

  // Link: gl_Position, then each varying the fragment stage reads, in float slots.
  const auto position = vc.outputs.find("gl_Position");
  if (position == vc.outputs.end()) throw CompileError(vertex.name + ": the vertex shader does not write gl_Position");
  for (uint32_t k = 0; k < 4; ++k) module->vertex.outputs.emplace_back(position->second[k], k);
  for (const auto& [name, regs] : fc.varying_inputs) {
    const auto written = vc.outputs.find(name);
    for (size_t k = 0; k < regs.size(); ++k) {
      if (written == vc.outputs.end() || k >= written->second.size()) {
        // Not written by the vertex stage: GLSL leaves it undefined; it reads 0.
        module->fragment.constants.emplace_back(regs[k], 0u);
        continue;
      }
      const auto slot = uint32_t(module->varying_count++);
      module->vertex.outputs.emplace_back(written->second[k], 4 + slot);
      module->fragment.inputs.emplace_back(regs[k], slot);
    }
  }
  if (module->varying_count > raster3d::FragmentBatch::kMaxVaryings)
    throw CompileError(fragment.name + ": the shaders pass " + std::to_string(module->varying_count) +
                       " floats of varyings; Tessera's limit is " +
                       std::to_string(raster3d::FragmentBatch::kMaxVaryings));
  const auto color = fc.outputs.find("gl_FragColor");
  if (color != fc.outputs.end())
    for (uint32_t k = 0; k < 4 && k < color->second.size(); ++k)
      module->fragment.outputs.emplace_back(color->second[k], k);
  return module;
}

}  // namespace tessera::glsl
