// Level-of-detail unit: Verilog reference of
// tlm/raster/datapath/lod_unit.h.
//
// Combinational (no latency). rho_i is the scale factor, unsigned 16.16
// texels per pixel. lambda_o = log2(rho) signed with 8 fraction bits
// (-16.0 for rho = 0): the leading one's position e gives the integer part
// e - 16, the mantissa m (1.15, the 16 bits from the leading one down,
// truncated) gives 10 fraction bits by repeated squaring (m^2 >= 2: bit 1
// and m^2 / 2 goes on, else bit 0 and m^2; each square truncated to 1.15),
// and the 10-bit result is rounded to 8 bits (ties up). Minified when
// rho > 2^16 (lambda > 0), or rho > 92681 (lambda > 1/2, sqrt 2 = 92681.9 /
// 2^16) for mag LINEAR with min NEAREST and a mipmap choice (GL's c = 1/2);
// linear_o is then the minification filter, else the magnification one.
// Levels (q = last_level_i): magnified, or mipmap none (or code 3): level 0.
// Nearest: (L + 127) >> 8 for lambda L (1/256) above 128, else 0, at most
// q. Linear: q alone for L >= q * 256, else floor(L) and the next with the
// weight L[7:0] of the second (L below 0 as 0); weight 0 is one level.
// Codes are fixed_function_pkg's (tex_filter_e, tex_mipmap_e), generated
// from contract/common/fixed_function.def.
module lod_unit (
  input  logic [31:0] rho_i,
  input  fixed_function_pkg::tex_filter_e min_filter_i,
  input  fixed_function_pkg::tex_filter_e mag_filter_i,
  input  fixed_function_pkg::tex_mipmap_e mipmap_i,
  input  logic [3:0]  last_level_i,
  output logic [13:0] lambda_o,
  output logic        minified_o,
  output logic        linear_o,
  output logic [3:0]  level0_o,
  output logic [3:0]  level1_o,
  output logic        two_levels_o,
  output logic [7:0]  weight_o
);

  // Fraction bits of log2(m) before rounding, and of lambda.
  localparam int unsigned Iterations = 10;
  localparam int unsigned FractionBits = 8;
  // rho of lambda = 0 and the largest rho with lambda <= 1/2.
  localparam logic [31:0] RhoOne = 32'd65536;
  localparam logic [31:0] RhoSqrt2Floor = 32'd92681;

  // Leading one: e = 31 - leading zeros (0 for rho = 0, handled apart).
  logic [4:0] e;
  always_comb begin
    e = 5'd0;
    for (int b = 0; b < 32; b++) begin
      if (rho_i[b]) e = 5'(b);
    end
  end

  // The mantissa as 1.15: the leading one at bit 15.
  logic [62:0] shifted;
  logic [15:0] m0;
  assign shifted = {31'd0, rho_i} << (5'd31 - e);
  assign m0 = shifted[31:16];

  // Repeated squaring, one fraction bit per stage (a chain of Iterations
  // 16 x 16 multipliers).
  logic [15:0] m;
  logic [31:0] square;
  logic [Iterations-1:0] fraction;
  always_comb begin
    m = m0;
    square = 32'd0;
    fraction = '0;
    for (int i = 0; i < Iterations; i++) begin
      square = {16'd0, m} * {16'd0, m};
      fraction[Iterations-1-i] = square[31];
      m = square[31] ? square[31:16] : square[30:15];
    end
  end

  // (e - 16) . fraction, 16 bits signed, rounded to 8 fraction bits:
  // -4096 .. 4096 (16.0 for rho just below 2^32), 14 bits.
  logic signed [15:0] raw;
  logic signed [15:0] rounded;
  assign raw = {1'b0, e, fraction} - 16'sd16384;
  assign rounded = (raw + 16'sd2) >>> 2;
  logic signed [13:0] lambda;
  assign lambda = (rho_i == 32'd0) ? -14'sd4096 : rounded[13:0];
  assign lambda_o = lambda;

  // The switch point and the within-level filter.
  logic mipmapped;
  logic half;
  assign mipmapped = (mipmap_i == fixed_function_pkg::TexMipmapNearest) ||
                     (mipmap_i == fixed_function_pkg::TexMipmapLinear);
  assign half = (mag_filter_i == fixed_function_pkg::TexFilterLinear) &&
                (min_filter_i == fixed_function_pkg::TexFilterNearest) && mipmapped;
  assign minified_o = rho_i > (half ? RhoSqrt2Floor : RhoOne);
  assign linear_o = minified_o ? (min_filter_i == fixed_function_pkg::TexFilterLinear)
                               : (mag_filter_i == fixed_function_pkg::TexFilterLinear);

  // Levels from L = max(lambda, 0), 13 bits (at most 16 * 256).
  logic [12:0] l;
  logic [4:0]  q;
  assign l = lambda[13] ? 13'd0 : lambda[12:0];
  assign q = {1'b0, last_level_i};

  logic [12:0] l_plus;
  logic [4:0]  nearest_raw;
  logic [4:0]  nearest;
  assign l_plus = l + 13'd127;
  assign nearest_raw = (l > 13'd128) ? l_plus[12:FractionBits] : 5'd0;
  assign nearest = (nearest_raw > q) ? q : nearest_raw;

  logic       below_q;
  logic [4:0] floor_level;
  logic [7:0] weight;
  assign below_q = l < {q, 8'd0};
  assign floor_level = below_q ? l[12:FractionBits] : q;
  assign weight = below_q ? l[FractionBits-1:0] : 8'd0;

  logic use_nearest;
  logic use_linear;
  logic [4:0] level0;
  assign use_nearest = minified_o && (mipmap_i == fixed_function_pkg::TexMipmapNearest);
  assign use_linear = minified_o && (mipmap_i == fixed_function_pkg::TexMipmapLinear);
  assign level0 = use_nearest ? nearest : (use_linear ? floor_level : 5'd0);
  assign weight_o = use_linear ? weight : 8'd0;
  assign two_levels_o = use_linear && (weight != 8'd0);
  assign level0_o = level0[3:0];
  assign level1_o = level0[3:0] + (two_levels_o ? 4'd1 : 4'd0);

  // Bits the unit does not use: the shifted-out and cut parts of the
  // mantissa and squares, the last mantissa, the rounding's top bits, the
  // low bits of L + 127, and the top of the chosen level (at most q <= 15).
  logic unused_bits;
  assign unused_bits = ^{shifted[62:32], shifted[15:0], m, square[14:0], rounded[15:14], l_plus[7:0], level0[4]};

endmodule
