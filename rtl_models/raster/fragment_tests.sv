// Per-fragment alpha, stencil and depth tests: Verilog reference of
// tlm/raster/datapath/fragment_tests.h.
//
// Combinational (no latency). Compare functions and stencil operations are
// the codes of fixed_function_pkg (compare_func_e, stencil_op_e), generated
// from contract/common/fixed_function.def; stencil codes without an entry keep the
// stored value. The incoming value is the left operand of a compare:
// alpha_i func alpha_ref_i, (stencil_ref_i & mask) func (stencil_i & mask),
// depth_i func stored_depth_i. INCR and DECR saturate. stencil_o is the value
// to store (through stencil_write_mask_i); depth_we_o says whether depth_i is
// to be stored. GL 1.2 sequencing is described in fragment_tests.h.
module fragment_tests (
  input  logic        alpha_enable_i,
  input  fixed_function_pkg::compare_func_e alpha_func_i,
  input  logic [7:0]  alpha_ref_i,
  input  logic [7:0]  alpha_i,
  input  logic        stencil_enable_i,
  input  fixed_function_pkg::compare_func_e stencil_func_i,
  input  logic [7:0]  stencil_ref_i,
  input  logic [7:0]  stencil_value_mask_i,
  input  logic [7:0]  stencil_write_mask_i,
  input  fixed_function_pkg::stencil_op_e   stencil_sfail_i,
  input  fixed_function_pkg::stencil_op_e   stencil_dpfail_i,
  input  fixed_function_pkg::stencil_op_e   stencil_dppass_i,
  input  logic [7:0]  stencil_i,
  input  logic        depth_enable_i,
  input  fixed_function_pkg::compare_func_e depth_func_i,
  input  logic        depth_write_mask_i,
  input  logic [23:0] depth_i,
  input  logic [23:0] stored_depth_i,
  output logic        alpha_pass_o,
  output logic        stencil_pass_o,
  output logic        depth_pass_o,
  output logic        pass_o,
  output logic [7:0]  stencil_o,
  output logic        depth_we_o
);

  // The widest compared quantity is depth (0.24); alpha and stencil are
  // zero-extended to it so that one comparator function serves all three.
  localparam int unsigned CompareWidth = 24;

  function automatic logic compare(input fixed_function_pkg::compare_func_e func,
                                   input logic [CompareWidth-1:0] incoming,
                                   input logic [CompareWidth-1:0] stored);
    // Assigned through the function name: yosys 0.23 has no `return`.
    compare = 1'b0;
    unique case (func)
      fixed_function_pkg::CompareFuncNever:    compare = 1'b0;
      fixed_function_pkg::CompareFuncLess:     compare = incoming < stored;
      fixed_function_pkg::CompareFuncEqual:    compare = incoming == stored;
      fixed_function_pkg::CompareFuncLequal:   compare = incoming <= stored;
      fixed_function_pkg::CompareFuncGreater:  compare = incoming > stored;
      fixed_function_pkg::CompareFuncNotequal: compare = incoming != stored;
      fixed_function_pkg::CompareFuncGequal:   compare = incoming >= stored;
      fixed_function_pkg::CompareFuncAlways:   compare = 1'b1;
      default: compare = 1'b0;
    endcase
  endfunction

  logic alpha_compare, stencil_compare, depth_compare;
  assign alpha_compare = compare(alpha_func_i, {16'd0, alpha_i}, {16'd0, alpha_ref_i});
  assign stencil_compare = compare(stencil_func_i, {16'd0, stencil_ref_i & stencil_value_mask_i},
                                   {16'd0, stencil_i & stencil_value_mask_i});
  assign depth_compare = compare(depth_func_i, depth_i, stored_depth_i);

  logic alpha_pass, stencil_pass, depth_pass;
  assign alpha_pass = !alpha_enable_i || alpha_compare;
  assign stencil_pass = !stencil_enable_i || stencil_compare;
  assign depth_pass = !depth_enable_i || depth_compare;

  assign alpha_pass_o = alpha_pass;
  assign stencil_pass_o = stencil_pass;
  assign depth_pass_o = depth_pass;
  assign pass_o = alpha_pass && stencil_pass && depth_pass;
  assign depth_we_o = alpha_pass && stencil_pass && depth_pass && depth_enable_i && depth_write_mask_i;

  fixed_function_pkg::stencil_op_e op;
  always_comb begin
    op = stencil_dppass_i;
    if (!stencil_pass) begin
      op = stencil_sfail_i;
    end else if (!depth_pass) begin
      op = stencil_dpfail_i;
    end
  end

  logic [7:0] op_result;
  always_comb begin
    op_result = stencil_i;
    unique case (op)
      fixed_function_pkg::StencilOpKeep:    op_result = stencil_i;
      fixed_function_pkg::StencilOpZero:    op_result = 8'd0;
      fixed_function_pkg::StencilOpReplace: op_result = stencil_ref_i;
      fixed_function_pkg::StencilOpIncr:    op_result = (stencil_i == 8'hff) ? 8'hff : stencil_i + 8'd1;
      fixed_function_pkg::StencilOpDecr:    op_result = (stencil_i == 8'h00) ? 8'h00 : stencil_i - 8'd1;
      fixed_function_pkg::StencilOpInvert:  op_result = ~stencil_i;
      default: op_result = stencil_i;
    endcase
  end

  always_comb begin
    stencil_o = stencil_i;
    if (alpha_pass && stencil_enable_i) begin
      stencil_o = (stencil_i & ~stencil_write_mask_i) | (op_result & stencil_write_mask_i);
    end
  end

endmodule
