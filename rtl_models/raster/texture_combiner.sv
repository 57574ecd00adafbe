// Texture combiner of one texture unit: Verilog reference of
// tlm/raster/datapath/texture_combiner.h (OpenGL ES 1.1 section 3.7.12,
// tables 3.15 to 3.18).
//
// Combinational (no latency). Colours are packed R [7:0] .. A [31:24], unorm
// 0.8. previous_i is the previous unit's result (the interpolated colour for
// the first unit), primary_i the interpolated colour, texel_i the filtered
// texel as stored (missing components expanded), env_color_i
// GL_TEXTURE_ENV_COLOR. env_i and base_format_i are codes of
// fixed_function_pkg (tex_env_e, tex_base_format_e); combine_rgb_i and
// combine_alpha_i are TextureUnitState's words: function bits 2:0 (bit 3
// ignored), source k at 4+4k, operand k at 16+4k (2 bits each), log2 scale
// at 29:28. Every mode's result is computed per channel and the code picks
// one (codes 6 and 7: previous_i passes). Products of 0.8 codes are divided
// by 255 with exact rounding, t = x + 128, (t + (t >> 8)) >> 8; a combiner
// function's value is exact in units of 1/510 of a code, shifted by the
// scale, then floor((n + 255) / 510) clamped to 0 .. 255, the division as
// floor(h / 255) = (h + 1 + ((h + 1) >> 8)) >> 8 on h = (n + 255) >> 1.
module texture_combiner (
  input  fixed_function_pkg::tex_env_e         env_i,
  input  fixed_function_pkg::tex_base_format_e base_format_i,
  input  logic [31:0] primary_i,
  input  logic [31:0] previous_i,
  input  logic [31:0] texel_i,
  input  logic [31:0] env_color_i,
  input  logic [31:0] combine_rgb_i,
  input  logic [31:0] combine_alpha_i,
  output logic [31:0] rgba_o
);
  localparam int unsigned NumColour = 3;
  localparam int unsigned NumArgs = 3;
  // Signed width of a combiner value: |2 * 3 * 255 * 255 * 8| < 2^22.
  localparam int unsigned ValueBits = 24;

  // The two dividers keep bits 15:8 of their sums; the others are unused by
  // construction.
  /* verilator lint_off UNUSEDSIGNAL */
  // round(x / 255) for x <= 65025.
  function automatic logic [7:0] div255(input logic [15:0] x);
    logic [15:0] t;
    logic [16:0] q;
    t = x + 16'd128;
    q = {1'b0, t} + {9'd0, t[15:8]};
    div255 = q[15:8];
  endfunction

  // floor((n + 255) / 510) clamped to 0 .. 255.
  function automatic logic [7:0] combine_round(input logic signed [ValueBits-1:0] n);
    logic signed [ValueBits-1:0] m;
    logic [16:0] h1;
    logic [17:0] q;
    m = n + ValueBits'(255);
    h1 = {1'b0, m[16:1]} + 17'd1;
    q = {1'b0, h1} + {9'd0, h1[16:8]};
    if (m[ValueBits-1]) combine_round = 8'd0;
    else if (m >= ValueBits'(256 * 510)) combine_round = 8'd255;
    else combine_round = q[15:8];
  endfunction
  /* verilator lint_on UNUSEDSIGNAL */

  // The stages' fields.
  logic [fixed_function_pkg::CombineFuncBits-1:0] rgb_func, alpha_func;
  logic [1:0] rgb_scale, alpha_scale;
  logic [1:0] rgb_source[NumArgs], alpha_source[NumArgs], rgb_operand[NumArgs], alpha_operand[NumArgs];
  assign rgb_func = combine_rgb_i[fixed_function_pkg::CombineFuncBits-1:0];
  assign alpha_func = combine_alpha_i[fixed_function_pkg::CombineFuncBits-1:0];
  assign rgb_scale = combine_rgb_i[29:28];
  assign alpha_scale = combine_alpha_i[29:28];
  for (genvar k = 0; k < NumArgs; k++) begin : g_fields
    assign rgb_source[k] = combine_rgb_i[4+4*k +: 2];
    assign alpha_source[k] = combine_alpha_i[4+4*k +: 2];
    assign rgb_operand[k] = combine_rgb_i[16+4*k +: 2];
    assign alpha_operand[k] = combine_alpha_i[16+4*k +: 2];
  end

  logic unused_word_bits;
  assign unused_word_bits = ^{combine_rgb_i[31:30], combine_rgb_i[27:26], combine_rgb_i[23:22],
                              combine_rgb_i[19:18], combine_rgb_i[15:14], combine_rgb_i[11:10],
                              combine_rgb_i[7:fixed_function_pkg::CombineFuncBits], combine_alpha_i[31:30], combine_alpha_i[27:26],
                              combine_alpha_i[23:22], combine_alpha_i[19:18], combine_alpha_i[15:14],
                              combine_alpha_i[11:10], combine_alpha_i[7:fixed_function_pkg::CombineFuncBits]};

  // Sources by CombineSource code: texture, constant, primary, previous.
  logic [31:0] sources[4];
  assign sources[0] = texel_i;
  assign sources[1] = env_color_i;
  assign sources[2] = primary_i;
  assign sources[3] = previous_i;

  function automatic logic [7:0] argument(input logic [1:0] source, input logic [1:0] operand,
                                          input logic [1:0] channel, input logic [31:0] s0,
                                          input logic [31:0] s1, input logic [31:0] s2, input logic [31:0] s3);
    logic [31:0] colour;
    logic [7:0] x;
    unique case (source)
      2'd0: colour = s0;
      2'd1: colour = s1;
      2'd2: colour = s2;
      default: colour = s3;
    endcase
    x = operand[1] ? colour[31:24] : colour[8*channel +: 8];
    argument = operand[0] ? ~x : x;
  endfunction

  // The function's value in 1/510 of a code, DOT3 codes 0.
  function automatic logic signed [ValueBits-1:0] combine_value(input logic [fixed_function_pkg::CombineFuncBits-1:0] func,
                                                                input logic [7:0] a0, input logic [7:0] a1,
                                                                input logic [7:0] a2);
    logic signed [ValueBits-1:0] s0, s1, s2;
    s0 = ValueBits'(a0);
    s1 = ValueBits'(a1);
    s2 = ValueBits'(a2);
    unique case (func)
      fixed_function_pkg::CombineFuncReplace:     combine_value = s0 * ValueBits'(510);
      fixed_function_pkg::CombineFuncModulate:    combine_value = (s0 * s1) <<< 1;
      fixed_function_pkg::CombineFuncAdd:         combine_value = (s0 + s1) * ValueBits'(510);
      fixed_function_pkg::CombineFuncAddSigned:   combine_value = (s0 + s1) * ValueBits'(510) - ValueBits'(65025);
      fixed_function_pkg::CombineFuncInterpolate: combine_value = (s0 * s2 + s1 * (ValueBits'(255) - s2)) <<< 1;
      fixed_function_pkg::CombineFuncSubtract:    combine_value = (s0 - s1) * ValueBits'(510);
      default:                combine_value = '0;
    endcase
  endfunction

  logic no_alpha, no_colour;
  assign no_alpha = base_format_i == fixed_function_pkg::TexBaseFormatRgb || base_format_i == fixed_function_pkg::TexBaseFormatLuminance;
  assign no_colour = base_format_i == fixed_function_pkg::TexBaseFormatAlpha;

  logic [7:0] fa, ta, alpha_product;
  assign fa = previous_i[31:24];
  assign ta = texel_i[31:24];
  assign alpha_product = div255({8'd0, fa} * {8'd0, ta});

  logic [31:0] replace_rgba, modulate_rgba, decal_rgba, blend_rgba, add_rgba, combine_rgba;
  logic signed [ValueBits-1:0] dot_term[NumColour];

  for (genvar c = 0; c < NumColour; c++) begin : g_colour
    logic [7:0] fc, tc, cc;
    logic [8:0] sum;
    assign fc = previous_i[8*c +: 8];
    assign tc = texel_i[8*c +: 8];
    assign cc = env_color_i[8*c +: 8];
    assign sum = {1'b0, fc} + {1'b0, tc};
    assign replace_rgba[8*c +: 8] = no_colour ? fc : tc;
    assign modulate_rgba[8*c +: 8] = no_colour ? fc : div255({8'd0, fc} * {8'd0, tc});
    assign decal_rgba[8*c +: 8] = div255({8'd0, fc} * {8'd0, ~ta} + {8'd0, tc} * {8'd0, ta});
    assign blend_rgba[8*c +: 8] = div255({8'd0, fc} * {8'd0, ~tc} + {8'd0, cc} * {8'd0, tc});
    assign add_rgba[8*c +: 8] = sum[8] ? 8'd255 : sum[7:0];

    logic [7:0] a0, a1, a2;
    assign a0 = argument(rgb_source[0], rgb_operand[0], 2'(c), sources[0], sources[1], sources[2], sources[3]);
    assign a1 = argument(rgb_source[1], rgb_operand[1], 2'(c), sources[0], sources[1], sources[2], sources[3]);
    assign a2 = argument(rgb_source[2], rgb_operand[2], 2'(c), sources[0], sources[1], sources[2], sources[3]);
    // (2 a0 - 255)(2 a1 - 255), each factor in -255 .. 255.
    assign dot_term[c] = ((ValueBits'(a0) <<< 1) - ValueBits'(255)) * ((ValueBits'(a1) <<< 1) - ValueBits'(255));
    assign combine_rgba[8*c +: 8] = combine_round(combine_value(rgb_func, a0, a1, a2) <<< rgb_scale);
  end

  assign replace_rgba[31:24] = no_alpha ? fa : ta;
  assign modulate_rgba[31:24] = alpha_product;
  assign decal_rgba[31:24] = fa;
  assign blend_rgba[31:24] = alpha_product;
  assign add_rgba[31:24] = alpha_product;

  logic signed [ValueBits-1:0] dot;
  logic [7:0] dot_rgb, dot_alpha, stage_alpha, alpha_a0, alpha_a1, alpha_a2;
  logic is_dot3;
  assign dot = (dot_term[0] + dot_term[1] + dot_term[2]) <<< 1;
  assign dot_rgb = combine_round(dot <<< rgb_scale);
  assign dot_alpha = combine_round(dot <<< alpha_scale);
  assign alpha_a0 = argument(alpha_source[0], alpha_operand[0], 2'd3, sources[0], sources[1], sources[2], sources[3]);
  assign alpha_a1 = argument(alpha_source[1], alpha_operand[1], 2'd3, sources[0], sources[1], sources[2], sources[3]);
  assign alpha_a2 = argument(alpha_source[2], alpha_operand[2], 2'd3, sources[0], sources[1], sources[2], sources[3]);
  assign stage_alpha = combine_round(combine_value(alpha_func, alpha_a0, alpha_a1, alpha_a2) <<< alpha_scale);
  assign is_dot3 = rgb_func == fixed_function_pkg::CombineFuncDot3Rgb || rgb_func == fixed_function_pkg::CombineFuncDot3Rgba;
  assign combine_rgba[31:24] = rgb_func == fixed_function_pkg::CombineFuncDot3Rgba ? dot_alpha : stage_alpha;

  logic [31:0] combine_out;
  assign combine_out = is_dot3 ? {combine_rgba[31:24], dot_rgb, dot_rgb, dot_rgb} : combine_rgba;

  always_comb begin
    unique case (env_i)
      fixed_function_pkg::TexEnvReplace:  rgba_o = replace_rgba;
      fixed_function_pkg::TexEnvModulate: rgba_o = modulate_rgba;
      fixed_function_pkg::TexEnvDecal:    rgba_o = decal_rgba;
      fixed_function_pkg::TexEnvBlend:    rgba_o = blend_rgba;
      fixed_function_pkg::TexEnvAdd:      rgba_o = add_rgba;
      fixed_function_pkg::TexEnvCombine:  rgba_o = combine_out;
      default:        rgba_o = previous_i;
    endcase
  end

endmodule
