#include "cosim/raster_vectors.h"

#include <algorithm>

namespace tessera::raster {

const std::array<CompareFunc, 8> ALL_COMPARE_FUNCS{CompareFunc::never,  CompareFunc::less,    CompareFunc::equal,
                                                   CompareFunc::lequal, CompareFunc::greater, CompareFunc::notequal,
                                                   CompareFunc::gequal, CompareFunc::always};
const std::array<StencilOp, 7> ALL_STENCIL_OPS{StencilOp::keep,          StencilOp::zero, StencilOp::replace,
                                               StencilOp::incr,          StencilOp::decr, StencilOp::invert,
                                               static_cast<StencilOp>(7)};
const std::array<BlendFactor, 12> ALL_BLEND_FACTORS{BlendFactor::zero,
                                                    BlendFactor::one,
                                                    BlendFactor::src_color,
                                                    BlendFactor::one_minus_src_color,
                                                    BlendFactor::src_alpha,
                                                    BlendFactor::one_minus_src_alpha,
                                                    BlendFactor::dst_alpha,
                                                    BlendFactor::one_minus_dst_alpha,
                                                    BlendFactor::dst_color,
                                                    BlendFactor::one_minus_dst_color,
                                                    BlendFactor::src_alpha_saturate,
                                                    static_cast<BlendFactor>(15)};
const std::array<TexEnv, 4> ALL_TEXTURE_ENV_MODES{TexEnv::replace, TexEnv::modulate, TexEnv::decal,
                                                  static_cast<TexEnv>(3)};
const std::array<FogMode, 4> ALL_FOG_MODES{FogMode::linear, FogMode::exp, FogMode::exp2, static_cast<FogMode>(3)};

uint16_t random_reciprocal_operand(VectorRng& rng) {
  return static_cast<uint16_t>(rng() & RECIP_OPERAND_MAX);
}

EdgeSpanVector random_edge_span(VectorRng& rng, unsigned pixels) {
  const uint64_t bits = rng(), more = rng();
  EdgeSpanVector v;
  v.px = std::min(static_cast<unsigned>(more) & 0x1ff, 512 - pixels);
  v.py = static_cast<unsigned>(more >> 9) & 0x1ff;
  if (more >> 63) {
    const uint32_t cx = v.px * 16 + static_cast<uint32_t>((more >> 18) & 0x3f) - 32;
    const uint32_t cy = v.py * 16 + static_cast<uint32_t>((more >> 24) & 0x3f) - 32;
    v.edge = Edge{q9_4::from_raw(cx), q9_4::from_raw(cy), q9_4::from_raw(cx + ((more >> 30) & 0x7f)),
                  q9_4::from_raw(cy + ((more >> 37) & 0x7f) - 64)};
    const uint32_t l1 = edge_l1_length(v.edge).raw;
    v.recip = q5_16::from_raw(l1 == 0 ? 0 : static_cast<uint32_t>((uint64_t{1} << 20) / l1));
  } else {
    v.edge = Edge{q9_4::from_raw(static_cast<uint32_t>(bits)), q9_4::from_raw(static_cast<uint32_t>(bits >> 13)),
                  q9_4::from_raw(static_cast<uint32_t>(bits >> 26)), q9_4::from_raw(static_cast<uint32_t>(bits >> 39))};
    v.recip = q5_16::from_raw(static_cast<uint32_t>(more >> 42));
  }
  return v;
}

namespace {

// A word of 1 to 40 significant bits, sign-extended.
int64_t random_plane_word(VectorRng& rng) {
  const unsigned bits = 1 + static_cast<unsigned>(rng() % 40);
  return sign_extend(rng(), bits);
}

}  // namespace

AttributePlane random_attribute_plane(VectorRng& rng) {
  const auto kind = static_cast<AttributeKind>(rng() & 3);
  const int64_t start = random_plane_word(rng);
  const int64_t grad_x = random_plane_word(rng);
  const int64_t grad_y = random_plane_word(rng);
  return AttributePlane{kind, start, grad_x, grad_y};
}

PixelOffset random_pixel_offset(VectorRng& rng) {
  const uint64_t o = rng();
  return {static_cast<int32_t>(o & 0x3ff) - 512, static_cast<int32_t>((o >> 10) & 0x3ff) - 512};
}

FragmentTestState random_fragment_test_state(VectorRng& rng) {
  const uint64_t a = rng(), w = rng();
  FragmentTestState s;
  s.alpha_enable = a & 1;
  s.stencil_enable = (a >> 1) & 1;
  s.depth_enable = (a >> 2) & 1;
  s.depth_write_mask = (a >> 3) & 1;
  s.alpha_func = ALL_COMPARE_FUNCS[(a >> 4) & 7];
  s.stencil_func = ALL_COMPARE_FUNCS[(a >> 7) & 7];
  s.depth_func = ALL_COMPARE_FUNCS[(a >> 10) & 7];
  s.sfail = ALL_STENCIL_OPS[((a >> 13) & 0xff) % ALL_STENCIL_OPS.size()];
  s.dpfail = ALL_STENCIL_OPS[((a >> 21) & 0xff) % ALL_STENCIL_OPS.size()];
  s.dppass = ALL_STENCIL_OPS[((a >> 29) & 0xff) % ALL_STENCIL_OPS.size()];
  s.alpha_ref = unorm8::from_raw(static_cast<uint32_t>(a >> 37));
  s.stencil_ref = stencil8::from_raw(static_cast<uint32_t>(a >> 45));
  s.stencil_value_mask = static_cast<uint8_t>(a >> 53);
  s.stencil_write_mask = static_cast<uint8_t>(w);
  return s;
}

FragmentTestInput random_fragment(VectorRng& rng, const FragmentTestState& state) {
  const uint64_t f = rng();
  FragmentTestInput in;
  in.alpha = ((f >> 61) & 1) != 0 ? state.alpha_ref : unorm8::from_raw(static_cast<uint32_t>(f >> 8));
  in.stored_stencil = stencil8::from_raw(static_cast<uint32_t>(f >> 16));
  in.depth = unorm24::from_raw(static_cast<uint32_t>(f >> 24));
  in.stored_depth = (f >> 62) == 0 ? in.depth : unorm24::from_raw(static_cast<uint32_t>(rng()));
  return in;
}

BlendState random_blend_state(VectorRng& rng) {
  const uint64_t a = rng();
  BlendState s;
  s.blend_enable = (a & 3) != 0;
  s.logic_op_enable = ((a >> 2) & 7) == 0;
  s.src_factor = ALL_BLEND_FACTORS[((a >> 5) & 0xff) % ALL_BLEND_FACTORS.size()];
  s.dst_factor = ALL_BLEND_FACTORS[((a >> 13) & 0xff) % ALL_BLEND_FACTORS.size()];
  s.op = static_cast<LogicOp>((a >> 21) & 15);
  s.color_mask = ((a >> 25) & 3) == 0 ? static_cast<uint8_t>((a >> 27) & 15) : COLOR_MASK_ALL;
  return s;
}

ColourPair random_colour_pair(VectorRng& rng) {
  const uint64_t c = rng();
  return {static_cast<uint32_t>(c), static_cast<uint32_t>(c >> 32)};
}

TextureState random_texture_state(VectorRng& rng) {
  const uint64_t a = rng();
  TextureState st;
  st.base = static_cast<uint32_t>(a >> 32);
  st.log2_width = static_cast<uint8_t>(a % 10);
  st.log2_height = static_cast<uint8_t>((a >> 4) % 10);
  st.wrap_s = ((a >> 8) & 1) != 0 ? TexWrap::clamp_to_edge : TexWrap::repeat;
  st.wrap_t = ((a >> 9) & 1) != 0 ? TexWrap::clamp_to_edge : TexWrap::repeat;
  st.filter = ((a >> 10) & 1) != 0 ? TexFilter::linear : TexFilter::nearest;
  return st;
}

TexCoords random_tex_coords(VectorRng& rng) {
  const uint64_t c = rng();
  const unsigned bits = ((c >> 11) & 7) != 0 ? 20 : 32;
  return {static_cast<int32_t>(sign_extend(c, bits)), static_cast<int32_t>(sign_extend(c >> 32, bits))};
}

TexEnv random_texture_env_mode(VectorRng& rng) {
  return ALL_TEXTURE_ENV_MODES[rng() & 3];
}

TextureEnvLane random_texture_env_lane(VectorRng& rng) {
  const uint64_t a = rng(), c = rng(), d = rng();
  TextureEnvLane lane;
  lane.texel = {static_cast<uint32_t>(a), static_cast<uint32_t>(a >> 32), static_cast<uint32_t>(c),
                static_cast<uint32_t>(c >> 32)};
  lane.weight_s = static_cast<uint8_t>(d >> 8);
  lane.weight_t = static_cast<uint8_t>(d >> 16);
  lane.fragment = static_cast<uint32_t>(d >> 32);
  return lane;
}

FogUnitState random_fog_state(VectorRng& rng) {
  const uint64_t m = rng();
  return {ALL_FOG_MODES[m & 3], Rgba8::unpack(static_cast<uint32_t>(m >> 32))};
}

FogLane random_fog_lane(VectorRng& rng) {
  const uint64_t a = rng();
  FogLane lane;
  lane.argument =
      ((a >> 2) & 1) != 0 ? static_cast<int32_t>(a >> 32) : static_cast<int32_t>((a >> 8) & 0x1fffff) - (1 << 16);
  lane.fragment = static_cast<uint32_t>(rng());
  return lane;
}

LodState LodState::from_code(unsigned code) {
  return {tessera::from_code<TexFilter>(code), tessera::from_code<TexFilter>(code >> 1),
          tessera::from_code<TexMipmap>(code >> 2), (code >> 4) & 15};
}

LodState random_lod_state(VectorRng& rng) {
  return LodState::from_code(static_cast<unsigned>(rng()) % LOD_STATES);
}

uint32_t random_lod_rho(VectorRng& rng) {
  const uint64_t a = rng();
  return static_cast<uint32_t>(a) >> ((a >> 32) & 31);
}

TextureUnitEnv CombinerState::unit() const {
  TextureUnitEnv u;
  u.env = tessera::from_code<TexEnv>(env);
  u.base_format = tessera::from_code<TexBaseFormat>(base_format);
  u.env_color = env_color;
  u.rgb = CombineStage::decode(rgb_word);
  u.alpha = CombineStage::decode(alpha_word);
  return u;
}

CombinerState random_combiner_state(VectorRng& rng) {
  const uint64_t a = rng(), d = rng();
  CombinerState s;
  s.env = (d & 1) != 0 ? 5u : static_cast<uint32_t>(d >> 1) & 7;
  s.base_format = static_cast<uint32_t>(d >> 4) & 7;
  s.env_color = Rgba8::unpack(static_cast<uint32_t>(a));
  s.rgb_word = static_cast<uint32_t>(d >> 8);
  s.alpha_word = static_cast<uint32_t>(d >> 32) ^ static_cast<uint32_t>(a >> 16);
  return s;
}

CombinerLane random_combiner_lane(VectorRng& rng) {
  const uint64_t b = rng(), e = rng();
  return {static_cast<uint32_t>(b), static_cast<uint32_t>(b >> 32), static_cast<uint32_t>(e)};
}

}  // namespace tessera::raster
