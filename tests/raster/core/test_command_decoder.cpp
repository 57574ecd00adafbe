// Command decode (tlm/raster/core/command_decoder.h) on its own: command
// lists, StateBlocks and triangle records written word by word in a plain
// memory, decoded through CommandDecoder, and checked against the words'
// layout in contract/raster/command_format.h and the error table of
// tlm/raster/core/README.md ("Errors").
#include <gtest/gtest.h>

#include "raster/core/command_decoder.h"
#include "raster/datapath/texture_env.h"
#include "raster_core_test_support.h"

using namespace tessera::raster;
using tessera::BlendFactor;
using tessera::code_of;
using tessera::CompareFunc;
using tessera::FogMode;
using tessera::LogicOp;
using tessera::StencilOp;
using tessera::TexEnv;
using tessera::TexFilter;
using tessera::TexWrap;
using tessera::raster::test::blend_codes;
using tessera::raster::test::default_state;
using tessera::raster::test::StageRun;

namespace {

constexpr uint32_t LIST = 0x100;
constexpr uint32_t BLOCK = 0x400;
constexpr uint32_t RECORD = 0x800;

// A decoder over one tile's list in a 4 KB memory.
struct DecoderBench : StageRun {
  explicit DecoderBench(uint32_t word_count) : StageRun(0x1000, RunConfig{}), entry{LIST, word_count} {}
  TileEntry entry;
};

TEST(CommandDecoder, DecodesClearStateAndTriangleCommands) {
  DecoderBench b(8);
  // CLEAR: mask bits 8-10 all set; RGBA8888 R in bits 0-7; depth24 with
  // junk in bits 24-31 (not part of the field); stencil 0x5a, colour mask
  // R and B (0b0101), depth_write, stencil write mask 0x0f.
  b.port.set_words(LIST, {1 | 7u << 8, 0x44332211, 0xffabcdef, 0x5a | 5u << 8 | 1u << 12 | 0x0fu << 16});
  b.port.set_words(LIST + 16, {uint32_t(Opcode::state), BLOCK});
  b.port.set_words(LIST + 24, {uint32_t(Opcode::triangle), RECORD});
  CommandDecoder decoder(b.run, b.entry);

  Command c;
  ASSERT_TRUE(decoder.next(c));
  EXPECT_EQ(c.opcode, Opcode::clear);
  EXPECT_TRUE(c.clear.color && c.clear.depth && c.clear.stencil);
  EXPECT_EQ(c.clear.rgba.r.raw, 0x11u);
  EXPECT_EQ(c.clear.rgba.g.raw, 0x22u);
  EXPECT_EQ(c.clear.rgba.b.raw, 0x33u);
  EXPECT_EQ(c.clear.rgba.a.raw, 0x44u);
  EXPECT_EQ(c.clear.depth_value, 0xabcdefu);
  EXPECT_EQ(c.clear.stencil_value, 0x5a);
  EXPECT_EQ(c.clear.color_mask, 5);
  EXPECT_TRUE(c.clear.depth_write);
  EXPECT_EQ(c.clear.stencil_write_mask, 0x0f);

  ASSERT_TRUE(decoder.next(c));
  EXPECT_EQ(c.opcode, Opcode::state);
  EXPECT_EQ(c.pointer, BLOCK);
  ASSERT_TRUE(decoder.next(c));
  EXPECT_EQ(c.opcode, Opcode::triangle);
  EXPECT_EQ(c.pointer, RECORD);
  EXPECT_FALSE(decoder.next(c));  // 4 + 2 + 2 = 8 words: the end of the list, not an error

  EXPECT_EQ(b.run.result().error, RasterError::none);
  // Three commands, one `command` cycle each (README.md, "Counters and cycle costs").
  EXPECT_EQ(b.run.result().commands, 3u);
  EXPECT_EQ(b.run.result().tile_cycles, 3u * b.costs.command);
  // 8 words fetched: each command's first word, then its rest in one access.
  EXPECT_EQ(b.run.result().bytes_read, 32u);
  EXPECT_EQ(b.port.reads, (std::vector<uint32_t>{LIST, LIST + 4, LIST + 16, LIST + 20, LIST + 24, LIST + 28}));
}

TEST(CommandDecoder, ClearMaskBitsNameTheBuffers) {
  DecoderBench b(4);
  b.port.set_words(LIST, {1 | 2u << 8, 0, 0x123456, 0});  // mask bit 1 alone: depth
  CommandDecoder decoder(b.run, b.entry);
  Command c;
  ASSERT_TRUE(decoder.next(c));
  EXPECT_FALSE(c.clear.color);
  EXPECT_TRUE(c.clear.depth);
  EXPECT_FALSE(c.clear.stencil);
  EXPECT_FALSE(c.clear.depth_write);  // bit 12 of the fourth word clear
}

TEST(CommandDecoder, RefusesABadOpcodeAtTheCommandWord) {
  DecoderBench b(6);
  // A good CLEAR, then a word whose bits 0-7 are 0 (bits above them set:
  // they are not the opcode).
  b.port.set_words(LIST, {1 | 7u << 8, 0, 0, 0, 0x00000300, BLOCK});
  CommandDecoder decoder(b.run, b.entry);
  Command c;
  ASSERT_TRUE(decoder.next(c));
  EXPECT_FALSE(decoder.next(c));
  EXPECT_EQ(b.run.result().error, RasterError::bad_opcode);
  EXPECT_EQ(b.run.result().error_address, LIST + 16);
  EXPECT_EQ(b.run.result().commands, 1u);  // the bad word is not a command
  EXPECT_FALSE(decoder.next(c));           // and nothing after the error
}

TEST(CommandDecoder, OpcodesAboveThreeAreBad) {
  for (uint32_t opcode : {0u, 4u, 0xffu}) {
    DecoderBench b(2);
    b.port.set_words(LIST, {opcode, 0});
    CommandDecoder decoder(b.run, b.entry);
    Command c;
    EXPECT_FALSE(decoder.next(c)) << opcode;
    EXPECT_EQ(b.run.result().error, RasterError::bad_opcode) << opcode;
    EXPECT_EQ(b.run.result().error_address, LIST) << opcode;
  }
}

TEST(CommandDecoder, RefusesACommandRunningPastTheList) {
  {
    // A 4-word CLEAR in a 3-word list: list_overrun at its first word,
    // before the rest of it is fetched.
    DecoderBench b(3);
    b.port.set_words(LIST, {1 | 7u << 8, 0, 0, 0});
    CommandDecoder decoder(b.run, b.entry);
    Command c;
    EXPECT_FALSE(decoder.next(c));
    EXPECT_EQ(b.run.result().error, RasterError::list_overrun);
    EXPECT_EQ(b.run.result().error_address, LIST);
    EXPECT_EQ(b.port.reads, std::vector<uint32_t>{LIST});
    EXPECT_EQ(b.run.result().commands, 0u);
  }
  {
    // A CLEAR that fits, then a TRIANGLE's op word as the list's last word.
    DecoderBench b(5);
    b.port.set_words(LIST, {1 | 7u << 8, 0, 0, 0, uint32_t(Opcode::triangle), RECORD});
    CommandDecoder decoder(b.run, b.entry);
    Command c;
    ASSERT_TRUE(decoder.next(c));
    EXPECT_FALSE(decoder.next(c));
    EXPECT_EQ(b.run.result().error, RasterError::list_overrun);
    EXPECT_EQ(b.run.result().error_address, LIST + 16);
  }
}

TEST(CommandDecoder, ARefusedFetchIsABusErrorAtTheAccess) {
  DecoderBench b(4);
  b.port.set_words(LIST, {1 | 7u << 8, 0, 0, 0});
  b.port.fail_begin = LIST + 8;  // the third word of the CLEAR
  b.port.fail_end = LIST + 12;
  CommandDecoder decoder(b.run, b.entry);
  Command c;
  EXPECT_FALSE(decoder.next(c));
  EXPECT_EQ(b.run.result().error, RasterError::bus_error);
  // The failing access is the command's rest (words 1-3) in one read.
  EXPECT_EQ(b.run.result().error_address, LIST + 4);
}

TEST(CommandDecoder, ReadStateDecodesEveryFieldOfTheBlock) {
  DecoderBench b(0);
  StateBlock s = default_state();
  s.flags = StateFlag::depth_test | StateFlag::blend | StateFlag::scissor_test | StateFlag::texture;
  s.depth_func = 0xfffffff8 | code_of(CompareFunc::gequal);  // cut to the code's 3 bits
  s.alpha_func = code_of(CompareFunc::greater) | 0x80u << 8;
  s.stencil_func = code_of(CompareFunc::equal) | 0x33u << 8 | 0x0fu << 16 | 0xf0u << 24;
  s.stencil_ops = code_of(StencilOp::incr) << STENCIL_FAIL_SHIFT |
                  code_of(StencilOp::decr) << STENCIL_DEPTH_FAIL_SHIFT |
                  code_of(StencilOp::invert) << STENCIL_DEPTH_PASS_SHIFT;
  s.blend = code_of(BlendFactor::src_alpha) << BLEND_SRC_SHIFT |
            code_of(BlendFactor::one_minus_src_alpha) << BLEND_DST_SHIFT |
            code_of(LogicOp::xor_) << BLEND_LOGIC_OP_SHIFT;
  s.color_mask = 0xfa;  // bits 0-3 only: G and A
  // glScissor(-5, 7, 20, 30): x signed 16-bit, so the box is x -5..15, y 7..37.
  s.scissor_xy = 0xfffbu | 7u << 16;
  s.scissor_size = 20u | 30u << 16;
  s.texture_address = 0x8000;
  s.texture_size = 9u | 3u << 8;  // log2 width 9 is stored as it is and clamped to 8 for addressing
  s.texture_mode = code_of(TexFilter::linear) << TEXTURE_MIN_FILTER_SHIFT |
                   code_of(TexFilter::nearest) << TEXTURE_MAG_FILTER_SHIFT |
                   code_of(TexWrap::clamp_to_edge) << TEXTURE_WRAP_S_SHIFT |
                   code_of(TexWrap::repeat) << TEXTURE_WRAP_T_SHIFT | 3u << TEXTURE_ENV_SHIFT;
  std::memcpy(b.port.memory.data() + BLOCK, &s, sizeof s);
  CommandDecoder decoder(b.run, b.entry);
  DrawState state;
  ASSERT_TRUE(decoder.read_state(BLOCK, state));

  EXPECT_EQ(state.address, BLOCK);
  const FragmentOperationsState& o = state.operations;
  EXPECT_TRUE(o.depth_test);
  EXPECT_FALSE(o.depth_write);  // not in the flags
  EXPECT_FALSE(o.alpha_test);
  EXPECT_FALSE(o.stencil_test);
  EXPECT_TRUE(o.blend);
  EXPECT_FALSE(o.logic_op);
  EXPECT_EQ(o.depth_func, CompareFunc::gequal);
  EXPECT_EQ(o.alpha_func, CompareFunc::greater);
  EXPECT_EQ(o.alpha_ref, 0x80);
  EXPECT_EQ(o.stencil_func, CompareFunc::equal);
  EXPECT_EQ(o.stencil_ref, 0x33);
  EXPECT_EQ(o.stencil_value_mask, 0x0f);
  EXPECT_EQ(o.stencil_write_mask, 0xf0);
  EXPECT_EQ(o.stencil_fail, StencilOp::incr);
  EXPECT_EQ(o.depth_fail, StencilOp::decr);
  EXPECT_EQ(o.depth_pass, StencilOp::invert);
  EXPECT_EQ(o.blend_src, BlendFactor::src_alpha);
  EXPECT_EQ(o.blend_dst, BlendFactor::one_minus_src_alpha);
  EXPECT_EQ(o.logic_op_mode, LogicOp::xor_);
  EXPECT_EQ(o.color_mask, 0x0a);
  EXPECT_TRUE(state.scissor);
  EXPECT_EQ(state.scissor_box.x0, -5);
  EXPECT_EQ(state.scissor_box.y0, 7);
  EXPECT_EQ(state.scissor_box.x1, 15);
  EXPECT_EQ(state.scissor_box.y1, 37);
  EXPECT_EQ(state.texture.base, 0x8000u);
  EXPECT_EQ(state.log2_width, 9u);
  EXPECT_EQ(state.log2_height, 3u);
  EXPECT_EQ(state.texture.log2_width, 8u);
  EXPECT_EQ(state.texture.log2_height, 3u);
  EXPECT_EQ(state.min_filter, TexFilter::linear);
  EXPECT_EQ(state.mag_filter, TexFilter::nearest);
  EXPECT_EQ(state.texture.wrap_s, TexWrap::clamp_to_edge);
  EXPECT_EQ(state.texture.wrap_t, TexWrap::repeat);
  // The block's reserved environment code 3 passes the fragment through
  // (command_format.h): the texel has no effect on the fragment's colour.
  EXPECT_EQ(texture_environment_word(state.env, 0x11223344, 0xaabbccdd), 0x11223344u);
  EXPECT_TRUE(state.textured());
  EXPECT_EQ(state.unit_count, 0u);
  // One access: 12 words, no fog or texture unit words without their flags.
  EXPECT_EQ(b.port.reads, std::vector<uint32_t>{BLOCK});
  EXPECT_EQ(b.run.result().bytes_read, 48u);
}

TEST(CommandDecoder, ReadStateFetchesTheFogStateAfterTheBlock) {
  DecoderBench b(0);
  StateBlock s = default_state();
  s.flags |= StateFlag::fog;
  std::memcpy(b.port.memory.data() + BLOCK, &s, sizeof s);
  b.port.set_words(BLOCK + 48, {code_of(FogMode::exp2), 0x00102030});
  CommandDecoder decoder(b.run, b.entry);
  DrawState state;
  ASSERT_TRUE(decoder.read_state(BLOCK, state));
  EXPECT_EQ(state.fog_mode, FogMode::exp2);
  EXPECT_EQ(state.fog_color.r.raw, 0x30u);
  EXPECT_EQ(state.fog_color.g.raw, 0x20u);
  EXPECT_EQ(state.fog_color.b.raw, 0x10u);
  EXPECT_EQ(b.port.reads, (std::vector<uint32_t>{BLOCK, BLOCK + 48}));  // the FogState, a second access
}

TEST(CommandDecoder, ReadStateRefusesAUnitCountOutsideOneToTheHardwares) {
  for (uint32_t count : {0u, 3u}) {
    DecoderBench b(0);
    b.config.texture_units = 2;  // this hardware has two units
    StateBlock s = default_state();
    s.flags |= StateFlag::texture_units;
    std::memcpy(b.port.memory.data() + BLOCK, &s, sizeof s);
    b.port.set_word(BLOCK + 48, count);  // the TextureUnitsHeader, right after the block without fog
    CommandDecoder decoder(b.run, b.entry);
    DrawState state;
    EXPECT_FALSE(decoder.read_state(BLOCK, state)) << count;
    EXPECT_EQ(b.run.result().error, RasterError::bad_texture) << count;
    EXPECT_EQ(b.run.result().error_address, BLOCK + 48) << count;
  }
}

TEST(CommandDecoder, ReadStateOfARefusedBlockIsABusError) {
  DecoderBench b(0);
  b.port.fail_begin = BLOCK + 44;
  b.port.fail_end = BLOCK + 48;
  CommandDecoder decoder(b.run, b.entry);
  DrawState state;
  state.address = 0x1234;
  EXPECT_FALSE(decoder.read_state(BLOCK, state));
  EXPECT_EQ(b.run.result().error, RasterError::bus_error);
  EXPECT_EQ(b.run.result().error_address, BLOCK);
  EXPECT_EQ(state.address, 0x1234u);  // the state in force is left as it was
}

TEST(CommandDecoder, ReadTriangleDecodesTheVertexRecords) {
  DecoderBench b(0);
  TriangleRecord t{};
  // x 9.4 in bits 0-15, y in 16-31: (1.5, 2.25), (511.9375, 0), (0, 511.9375).
  t.v[0] = {24u | 36u << 16, 0xff000001, 0x04030201, 0.25f, 0.5f, 1.0f};
  t.v[1] = {8191u, 0x00ffffff, 0xffffffff, -1.0f, 2.0f, 0.5f};
  t.v[2] = {8191u << 16, 0x00800000, 0, 0, 0, 0.125f};
  std::memcpy(b.port.memory.data() + RECORD, &t, sizeof t);
  CommandDecoder decoder(b.run, b.entry);
  DrawState state;  // GL's defaults: no fog, no texture units
  TriangleVertices v;
  ASSERT_TRUE(decoder.read_triangle(RECORD, state, v));
  EXPECT_EQ(v[0].x, 24u);
  EXPECT_EQ(v[0].y, 36u);
  EXPECT_EQ(v[0].z, 1u);  // bits 24-31 are not part of the 0.24 depth
  EXPECT_EQ(v[0].color.r.raw, 1u);
  EXPECT_EQ(v[0].color.a.raw, 4u);
  EXPECT_EQ(v[0].s_over_w, 0.25f);
  EXPECT_EQ(v[0].t_over_w, 0.5f);
  EXPECT_EQ(v[0].inv_w, 1.0f);
  EXPECT_EQ(v[0].fog, 0);
  EXPECT_EQ(v[1].x, 8191u);
  EXPECT_EQ(v[1].y, 0u);
  EXPECT_EQ(v[1].z, 0xffffffu);
  EXPECT_EQ(v[1].s_over_w, -1.0f);
  EXPECT_EQ(v[2].x, 0u);
  EXPECT_EQ(v[2].y, 8191u);
  EXPECT_EQ(v[2].inv_w, 0.125f);
  EXPECT_EQ(b.run.result().bytes_read, 72u);  // 18 words in one access
  EXPECT_EQ(b.run.result().triangles_skipped, 0u);
}

TEST(CommandDecoder, ReadTriangleSkipsCoordinatesOutsideNinePointFour) {
  DecoderBench b(0);
  TriangleRecord t{};
  t.v[1].xy = 8192u;  // x = 512.0: one code beyond 9.4
  std::memcpy(b.port.memory.data() + RECORD, &t, sizeof t);
  CommandDecoder decoder(b.run, b.entry);
  DrawState state;
  TriangleVertices v;
  EXPECT_FALSE(decoder.read_triangle(RECORD, state, v));
  EXPECT_EQ(b.run.result().triangles_skipped, 1u);
  EXPECT_EQ(b.run.result().error, RasterError::none);  // skipped, not an error
}

TEST(CommandDecoder, ReadTriangleWithFogFetchesTwentyOneWords) {
  DecoderBench b(0);
  TriangleRecord t{};
  std::memcpy(b.port.memory.data() + RECORD, &t, sizeof t);
  b.port.set_words(RECORD + 72, {0x10000, 0xfffe0000, 0x7fffffff});  // 1.0, -2.0, the largest 16.16
  CommandDecoder decoder(b.run, b.entry);
  DrawState state;
  state.flags |= StateFlag::fog;
  TriangleVertices v;
  ASSERT_TRUE(decoder.read_triangle(RECORD, state, v));
  EXPECT_EQ(v[0].fog, 0x10000);
  EXPECT_EQ(v[1].fog, -0x20000);
  EXPECT_EQ(v[2].fog, 0x7fffffff);
  EXPECT_EQ(b.run.result().bytes_read, 84u);
}

}  // namespace
