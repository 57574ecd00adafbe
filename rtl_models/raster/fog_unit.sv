// Fog unit: Verilog reference of tlm/raster/datapath/fog_unit.h (the
// arithmetic of contract/common/fog.h).
//
// Combinational (no latency). argument_i is the fragment's fog argument,
// signed 16.16: the factor f is clamp(a, 0, 1) * 255 rounded (linear),
// 255 * 2^-x with x = max(a, 0) (exp) or x = min(max(a, 0), 4)^2 truncated
// to 16.16 (exp2), and 255 for a mode code without an entry. 2^-x is
// 2^-frac(x) >> floor(x): the table fog_table_pkg::fog_exp2_entry (unsigned
// 0.16, 256 entries indexed by the top 8 fraction bits, generated from
// contract/common/fog_exp2_table.def), shifted right by the integer part (0 from
// 16 on), rounded once to 8 bits: (m * 255 + 2^15) >> 16. Colours are packed
// R [7:0] .. A [31:24]; each of R, G, B is (f Cf + (255 - f) Cfog) / 255
// rounded to nearest exactly, t = x + 128, (t + (t >> 8)) >> 8; alpha is the
// fragment's.
module fog_unit (
  input  fixed_function_pkg::fog_mode_e fog_mode_i,
  input  logic [31:0] argument_i,
  input  logic [31:0] fragment_i,
  input  logic [31:0] fog_color_i,
  output logic [7:0]  factor_o,
  output logic [31:0] rgba_o
);

  // Fraction bits of the fog argument (16.16).
  localparam int unsigned FractionBits = 16;
  // exp2 squares at most 4.0 (19 bits in 16.16): 4^2 = 16 shifts every
  // table entry out.
  localparam logic [18:0] Exp2Limit = 19'd262144;
  // R, G, B are fogged; alpha (index 3) is not.
  localparam int unsigned NumFogged = 3;

  // Negative arguments act as 0 in every mode.
  logic [30:0] positive;
  assign positive = argument_i[31] ? 31'd0 : argument_i[30:0];

  // Linear: clamp to [0, 1.0] (17 bits), scale to 255 and round.
  logic [16:0] linear_a;
  logic [24:0] linear_scaled;
  assign linear_a = (positive > 31'd65536) ? 17'd65536 : positive[16:0];
  assign linear_scaled = {8'd0, linear_a} * 25'd255 + 25'd32768;

  // exp2: the argument clamped to 4.0 and squared, back to 16.16.
  logic [18:0] exp2_a;
  logic [37:0] exp2_square;
  assign exp2_a = (positive > {12'd0, Exp2Limit}) ? Exp2Limit : positive[18:0];
  assign exp2_square = {19'd0, exp2_a} * {19'd0, exp2_a};

  // x of 2^-x: 31 bits for exp, 22 for exp2.
  logic [30:0] x;
  assign x = (fog_mode_i == fixed_function_pkg::FogModeExp2) ? {9'd0, exp2_square[37:FractionBits]} : positive;

  logic [14:0] whole;
  logic [7:0]  index;
  logic [15:0] entry;
  logic [15:0] mantissa;
  logic [23:0] exp_scaled;
  logic [7:0]  exp_factor;
  assign whole = x[30:FractionBits];
  assign index = x[FractionBits-1 -: 8];
  assign entry = fog_table_pkg::fog_exp2_entry(index);
  assign mantissa = (whole >= 15'd16) ? 16'd0 : (entry >> whole[3:0]);
  assign exp_scaled = {8'd0, mantissa} * 24'd255 + 24'd32768;
  assign exp_factor = exp_scaled[23:16];

  logic unused_bits;
  assign unused_bits = ^{linear_scaled[24], linear_scaled[15:0], exp_scaled[15:0], exp2_square[FractionBits-1:0],
                         x[7:0]};

  always_comb begin
    factor_o = 8'd255;
    unique case (fog_mode_i)
      fixed_function_pkg::FogModeLinear: factor_o = linear_scaled[23:16];
      fixed_function_pkg::FogModeExp:    factor_o = exp_factor;
      fixed_function_pkg::FogModeExp2:   factor_o = exp_factor;
      default:                           factor_o = 8'd255;
    endcase
  end

  logic [7:0] inv_factor;
  assign inv_factor = ~factor_o;

  for (genvar c = 0; c < NumFogged; c++) begin : g_channel
    // f Cf + (255 - f) Cfog <= 65025, plus the rounding half: 16 bits.
    logic [15:0] blend_t;
    logic [16:0] blend_q;
    assign blend_t = {8'd0, factor_o} * {8'd0, fragment_i[8*c +: 8]} +
                     {8'd0, inv_factor} * {8'd0, fog_color_i[8*c +: 8]} + 16'd128;
    assign blend_q = {1'b0, blend_t} + {9'd0, blend_t[15:8]};
    assign rgba_o[8*c +: 8] = blend_q[15:8];

    logic unused_blend_bits;
    assign unused_blend_bits = ^{blend_q[16], blend_q[7:0]};
  end
  assign rgba_o[31:24] = fragment_i[31:24];

  logic unused_fog_alpha;
  assign unused_fog_alpha = ^fog_color_i[31:24];

endmodule
