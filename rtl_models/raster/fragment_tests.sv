// Per-fragment alpha, stencil and depth tests: Verilog reference of
// tlm/raster/datapath/fragment_tests.h.
//
// Combinational (no latency). Compare function fields hold the GL enum minus
// 0x0200 (NEVER 0, LESS 1, EQUAL 2, LEQUAL 3, GREATER 4, NOTEQUAL 5,
// GEQUAL 6, ALWAYS 7); the incoming value is the left operand:
// alpha_i func alpha_ref_i, (stencil_ref_i & mask) func (stencil_i & mask),
// depth_i func stored_depth_i. Stencil operation fields: KEEP 0, ZERO 1,
// REPLACE 2, INCR 3 (saturating), DECR 4 (saturating), INVERT 5, 6 and 7 act
// as KEEP. stencil_o is the value to store (through stencil_write_mask_i);
// depth_we_o says whether depth_i is to be stored. GL 1.2 sequencing is
// described in fragment_tests.h.
module fragment_tests (
  input  logic        alpha_enable_i,
  input  logic [2:0]  alpha_func_i,
  input  logic [7:0]  alpha_ref_i,
  input  logic [7:0]  alpha_i,
  input  logic        stencil_enable_i,
  input  logic [2:0]  stencil_func_i,
  input  logic [7:0]  stencil_ref_i,
  input  logic [7:0]  stencil_value_mask_i,
  input  logic [7:0]  stencil_write_mask_i,
  input  logic [2:0]  stencil_sfail_i,
  input  logic [2:0]  stencil_dpfail_i,
  input  logic [2:0]  stencil_dppass_i,
  input  logic [7:0]  stencil_i,
  input  logic        depth_enable_i,
  input  logic [2:0]  depth_func_i,
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

  function automatic logic compare(input logic [2:0] func,
                                   input logic [CompareWidth-1:0] incoming,
                                   input logic [CompareWidth-1:0] stored);
    // Assigned through the function name: yosys 0.23 has no `return`.
    compare = 1'b0;
    unique case (func)
      3'd0: compare = 1'b0;
      3'd1: compare = incoming < stored;
      3'd2: compare = incoming == stored;
      3'd3: compare = incoming <= stored;
      3'd4: compare = incoming > stored;
      3'd5: compare = incoming != stored;
      3'd6: compare = incoming >= stored;
      3'd7: compare = 1'b1;
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

  logic [2:0] op;
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
      3'd0: op_result = stencil_i;
      3'd1: op_result = 8'd0;
      3'd2: op_result = stencil_ref_i;
      3'd3: op_result = (stencil_i == 8'hff) ? 8'hff : stencil_i + 8'd1;
      3'd4: op_result = (stencil_i == 8'h00) ? 8'h00 : stencil_i - 8'd1;
      3'd5: op_result = ~stencil_i;
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
