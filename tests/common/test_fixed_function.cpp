// The fixed-function state table (common/fixed_function.def and .h): codes
// dense and unique within their field, every GL enum checked against
// Khronos' GLES/gl.h and round-tripped, the enums GL does not accept
// rejected (blend factors per side as OpenGL ES 1.1 lists them), unknown
// codes cut and named as the table says, and the generated SystemVerilog
// package holding the same numbers.
#include <GLES/gl.h>
#include <gtest/gtest.h>

#include <cctype>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "common/fixed_function.h"

namespace {

using namespace tessera;

// Every enumeration in the same checks.
template <typename E>
void check_dense_unique_and_round_trip(const std::map<E, GLenum>& khronos) {
  const auto& entries = FixedFunction<E>::ENTRIES;
  const unsigned count = static_cast<unsigned>(std::size(entries));
  SCOPED_TRACE(FixedFunction<E>::NAME);
  EXPECT_LE(count, 1u << FixedFunction<E>::BITS);
  std::set<uint32_t> codes, gl_enums;
  std::set<std::string> names;
  for (const FixedFunctionEntry<E>& entry : entries) {
    const uint32_t code = static_cast<uint32_t>(entry.value);
    EXPECT_LT(code, count) << entry.name << ": codes are 0 .. count - 1";
    EXPECT_TRUE(codes.insert(code).second) << entry.name << ": code used twice";
    EXPECT_TRUE(gl_enums.insert(entry.gl_enum).second) << entry.name << ": GL enum used twice";
    EXPECT_TRUE(names.insert(entry.name).second) << entry.name;
    EXPECT_NE(std::string(entry.description), "");

    // GL enum <-> code, and the field's cut, give the entry back.
    ASSERT_EQ(khronos.count(entry.value), 1u) << entry.name << " has no GLES/gl.h name in the test";
    EXPECT_EQ(entry.gl_enum, khronos.at(entry.value)) << entry.name;
    EXPECT_EQ(from_gl_enum<E>(entry.gl_enum), entry.value) << entry.name;
    EXPECT_EQ(gl_enum_of(entry.value), entry.gl_enum) << entry.name;
    EXPECT_EQ(code_of(entry.value), code);
    EXPECT_EQ(from_code<E>(code), entry.value);
    EXPECT_EQ(from_code<E>(code | 0xffffff00u << FixedFunction<E>::BITS), entry.value) << "bits above the field";
    EXPECT_EQ(entry_of(entry.value), &entry);
    EXPECT_STREQ(name_of(entry.value), entry.name);
  }
  EXPECT_EQ(khronos.size(), std::size(entries)) << "GLES/gl.h names without an entry";

  // Codes of the field without an entry: legal values, no GL enum, "unknown".
  for (uint32_t code = count; code < (1u << FixedFunction<E>::BITS); ++code) {
    const E unknown = from_code<E>(code);
    EXPECT_EQ(code_of(unknown), code);
    EXPECT_EQ(entry_of(unknown), nullptr);
    EXPECT_FALSE(gl_enum_of(unknown).has_value());
    EXPECT_STREQ(name_of(unknown), "unknown");
  }
}

// Every enum value of every table, their neighbours and a few others: only
// this table's own enums convert.
template <typename E>
void check_rejects_other_enums() {
  SCOPED_TRACE(FixedFunction<E>::NAME);
  std::set<uint32_t> candidates = {0xffffffffu,
                                   0x10000u,
                                   0x0B41u,
                                   GL_ADD,
                                   GL_COMBINE,
                                   GL_BLEND,
                                   GL_NEAREST_MIPMAP_NEAREST,
                                   GL_LINEAR_MIPMAP_LINEAR,
                                   GL_CLAMP_TO_EDGE + 1};
  const auto add = [&candidates](const auto& entries) {
    for (const auto& entry : entries) {
      candidates.insert(entry.gl_enum);
      candidates.insert(entry.gl_enum + 1);
      if (entry.gl_enum > 0) candidates.insert(entry.gl_enum - 1);
    }
  };
  add(FixedFunction<CompareFunc>::ENTRIES);
  add(FixedFunction<StencilOp>::ENTRIES);
  add(FixedFunction<BlendFactor>::ENTRIES);
  add(FixedFunction<LogicOp>::ENTRIES);
  add(FixedFunction<TexEnv>::ENTRIES);
  add(FixedFunction<TexBaseFormat>::ENTRIES);
  add(FixedFunction<CombineFunc>::ENTRIES);
  add(FixedFunction<CombineSource>::ENTRIES);
  add(FixedFunction<CombineOperand>::ENTRIES);
  add(FixedFunction<TexFilter>::ENTRIES);
  add(FixedFunction<TexWrap>::ENTRIES);
  add(FixedFunction<TexMipmap>::ENTRIES);
  add(FixedFunction<FogMode>::ENTRIES);
  for (const uint32_t gl_enum : candidates) {
    bool listed = false;
    for (const FixedFunctionEntry<E>& entry : FixedFunction<E>::ENTRIES) listed = listed || entry.gl_enum == gl_enum;
    EXPECT_EQ(from_gl_enum<E>(gl_enum).has_value(), listed) << std::hex << gl_enum;
  }
}

TEST(FixedFunction, CompareFunctions) {
  check_dense_unique_and_round_trip<CompareFunc>({{CompareFunc::never, GL_NEVER},
                                                  {CompareFunc::less, GL_LESS},
                                                  {CompareFunc::equal, GL_EQUAL},
                                                  {CompareFunc::lequal, GL_LEQUAL},
                                                  {CompareFunc::greater, GL_GREATER},
                                                  {CompareFunc::notequal, GL_NOTEQUAL},
                                                  {CompareFunc::gequal, GL_GEQUAL},
                                                  {CompareFunc::always, GL_ALWAYS}});
  check_rejects_other_enums<CompareFunc>();
  // The code is the GL order, as the hardware compares (GL_NEVER + code).
  for (const auto& entry : FixedFunction<CompareFunc>::ENTRIES)
    EXPECT_EQ(entry.gl_enum, GL_NEVER + code_of(entry.value));
}

TEST(FixedFunction, StencilOperations) {
  check_dense_unique_and_round_trip<StencilOp>({{StencilOp::keep, GL_KEEP},
                                                {StencilOp::zero, GL_ZERO},
                                                {StencilOp::replace, GL_REPLACE},
                                                {StencilOp::incr, GL_INCR},
                                                {StencilOp::decr, GL_DECR},
                                                {StencilOp::invert, GL_INVERT}});
  check_rejects_other_enums<StencilOp>();
}

TEST(FixedFunction, BlendFactors) {
  check_dense_unique_and_round_trip<BlendFactor>({{BlendFactor::zero, GL_ZERO},
                                                  {BlendFactor::one, GL_ONE},
                                                  {BlendFactor::src_color, GL_SRC_COLOR},
                                                  {BlendFactor::one_minus_src_color, GL_ONE_MINUS_SRC_COLOR},
                                                  {BlendFactor::src_alpha, GL_SRC_ALPHA},
                                                  {BlendFactor::one_minus_src_alpha, GL_ONE_MINUS_SRC_ALPHA},
                                                  {BlendFactor::dst_alpha, GL_DST_ALPHA},
                                                  {BlendFactor::one_minus_dst_alpha, GL_ONE_MINUS_DST_ALPHA},
                                                  {BlendFactor::dst_color, GL_DST_COLOR},
                                                  {BlendFactor::one_minus_dst_color, GL_ONE_MINUS_DST_COLOR},
                                                  {BlendFactor::src_alpha_saturate, GL_SRC_ALPHA_SATURATE}});
  check_rejects_other_enums<BlendFactor>();
}

// OpenGL ES 1.1, section 4.1.7: the sfactor and dfactor lists of glBlendFunc.
TEST(FixedFunction, BlendFactorSidesAreThoseOfGlEs11) {
  const std::set<GLenum> source = {GL_ZERO,
                                   GL_ONE,
                                   GL_DST_COLOR,
                                   GL_ONE_MINUS_DST_COLOR,
                                   GL_SRC_ALPHA,
                                   GL_ONE_MINUS_SRC_ALPHA,
                                   GL_DST_ALPHA,
                                   GL_ONE_MINUS_DST_ALPHA,
                                   GL_SRC_ALPHA_SATURATE};
  const std::set<GLenum> destination = {GL_ZERO,      GL_ONE,       GL_SRC_COLOR,           GL_ONE_MINUS_SRC_COLOR,
                                        GL_SRC_ALPHA, GL_DST_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE_MINUS_DST_ALPHA};
  for (const auto& entry : FixedFunction<BlendFactor>::ENTRIES) {
    const bool as_source = source.count(entry.gl_enum) != 0;
    const bool as_destination = destination.count(entry.gl_enum) != 0;
    EXPECT_EQ(blend_factor_allowed(entry.value, BlendSide::source), as_source) << entry.name;
    EXPECT_EQ(blend_factor_allowed(entry.value, BlendSide::destination), as_destination) << entry.name;
    EXPECT_EQ(blend_factor_from_gl_enum(entry.gl_enum, BlendSide::source).has_value(), as_source) << entry.name;
    EXPECT_EQ(blend_factor_from_gl_enum(entry.gl_enum, BlendSide::destination).has_value(), as_destination)
        << entry.name;
  }
  EXPECT_EQ(std::size(BLEND_FACTOR_SIDES), std::size(FixedFunction<BlendFactor>::ENTRIES));
  EXPECT_FALSE(blend_factor_from_gl_enum(GL_SRC_COLOR, BlendSide::source).has_value());
  EXPECT_FALSE(blend_factor_from_gl_enum(GL_SRC_ALPHA_SATURATE, BlendSide::destination).has_value());
  EXPECT_FALSE(blend_factor_from_gl_enum(GL_LESS, BlendSide::source).has_value());
  EXPECT_FALSE(blend_factor_allowed(from_code<BlendFactor>(15), BlendSide::source));
}

TEST(FixedFunction, LogicOps) {
  check_dense_unique_and_round_trip<LogicOp>({{LogicOp::clear, GL_CLEAR},
                                              {LogicOp::and_, GL_AND},
                                              {LogicOp::and_reverse, GL_AND_REVERSE},
                                              {LogicOp::copy, GL_COPY},
                                              {LogicOp::and_inverted, GL_AND_INVERTED},
                                              {LogicOp::noop, GL_NOOP},
                                              {LogicOp::xor_, GL_XOR},
                                              {LogicOp::or_, GL_OR},
                                              {LogicOp::nor, GL_NOR},
                                              {LogicOp::equiv, GL_EQUIV},
                                              {LogicOp::invert, GL_INVERT},
                                              {LogicOp::or_reverse, GL_OR_REVERSE},
                                              {LogicOp::copy_inverted, GL_COPY_INVERTED},
                                              {LogicOp::or_inverted, GL_OR_INVERTED},
                                              {LogicOp::nand, GL_NAND},
                                              {LogicOp::set, GL_SET}});
  check_rejects_other_enums<LogicOp>();
}

TEST(FixedFunction, TextureEnvironmentsFiltersAndWraps) {
  check_dense_unique_and_round_trip<TexEnv>({{TexEnv::replace, GL_REPLACE},
                                             {TexEnv::modulate, GL_MODULATE},
                                             {TexEnv::decal, GL_DECAL},
                                             {TexEnv::blend, GL_BLEND},
                                             {TexEnv::add, GL_ADD},
                                             {TexEnv::combine, GL_COMBINE}});
  check_rejects_other_enums<TexEnv>();
  // The StateBlock's 2-bit field carries the first three (command_format.h).
  EXPECT_LT(code_of(TexEnv::replace), 4u);
  EXPECT_LT(code_of(TexEnv::modulate), 4u);
  EXPECT_LT(code_of(TexEnv::decal), 4u);
  check_dense_unique_and_round_trip<TexFilter>({{TexFilter::nearest, GL_NEAREST}, {TexFilter::linear, GL_LINEAR}});
  check_rejects_other_enums<TexFilter>();
  check_dense_unique_and_round_trip<TexWrap>(
      {{TexWrap::repeat, GL_REPEAT}, {TexWrap::clamp_to_edge, GL_CLAMP_TO_EDGE}});
  check_rejects_other_enums<TexWrap>();
}

// The choice between levels, named by the minification filters that take
// NEAREST within a level (the within-level filter is TexFilter's).
TEST(FixedFunction, TextureMipmapChoices) {
  check_dense_unique_and_round_trip<TexMipmap>({{TexMipmap::none, GL_NEAREST},
                                                {TexMipmap::nearest, GL_NEAREST_MIPMAP_NEAREST},
                                                {TexMipmap::linear, GL_NEAREST_MIPMAP_LINEAR}});
  check_rejects_other_enums<TexMipmap>();
  EXPECT_EQ(FixedFunction<TexMipmap>::BITS, 2u);
  EXPECT_STREQ(FixedFunction<TexMipmap>::UNKNOWN, "code 3 acts as none, level 0 only");
}

// ES 1.1 table 3.15's base formats (RGBA is code 0: a unit state without
// the field set draws an RGBA texture) and the combiner's tables 3.17, 3.18.
TEST(FixedFunction, BaseFormatsAndCombiner) {
  check_dense_unique_and_round_trip<TexBaseFormat>({{TexBaseFormat::rgba, GL_RGBA},
                                                    {TexBaseFormat::rgb, GL_RGB},
                                                    {TexBaseFormat::alpha, GL_ALPHA},
                                                    {TexBaseFormat::luminance, GL_LUMINANCE},
                                                    {TexBaseFormat::luminance_alpha, GL_LUMINANCE_ALPHA}});
  check_rejects_other_enums<TexBaseFormat>();
  EXPECT_EQ(code_of(TexBaseFormat::rgba), 0u);
  check_dense_unique_and_round_trip<CombineFunc>({{CombineFunc::replace, GL_REPLACE},
                                                  {CombineFunc::modulate, GL_MODULATE},
                                                  {CombineFunc::add, GL_ADD},
                                                  {CombineFunc::add_signed, GL_ADD_SIGNED},
                                                  {CombineFunc::interpolate, GL_INTERPOLATE},
                                                  {CombineFunc::subtract, GL_SUBTRACT},
                                                  {CombineFunc::dot3_rgb, GL_DOT3_RGB},
                                                  {CombineFunc::dot3_rgba, GL_DOT3_RGBA}});
  check_rejects_other_enums<CombineFunc>();
  check_dense_unique_and_round_trip<CombineSource>({{CombineSource::texture, GL_TEXTURE},
                                                    {CombineSource::constant, GL_CONSTANT},
                                                    {CombineSource::primary_color, GL_PRIMARY_COLOR},
                                                    {CombineSource::previous, GL_PREVIOUS}});
  check_rejects_other_enums<CombineSource>();
  check_dense_unique_and_round_trip<CombineOperand>({{CombineOperand::src_color, GL_SRC_COLOR},
                                                     {CombineOperand::one_minus_src_color, GL_ONE_MINUS_SRC_COLOR},
                                                     {CombineOperand::src_alpha, GL_SRC_ALPHA},
                                                     {CombineOperand::one_minus_src_alpha, GL_ONE_MINUS_SRC_ALPHA}});
  check_rejects_other_enums<CombineOperand>();
}

TEST(FixedFunction, FogModes) {
  check_dense_unique_and_round_trip<FogMode>(
      {{FogMode::linear, GL_LINEAR}, {FogMode::exp, GL_EXP}, {FogMode::exp2, GL_EXP2}});
  check_rejects_other_enums<FogMode>();
  EXPECT_EQ(FixedFunction<FogMode>::BITS, 2u);
  EXPECT_STREQ(FixedFunction<FogMode>::UNKNOWN, "code 3 applies no fog, f = 1");
}

// The unknown codes the table defines are the ones its description names.
TEST(FixedFunction, FieldsSayWhatUnknownCodesDo) {
  EXPECT_EQ(FixedFunction<CompareFunc>::BITS, 3u);
  EXPECT_EQ(FixedFunction<StencilOp>::BITS, 3u);
  EXPECT_EQ(FixedFunction<BlendFactor>::BITS, 4u);
  EXPECT_EQ(FixedFunction<LogicOp>::BITS, 4u);
  EXPECT_EQ(FixedFunction<TexEnv>::BITS, 3u);
  EXPECT_EQ(FixedFunction<TexBaseFormat>::BITS, 3u);
  EXPECT_EQ(FixedFunction<CombineFunc>::BITS, 3u);
  EXPECT_EQ(FixedFunction<CombineSource>::BITS, 2u);
  EXPECT_EQ(FixedFunction<CombineOperand>::BITS, 2u);
  EXPECT_EQ(FixedFunction<TexFilter>::BITS, 1u);
  EXPECT_EQ(FixedFunction<TexWrap>::BITS, 2u);
  EXPECT_STREQ(FixedFunction<StencilOp>::UNKNOWN, "codes 6 and 7 keep the stored value");
  EXPECT_STREQ(FixedFunction<BlendFactor>::UNKNOWN, "codes 11 to 15 act as zero");
  EXPECT_STREQ(FixedFunction<TexEnv>::UNKNOWN, "codes 6 and 7 pass the unit's input colour through");
  EXPECT_STREQ(FixedFunction<TexBaseFormat>::UNKNOWN, "codes 5 to 7 act as RGBA");
  EXPECT_STREQ(FixedFunction<TexWrap>::UNKNOWN, "codes 2 and 3 act as repeat, the GL default");
}

// and_reverse -> AndReverse, xor_ -> Xor: the package generator's names.
std::string upper_camel(std::string name) {
  if (!name.empty() && name.back() == '_') name.pop_back();
  std::string out;
  bool start = true;
  for (const char c : name) {
    if (c == '_') {
      start = true;
      continue;
    }
    out += start ? static_cast<char>(std::toupper(static_cast<unsigned char>(c))) : c;
    start = false;
  }
  return out;
}

// The package rtl_models' units read, generated at build time from the
// .def (cmake/fixed_function_pkg.cmake), against the C++ view of the table.
class GeneratedPackage : public ::testing::Test {
 protected:
  void SetUp() override {
    std::ifstream in(TESSERA_FIXED_FUNCTION_PKG);
    ASSERT_TRUE(in) << "cannot read " << TESSERA_FIXED_FUNCTION_PKG;
    std::stringstream text;
    text << in.rdbuf();
    const std::string sv = text.str();
    const std::regex bits(R"(localparam int unsigned (\w+)Bits = (\d+);)");
    for (auto it = std::sregex_iterator(sv.begin(), sv.end(), bits); it != std::sregex_iterator(); ++it)
      m_bits[(*it)[1]] = std::stoul((*it)[2]);
    const std::regex value(R"((\w+) = (\d+)'d(\d+)[, ])");
    for (auto it = std::sregex_iterator(sv.begin(), sv.end(), value); it != std::sregex_iterator(); ++it)
      m_values[(*it)[1]] = {std::stoul((*it)[2]), std::stoul((*it)[3])};
    const std::regex type(R"(\} (\w+)_e;)");
    for (auto it = std::sregex_iterator(sv.begin(), sv.end(), type); it != std::sregex_iterator(); ++it)
      m_types.insert((*it)[1]);
  }

