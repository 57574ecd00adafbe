// Texel addressing for RGBA8 textures: Verilog reference of
// tlm/raster/datapath/texel_address.h.
//
// Combinational (no latency). s_i and t_i are signed q15.16 texture
// coordinates; log2_width_i / log2_height_i give the power-of-two size
// (values above 8 act as 8); wrap_*_i and filter_i are codes of
// fixed_function_pkg (tex_wrap_e, tex_filter_e, generated from
// contract/common/fixed_function.def), wrap codes without an entry act as REPEAT.
// Per axis: u = coord * N (16 fraction bits, exact); CLAMP_TO_EDGE limits u
// to [1/2, N - 1/2]; LINEAR subtracts 1/2, takes i0 = floor, i1 = i0 + 1 and
// the weight of i1 as the 8 fraction bits below the index (truncated);
// REPEAT masks the indices with N - 1, CLAMP_TO_EDGE limits i1 to N - 1.
// NEAREST gives i1 = i0 and weight 0. Byte addresses: base + ((j << log2 width) + i) * 4
// for (i0,j0), (i1,j0), (i0,j1), (i1,j1), modulo 2^32.
module texel_address (
  input  logic [31:0] s_i,
  input  logic [31:0] t_i,
  input  logic [3:0]  log2_width_i,
  input  logic [3:0]  log2_height_i,
  input  fixed_function_pkg::tex_wrap_e   wrap_s_i,
  input  fixed_function_pkg::tex_wrap_e   wrap_t_i,
  input  fixed_function_pkg::tex_filter_e filter_i,
  input  logic [31:0] base_i,
  output logic [7:0]  i0_o,
  output logic [7:0]  i1_o,
  output logic [7:0]  j0_o,
  output logic [7:0]  j1_o,
  output logic [7:0]  weight_s_o,
  output logic [7:0]  weight_t_o,
  output logic [31:0] addr00_o,
  output logic [31:0] addr10_o,
  output logic [31:0] addr01_o,
  output logic [31:0] addr11_o
);

  // Textures are at most 256 texels wide or high (8-bit texel indices).
  localparam int unsigned MaxLog2 = 8;
  // q15.16 shifted left by up to MaxLog2 places, exactly.
  localparam int unsigned TexelCoordWidth = 32 + MaxLog2;

  // Both axes side by side (s in the low half); flat vectors because
  // yosys 0.23 reads no packed multi-dimensional arrays.
  logic [63:0] coord;
  logic [7:0]  log2_in;
  logic [1:0]  clamp;
  logic        linear;
  logic [15:0] index0, index1, weight;
  logic [3:0]  log2_width;

  assign coord = {t_i, s_i};
  assign log2_in = {log2_height_i, log2_width_i};
  assign clamp = {wrap_t_i == fixed_function_pkg::TexWrapClampToEdge,
                  wrap_s_i == fixed_function_pkg::TexWrapClampToEdge};
  assign linear = filter_i == fixed_function_pkg::TexFilterLinear;

  for (genvar a = 0; a < 2; a++) begin : g_axis
    logic [3:0] log2n;
    logic [8:0] size, size_mask;
    logic signed [TexelCoordWidth-1:0] u, clamp_hi, u_clamped, v;
    logic signed [23:0] i0_full, i1_full;

    assign log2n = (log2_in[4*a +: 4] > 4'(MaxLog2)) ? 4'(MaxLog2) : log2_in[4*a +: 4];
    assign size = 9'd1 << log2n;
    assign size_mask = size - 9'd1;
    assign u = $signed({{MaxLog2{coord[32*a+31]}}, coord[32*a +: 32]}) <<< log2n;
    assign clamp_hi = $signed({15'd0, size, 16'd0}) - 40'sd32768;

    always_comb begin
      u_clamped = u;
      if (clamp[a]) begin
        if (u < 40'sd32768) begin
          u_clamped = 40'sd32768;
        end else if (u > clamp_hi) begin
          u_clamped = clamp_hi;
        end
      end
    end

    assign v = linear ? u_clamped - 40'sd32768 : u_clamped;
    assign i0_full = v[TexelCoordWidth-1:16];
    assign i1_full = linear ? i0_full + 24'sd1 : i0_full;

    always_comb begin
      index0[8*a +: 8] = i0_full[7:0] & size_mask[7:0];
      index1[8*a +: 8] = i1_full[7:0] & size_mask[7:0];
      if (clamp[a]) begin
        index0[8*a +: 8] = i0_full[7:0];
        index1[8*a +: 8] = (i1_full > $signed({15'd0, size_mask})) ? size_mask[7:0] : i1_full[7:0];
      end
    end

    assign weight[8*a +: 8] = linear ? v[15:8] : 8'd0;

    logic unused_axis;
    assign unused_axis = ^{v[7:0], size_mask[8]};
  end

  assign i0_o = index0[7:0];
  assign i1_o = index1[7:0];
  assign j0_o = index0[15:8];
  assign j1_o = index1[15:8];
  assign weight_s_o = weight[7:0];
  assign weight_t_o = weight[15:8];

  assign log2_width = (log2_width_i > 4'(MaxLog2)) ? 4'(MaxLog2) : log2_width_i;

  logic [15:0] texel00, texel10, texel01, texel11;
  assign texel00 = ({8'd0, j0_o} << log2_width) + {8'd0, i0_o};
  assign texel10 = ({8'd0, j0_o} << log2_width) + {8'd0, i1_o};
  assign texel01 = ({8'd0, j1_o} << log2_width) + {8'd0, i0_o};
  assign texel11 = ({8'd0, j1_o} << log2_width) + {8'd0, i1_o};

  assign addr00_o = base_i + {14'd0, texel00, 2'b00};
  assign addr10_o = base_i + {14'd0, texel10, 2'b00};
  assign addr01_o = base_i + {14'd0, texel01, 2'b00};
  assign addr11_o = base_i + {14'd0, texel11, 2'b00};

endmodule
