// Bilinear texel filter and texture environment: Verilog reference of
// tlm/raster/datapath/texture_env.h.
//
// Combinational (no latency). Colours are packed R [7:0] .. A [31:24], unorm
// 0.8. texel00_i .. texel11_i are the texels (i0,j0), (i1,j0), (i0,j1),
// (i1,j1); weight_s_i / weight_t_i the weights of i1 / j1 in 1/256 (0 for
// NEAREST, which then returns texel00_i). Each filtered channel is
// (sum w * texel + 2^15) >> 16 with w00 = (256-a)(256-b), w10 = a(256-b),
// w01 = (256-a)b, w11 = ab. env_mode_i is a code of fixed_function_pkg
// (tex_env_e, generated from contract/common/fixed_function.def); codes other
// than REPLACE, MODULATE and DECAL (those of texture_combiner.sv, and those
// without an entry) pass fragment_i through. Products are divided by 255 with exact
// rounding: t = x + 128, (t + (t >> 8)) >> 8.
module texture_env (
  input  logic [31:0] texel00_i,
  input  logic [31:0] texel10_i,
  input  logic [31:0] texel01_i,
  input  logic [31:0] texel11_i,
  input  logic [7:0]  weight_s_i,
  input  logic [7:0]  weight_t_i,
  input  logic [31:0] fragment_i,
  input  fixed_function_pkg::tex_env_e env_mode_i,
  output logic [31:0] texel_o,
  output logic [31:0] rgba_o
);

  // RGBA: DECAL treats the alpha channel (index 3) differently.
  localparam int unsigned NumChannels = 4;

  // Bilinear weights, 17 bits: (256 - 0) * (256 - 0) = 2^16.
  logic [8:0]  inv_s, inv_t;
  logic [16:0] w00, w10, w01, w11;
  assign inv_s = 9'd256 - {1'b0, weight_s_i};
  assign inv_t = 9'd256 - {1'b0, weight_t_i};
  // Operands are widened explicitly rather than through casts, so that every
  // tool sizes the products alike.
  assign w00 = {8'd0, inv_s} * {8'd0, inv_t};
  assign w10 = {9'd0, weight_s_i} * {8'd0, inv_t};
  assign w01 = {8'd0, inv_s} * {9'd0, weight_t_i};
  assign w11 = {9'd0, weight_s_i} * {9'd0, weight_t_i};

  logic [7:0] texel_alpha, texel_alpha_inv;
  assign texel_alpha = texel_o[31:24];
  assign texel_alpha_inv = ~texel_alpha;

  for (genvar c = 0; c < NumChannels; c++) begin : g_channel
    // sum of w * texel <= 2^16 * 255, plus the rounding half: 24 bits.
    logic [24:0] filter_sum;
    assign filter_sum = {8'd0, w00} * {17'd0, texel00_i[8*c +: 8]} +
                        {8'd0, w10} * {17'd0, texel10_i[8*c +: 8]} +
                        {8'd0, w01} * {17'd0, texel01_i[8*c +: 8]} +
                        {8'd0, w11} * {17'd0, texel11_i[8*c +: 8]} + 25'd32768;
    assign texel_o[8*c +: 8] = filter_sum[23:16];

    logic [7:0] f, t;
    assign f = fragment_i[8*c +: 8];
    assign t = texel_o[8*c +: 8];

    // x / 255 rounded: x <= 65025, x + 128 + ((x + 128) >> 8) < 2^16.
    logic [15:0] modulate_x, decal_x, modulate_t, decal_t;
    logic [16:0] modulate_q, decal_q;
    assign modulate_x = {8'd0, f} * {8'd0, t};
    assign decal_x = {8'd0, f} * {8'd0, texel_alpha_inv} + {8'd0, t} * {8'd0, texel_alpha};
    assign modulate_t = modulate_x + 16'd128;
    assign decal_t = decal_x + 16'd128;
    assign modulate_q = {1'b0, modulate_t} + {9'd0, modulate_t[15:8]};
    assign decal_q = {1'b0, decal_t} + {9'd0, decal_t[15:8]};

    logic unused_low_bits;
    assign unused_low_bits = ^{filter_sum[24], filter_sum[15:0], modulate_q[16], modulate_q[7:0],
                               decal_q[16], decal_q[7:0]};

    always_comb begin
      rgba_o[8*c +: 8] = f;
      unique case (env_mode_i)
        fixed_function_pkg::TexEnvReplace:  rgba_o[8*c +: 8] = t;
        fixed_function_pkg::TexEnvModulate: rgba_o[8*c +: 8] = modulate_q[15:8];
        fixed_function_pkg::TexEnvDecal:    rgba_o[8*c +: 8] = (c == 3) ? f : decal_q[15:8];
        default: rgba_o[8*c +: 8] = f;
      endcase
    end
  end

endmodule