  template <typename E>
  void check(const std::string& type) {
    SCOPED_TRACE(type);
    EXPECT_EQ(m_bits[type], FixedFunction<E>::BITS);
    EXPECT_EQ(m_types.count(FixedFunction<E>::NAME), 1u);
    for (const FixedFunctionEntry<E>& entry : FixedFunction<E>::ENTRIES) {
      const std::string name = type + upper_camel(entry.name);
      ASSERT_EQ(m_values.count(name), 1u) << name << " missing from the package";
      EXPECT_EQ(m_values[name].first, FixedFunction<E>::BITS) << name;
      EXPECT_EQ(m_values[name].second, code_of(entry.value)) << name;
      ++m_checked;
    }
  }

  std::map<std::string, unsigned long> m_bits;
  std::map<std::string, std::pair<unsigned long, unsigned long>> m_values;
  std::set<std::string> m_types;
  size_t m_checked = 0;
};

TEST_F(GeneratedPackage, HoldsTheTablesCodes) {
  check<CompareFunc>("CompareFunc");
  check<StencilOp>("StencilOp");
  check<BlendFactor>("BlendFactor");
  check<LogicOp>("LogicOp");
  check<TexEnv>("TexEnv");
  check<TexBaseFormat>("TexBaseFormat");
  check<CombineFunc>("CombineFunc");
  check<CombineSource>("CombineSource");
  check<CombineOperand>("CombineOperand");
  check<TexFilter>("TexFilter");
  check<TexWrap>("TexWrap");
  check<TexMipmap>("TexMipmap");
  check<FogMode>("FogMode");
  EXPECT_EQ(m_checked, m_values.size()) << "the package has values the table does not";
  EXPECT_EQ(m_bits.size(), 13u);
  EXPECT_EQ(m_types.size(), 13u);
}

}  // namespace
