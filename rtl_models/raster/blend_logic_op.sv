// Blending (equation ADD), logical operation and colour write mask on RGBA8:
// Verilog reference of tlm/raster/datapath/blend_logic_op.h.
//
// Combinational (no latency). Colours are packed R in [7:0], G [15:8],
// B [23:16], A [31:24], each unorm 0.8. Blend factors and logic ops are the
// codes of fixed_function_pkg (blend_factor_e, logic_op_e), generated from
// contract/common/fixed_function.def; factor codes without an entry act as ZERO.
// Products are round(a * b / 255), exact: t = a * b + 128,
// (t + (t >> 8)) >> 8; the sum saturates at 255. An enabled logic op
// replaces blending. color_mask_i bit c keeps channel c of dst_i when clear.
module blend_logic_op (
  input  logic [31:0] src_i,
  input  logic [31:0] dst_i,
  input  logic        blend_enable_i,
  input  fixed_function_pkg::blend_factor_e src_factor_i,
  input  fixed_function_pkg::blend_factor_e dst_factor_i,
  input  logic        logic_op_enable_i,
  input  fixed_function_pkg::logic_op_e     logic_op_i,
  input  logic [3:0]  color_mask_i,
  output logic [31:0] rgba_o
);

  // RGBA: the alpha channel (index 3) differs only in SRC_ALPHA_SATURATE.
  localparam int unsigned NumChannels = 4;

  function automatic logic [7:0] factor(input fixed_function_pkg::blend_factor_e code,
                                        input logic [7:0] s, input logic [7:0] d,
                                        input logic [7:0] src_alpha, input logic [7:0] dst_alpha,
                                        input logic is_alpha);
    // Assigned through the function name: yosys 0.23 has no `return`.
    factor = 8'd0;
    unique case (code)
      fixed_function_pkg::BlendFactorZero:             factor = 8'd0;
      fixed_function_pkg::BlendFactorOne:              factor = 8'd255;
      fixed_function_pkg::BlendFactorSrcColor:         factor = s;
      fixed_function_pkg::BlendFactorOneMinusSrcColor: factor = ~s;
      fixed_function_pkg::BlendFactorSrcAlpha:         factor = src_alpha;
      fixed_function_pkg::BlendFactorOneMinusSrcAlpha: factor = ~src_alpha;
      fixed_function_pkg::BlendFactorDstAlpha:         factor = dst_alpha;
      fixed_function_pkg::BlendFactorOneMinusDstAlpha: factor = ~dst_alpha;
      fixed_function_pkg::BlendFactorDstColor:         factor = d;
      fixed_function_pkg::BlendFactorOneMinusDstColor: factor = ~d;
      fixed_function_pkg::BlendFactorSrcAlphaSaturate:
        factor = is_alpha ? 8'd255 : ((src_alpha < ~dst_alpha) ? src_alpha : ~dst_alpha);
      default: factor = 8'd0;
    endcase
  endfunction

  function automatic logic [7:0] logic_result(input fixed_function_pkg::logic_op_e op,
                                              input logic [7:0] s, input logic [7:0] d);
    logic_result = 8'd0;
    unique case (op)
      fixed_function_pkg::LogicOpClear:        logic_result = 8'd0;
      fixed_function_pkg::LogicOpAnd:          logic_result = s & d;
      fixed_function_pkg::LogicOpAndReverse:   logic_result = s & ~d;
      fixed_function_pkg::LogicOpCopy:         logic_result = s;
      fixed_function_pkg::LogicOpAndInverted:  logic_result = ~s & d;
      fixed_function_pkg::LogicOpNoop:         logic_result = d;
      fixed_function_pkg::LogicOpXor:          logic_result = s ^ d;
      fixed_function_pkg::LogicOpOr:           logic_result = s | d;
      fixed_function_pkg::LogicOpNor:          logic_result = ~(s | d);
      fixed_function_pkg::LogicOpEquiv:        logic_result = ~(s ^ d);
      fixed_function_pkg::LogicOpInvert:       logic_result = ~d;
      fixed_function_pkg::LogicOpOrReverse:    logic_result = s | ~d;
      fixed_function_pkg::LogicOpCopyInverted: logic_result = ~s;
      fixed_function_pkg::LogicOpOrInverted:   logic_result = ~s | d;
      fixed_function_pkg::LogicOpNand:         logic_result = ~(s & d);
      fixed_function_pkg::LogicOpSet:          logic_result = 8'hff;
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
