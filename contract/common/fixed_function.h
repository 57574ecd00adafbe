// The fixed-function state codes of fixed_function.def as typed enums, and
// the conversions every user of them shares: hardware code <-> enum (a field
// is cut to its width, as a register of that width would), enum <-> GL enum
// value, and the GL rules on which blend factors each side accepts. The value
// of an enumerator is its hardware code; a value without an entry (an unknown
// code) is legal and does what the table says. Plain C++, no SystemC, no GL
// headers: the GL front end passes its GLenum values as uint32_t.
#pragma once

#include <cstdint>
#include <optional>

namespace tessera {

enum class CompareFunc : uint8_t {
#define TESSERA_COMPARE_FUNC(name, code, gl_enum, description) name = (code),
#include "common/fixed_function.def"
};

enum class StencilOp : uint8_t {
#define TESSERA_STENCIL_OP(name, code, gl_enum, description) name = (code),
#include "common/fixed_function.def"
};

enum class BlendFactor : uint8_t {
#define TESSERA_BLEND_FACTOR(name, code, gl_enum, source, destination, description) name = (code),
#include "common/fixed_function.def"
};

enum class LogicOp : uint8_t {
#define TESSERA_LOGIC_OP(name, code, gl_enum, description) name = (code),
#include "common/fixed_function.def"
};

enum class TexEnv : uint8_t {
#define TESSERA_TEX_ENV(name, code, gl_enum, description) name = (code),
#include "common/fixed_function.def"
};

enum class TexBaseFormat : uint8_t {
#define TESSERA_TEX_BASE_FORMAT(name, code, gl_enum, description) name = (code),
#include "common/fixed_function.def"
};

enum class CombineFunc : uint8_t {
#define TESSERA_COMBINE_FUNC(name, code, gl_enum, description) name = (code),
#include "common/fixed_function.def"
};

enum class CombineSource : uint8_t {
#define TESSERA_COMBINE_SOURCE(name, code, gl_enum, description) name = (code),
#include "common/fixed_function.def"
};

enum class CombineOperand : uint8_t {
#define TESSERA_COMBINE_OPERAND(name, code, gl_enum, description) name = (code),
#include "common/fixed_function.def"
};

enum class TexFilter : uint8_t {
#define TESSERA_TEX_FILTER(name, code, gl_enum, description) name = (code),
#include "common/fixed_function.def"
};

enum class TexWrap : uint8_t {
#define TESSERA_TEX_WRAP(name, code, gl_enum, description) name = (code),
#include "common/fixed_function.def"
};

enum class TexMipmap : uint8_t {
#define TESSERA_TEX_MIPMAP(name, code, gl_enum, description) name = (code),
#include "common/fixed_function.def"
};

enum class FogMode : uint8_t {
#define TESSERA_FOG_MODE(name, code, gl_enum, description) name = (code),
#include "common/fixed_function.def"
};

template <typename E>
struct FixedFunctionEntry {
  E value;
  const char* name;  // the enumerator's
  uint32_t gl_enum;
  const char* description;
};

// What the table says about the whole enumeration: its name (the package's
// <NAME>_e), the width of its hardware field and what an unknown code does.
template <typename E>
struct FixedFunctionField;

#define TESSERA_FIXED_FUNCTION(type, sv_name, bits, unknown) \
  template <>                                                \
  struct FixedFunctionField<type> {                          \
    static constexpr const char* NAME = #sv_name;            \
    static constexpr unsigned BITS = (bits);                 \
    static constexpr const char* UNKNOWN = unknown;          \
  };
#include "common/fixed_function.def"

// The field and its entries, in the order of the table.
template <typename E>
struct FixedFunction;

template <>
struct FixedFunction<CompareFunc> : FixedFunctionField<CompareFunc> {
  static constexpr FixedFunctionEntry<CompareFunc> ENTRIES[] = {
#define TESSERA_COMPARE_FUNC(name, code, gl_enum, description) {CompareFunc::name, #name, gl_enum, description},
#include "common/fixed_function.def"
  };
};

template <>
struct FixedFunction<StencilOp> : FixedFunctionField<StencilOp> {
  static constexpr FixedFunctionEntry<StencilOp> ENTRIES[] = {
#define TESSERA_STENCIL_OP(name, code, gl_enum, description) {StencilOp::name, #name, gl_enum, description},
#include "common/fixed_function.def"
  };
};

template <>
struct FixedFunction<BlendFactor> : FixedFunctionField<BlendFactor> {
  static constexpr FixedFunctionEntry<BlendFactor> ENTRIES[] = {
#define TESSERA_BLEND_FACTOR(name, code, gl_enum, source, destination, description) \
  {BlendFactor::name, #name, gl_enum, description},
#include "common/fixed_function.def"
  };
};

template <>
struct FixedFunction<LogicOp> : FixedFunctionField<LogicOp> {
  static constexpr FixedFunctionEntry<LogicOp> ENTRIES[] = {
#define TESSERA_LOGIC_OP(name, code, gl_enum, description) {LogicOp::name, #name, gl_enum, description},
#include "common/fixed_function.def"
  };
};

template <>
struct FixedFunction<TexEnv> : FixedFunctionField<TexEnv> {
  static constexpr FixedFunctionEntry<TexEnv> ENTRIES[] = {
#define TESSERA_TEX_ENV(name, code, gl_enum, description) {TexEnv::name, #name, gl_enum, description},
#include "common/fixed_function.def"
  };
};

template <>
struct FixedFunction<TexBaseFormat> : FixedFunctionField<TexBaseFormat> {
  static constexpr FixedFunctionEntry<TexBaseFormat> ENTRIES[] = {
#define TESSERA_TEX_BASE_FORMAT(name, code, gl_enum, description) {TexBaseFormat::name, #name, gl_enum, description},
#include "common/fixed_function.def"
  };
};

template <>
struct FixedFunction<CombineFunc> : FixedFunctionField<CombineFunc> {
  static constexpr FixedFunctionEntry<CombineFunc> ENTRIES[] = {
#define TESSERA_COMBINE_FUNC(name, code, gl_enum, description) {CombineFunc::name, #name, gl_enum, description},
#include "common/fixed_function.def"
  };
};

template <>
struct FixedFunction<CombineSource> : FixedFunctionField<CombineSource> {
  static constexpr FixedFunctionEntry<CombineSource> ENTRIES[] = {
#define TESSERA_COMBINE_SOURCE(name, code, gl_enum, description) {CombineSource::name, #name, gl_enum, description},
#include "common/fixed_function.def"
  };
};

template <>
struct FixedFunction<CombineOperand> : FixedFunctionField<CombineOperand> {
  static constexpr FixedFunctionEntry<CombineOperand> ENTRIES[] = {
#define TESSERA_COMBINE_OPERAND(name, code, gl_enum, description) {CombineOperand::name, #name, gl_enum, description},
#include "common/fixed_function.def"
  };
};

template <>
struct FixedFunction<TexFilter> : FixedFunctionField<TexFilter> {
  static constexpr FixedFunctionEntry<TexFilter> ENTRIES[] = {
#define TESSERA_TEX_FILTER(name, code, gl_enum, description) {TexFilter::name, #name, gl_enum, description},
#include "common/fixed_function.def"
  };
};

template <>
struct FixedFunction<TexWrap> : FixedFunctionField<TexWrap> {
  static constexpr FixedFunctionEntry<TexWrap> ENTRIES[] = {
#define TESSERA_TEX_WRAP(name, code, gl_enum, description) {TexWrap::name, #name, gl_enum, description},
#include "common/fixed_function.def"
  };
};

template <>
struct FixedFunction<TexMipmap> : FixedFunctionField<TexMipmap> {
  static constexpr FixedFunctionEntry<TexMipmap> ENTRIES[] = {
#define TESSERA_TEX_MIPMAP(name, code, gl_enum, description) {TexMipmap::name, #name, gl_enum, description},
#include "common/fixed_function.def"
  };
};

template <>
struct FixedFunction<FogMode> : FixedFunctionField<FogMode> {
  static constexpr FixedFunctionEntry<FogMode> ENTRIES[] = {
#define TESSERA_FOG_MODE(name, code, gl_enum, description) {FogMode::name, #name, gl_enum, description},
#include "common/fixed_function.def"
  };
};

template <typename E>
constexpr uint32_t field_mask() {
  return (1u << FixedFunction<E>::BITS) - 1;
}

// The hardware code: the number the state blocks, the datapath and the RTL
// see, in its field's width (as a port of that width takes it).
template <typename E>
constexpr uint32_t code_of(E value) {
  return static_cast<uint32_t>(value) & field_mask<E>();
}

// The value a hardware field of the state holds: cut to the field's width,
// as a register of that width would; an unknown code stays as it is.
template <typename E>
constexpr E from_code(uint32_t field) {
  return static_cast<E>(field & field_mask<E>());
}

// The table's entry of a value; nullptr for an unknown code.
template <typename E>
constexpr const FixedFunctionEntry<E>* entry_of(E value) {
  for (const FixedFunctionEntry<E>& entry : FixedFunction<E>::ENTRIES)
    if (entry.value == value) return &entry;
  return nullptr;
}

// The GL enum value of a known code; nothing for an unknown one.
template <typename E>
constexpr std::optional<uint32_t> gl_enum_of(E value) {
  const FixedFunctionEntry<E>* entry = entry_of(value);
  if (entry == nullptr) return std::nullopt;
  return entry->gl_enum;
}

// The value a GL enum stands for; nothing if it is not one of the table's.
template <typename E>
constexpr std::optional<E> from_gl_enum(uint32_t gl_enum) {
  for (const FixedFunctionEntry<E>& entry : FixedFunction<E>::ENTRIES)
    if (entry.gl_enum == gl_enum) return entry.value;
  return std::nullopt;
}

// "less", "one_minus_src_alpha"; "unknown" for a code without an entry.
template <typename E>
constexpr const char* name_of(E value) {
  const FixedFunctionEntry<E>* entry = entry_of(value);
  return entry == nullptr ? "unknown" : entry->name;
}

// glBlendFunc's two arguments accept different factors (OpenGL ES 1.1,
// "Blending"); the datapath defines every combination.
enum class BlendSide : uint8_t { source, destination };

struct BlendFactorSides {
  BlendFactor factor;
  bool source, destination;
};

inline constexpr BlendFactorSides BLEND_FACTOR_SIDES[] = {
#define TESSERA_BLEND_FACTOR(name, code, gl_enum, source, destination, description) \
  {BlendFactor::name, source, destination},
#include "common/fixed_function.def"
};

constexpr bool blend_factor_allowed(BlendFactor factor, BlendSide side) {
  for (const BlendFactorSides& sides : BLEND_FACTOR_SIDES)
    if (sides.factor == factor) return side == BlendSide::source ? sides.source : sides.destination;
  return false;
}

// The factor a glBlendFunc argument stands for on `side`; nothing if the GL
// enum is not a factor or not one that side accepts.
constexpr std::optional<BlendFactor> blend_factor_from_gl_enum(uint32_t gl_enum, BlendSide side) {
  const std::optional<BlendFactor> factor = from_gl_enum<BlendFactor>(gl_enum);
  if (!factor || !blend_factor_allowed(*factor, side)) return std::nullopt;
  return factor;
}

// What GL says a compare function and a stencil operation do, for every
// renderer (the rasterizer's datapath, the arm back end's inner loop) to share.
// A compare code without an entry fails, as NEVER; a stencil code without one
// keeps the value, as KEEP. The stencil result is merged under write_mask.
template <typename T>
constexpr bool compare_passes(CompareFunc func, T incoming, T stored) {
  switch (func) {
    case CompareFunc::never: return false;
    case CompareFunc::less: return incoming < stored;
    case CompareFunc::equal: return incoming == stored;
    case CompareFunc::lequal: return incoming <= stored;
    case CompareFunc::greater: return incoming > stored;
    case CompareFunc::notequal: return incoming != stored;
    case CompareFunc::gequal: return incoming >= stored;
    case CompareFunc::always: return true;
  }
  return false;
}

constexpr uint8_t stencil_op_result(StencilOp op, uint8_t stored, uint8_t ref, uint8_t write_mask) {
  uint8_t result = stored;
  switch (op) {
    case StencilOp::keep: break;
    case StencilOp::zero: result = 0; break;
    case StencilOp::replace: result = ref; break;
    case StencilOp::incr: result = stored == 0xff ? stored : static_cast<uint8_t>(stored + 1); break;
    case StencilOp::decr: result = stored == 0 ? stored : static_cast<uint8_t>(stored - 1); break;
    case StencilOp::invert: result = static_cast<uint8_t>(~stored); break;
  }
  return static_cast<uint8_t>((stored & ~write_mask) | (result & write_mask));
}

}  // namespace tessera
