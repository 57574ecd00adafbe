// Blending (equation ADD), logical operation and colour write mask on RGBA8:
// Verilog reference of tlm/raster/datapath/blend_logic_op.h.
//
// Combinational (no latency). Colours are packed R in [7:0], G [15:8],
// B [23:16], A [31:24], each unorm 0.8. Factor codes: ZERO 0, ONE 1,
// SRC_COLOR 2, ONE_MINUS_SRC_COLOR 3, SRC_ALPHA 4, ONE_MINUS_SRC_ALPHA 5,
// DST_ALPHA 6, ONE_MINUS_DST_ALPHA 7, DST_COLOR 8, ONE_MINUS_DST_COLOR 9,
// SRC_ALPHA_SATURATE 10 (GL enum - 0x0300 + 2), 11..15 act as ZERO.
// Products are round(a * b / 255), exact: t = a * b + 128,
// (t + (t >> 8)) >> 8; the sum saturates at 255. Logic op codes are the GL
// enum minus 0x1500 (CLEAR 0 .. SET 15); an enabled logic op replaces
// blending. color_mask_i bit c keeps channel c of dst_i when clear.
module blend_logic_op (
  input  logic [31:0] src_i,
  input  logic [31:0] dst_i,
  input  logic        blend_enable_i,
  input  logic [3:0]  src_factor_i,
  input  logic [3:0]  dst_factor_i,
  input  logic        logic_op_enable_i,
  input  logic [3:0]  logic_op_i,
  input  logic [3:0]  color_mask_i,
  output logic [31:0] rgba_o
);

  // RGBA: the alpha channel (index 3) differs only in SRC_ALPHA_SATURATE.
  localparam int unsigned NumChannels = 4;

  function automatic logic [7:0] factor(input logic [3:0] code, input logic [7:0] s,
                                        input logic [7:0] d, input logic [7:0] src_alpha,
                                        input logic [7:0] dst_alpha, input logic is_alpha);
    // Assigned through the function name: yosys 0.23 has no `return`.
    factor = 8'd0;
    unique case (code)
      4'd0:  factor = 8'd0;
      4'd1:  factor = 8'd255;
      4'd2:  factor = s;
      4'd3:  factor = ~s;
      4'd4:  factor = src_alpha;
      4'd5:  factor = ~src_alpha;
      4'd6:  factor = dst_alpha;
      4'd7:  factor = ~dst_alpha;
      4'd8:  factor = d;
      4'd9:  factor = ~d;
      4'd10: factor = is_alpha ? 8'd255 : ((src_alpha < ~dst_alpha) ? src_alpha : ~dst_alpha);
      default: factor = 8'd0;
    endcase
  endfunction

  function automatic logic [7:0] logic_result(input logic [3:0] op, input logic [7:0] s,
                                              input logic [7:0] d);
    logic_result = 8'd0;
    unique case (op)
      4'd0:  logic_result = 8'd0;
      4'd1:  logic_result = s & d;
      4'd2:  logic_result = s & ~d;
      4'd3:  logic_result = s;
      4'd4:  logic_result = ~s & d;
      4'd5:  logic_result = d;
      4'd6:  logic_result = s ^ d;
      4'd7:  logic_result = s | d;
      4'd8:  logic_result = ~(s | d);
      4'd9:  logic_result = ~(s ^ d);
      4'd10: logic_result = ~d;
      4'd11: logic_result = s | ~d;
      4'd12: logic_result = ~s;
      4'd13: logic_result = ~s | d;
      4'd14: logic_result = ~(s & d);
      4'd15: logic_result = 8'hff;
      default: logic_result = 8'd0;
    endcase
  endfunction

  for (genvar c = 0; c < NumChannels; c++) begin : g_channel
    logic [7:0] s, d, src_weight, dst_weight;
    logic [15:0] src_t, dst_t;
    logic [16:0] src_q, dst_q;
    logic [8:0] sum;
    logic [7:0] blended, result;

    assign s = src_i[8*c +: 8];
    assign d = dst_i[8*c +: 8];
    assign src_weight = factor(src_factor_i, s, d, src_i[31:24], dst_i[31:24], c == 3);
    assign dst_weight = factor(dst_factor_i, s, d, src_i[31:24], dst_i[31:24], c == 3);

    // round(x * w / 255): a * b + 128 <= 65153 fits 16 bits; t + (t >> 8)
    // needs 17.
    assign src_t = s * src_weight + 16'd128;
    assign dst_t = d * dst_weight + 16'd128;
    assign src_q = {1'b0, src_t} + {9'd0, src_t[15:8]};
    assign dst_q = {1'b0, dst_t} + {9'd0, dst_t[15:8]};
    assign sum = {1'b0, src_q[15:8]} + {1'b0, dst_q[15:8]};
    assign blended = sum[8] ? 8'hff : sum[7:0];

    logic unused_low_bits;
    assign unused_low_bits = ^{src_q[16], src_q[7:0], dst_q[16], dst_q[7:0]};

    always_comb begin
      result = s;
      if (logic_op_enable_i) begin
        result = logic_result(logic_op_i, s, d);
      end else if (blend_enable_i) begin
        result = blended;
      end
    end

    assign rgba_o[8*c +: 8] = color_mask_i[c] ? result : d;
  end

endmodule
