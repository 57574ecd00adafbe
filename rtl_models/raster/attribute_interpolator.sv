// Attribute interpolator: Verilog reference of
// tlm/raster/datapath/attribute_interpolator.h.
//
// Combinational (no latency). value_o = start + grad_x * offset_x +
// grad_y * offset_y, exact in a signed 51-bit accumulator; value_next_x_o and
// value_next_y_o are the stepped values (one addition each). attr_o is value_o
// converted by kind_i with round-to-nearest (ties up) and clamping:
//   0 COLOR     40-bit words q23.16 -> unorm8 in attr_o[7:0]
//   1 DEPTH     40-bit words q31.8  -> unorm24 in attr_o[23:0]
//   2 TEXCOORD  40-bit words q15.24 -> q15.16 in attr_o[31:0]
//   3           undefined, attr_o = 0
// Formats and the overflow bound are described in attribute_interpolator.h.
module attribute_interpolator (
  input  logic [1:0]  kind_i,
  input  logic [39:0] start_i,
  input  logic [39:0] grad_x_i,
  input  logic [39:0] grad_y_i,
  input  logic [9:0]  offset_x_i,
  input  logic [9:0]  offset_y_i,
  output logic [50:0] value_o,
  output logic [50:0] value_next_x_o,
  output logic [50:0] value_next_y_o,
  output logic [31:0] attr_o
);

  // Accumulator width: |start| + 2 * 2^39 * 2^9 < 2^50, plus the sign.
  localparam int unsigned SumWidth = 51;

  logic signed [SumWidth-1:0] start, prod_x, prod_y, value;
  assign start = SumWidth'($signed(start_i));
  assign prod_x = $signed(grad_x_i) * $signed(offset_x_i);
  assign prod_y = $signed(grad_y_i) * $signed(offset_y_i);
  assign value = start + prod_x + prod_y;

  assign value_o = value;
  assign value_next_x_o = value + SumWidth'($signed(grad_x_i));
  assign value_next_y_o = value + SumWidth'($signed(grad_y_i));

  // Round to nearest, ties towards +infinity, at the kind's output LSB.
  logic signed [SumWidth-1:0] color_rounded, fine_rounded;
  logic signed [34:0] color_code;
  logic signed [42:0] fine_code;
  assign color_rounded = value + SumWidth'(32'sd32768);
  assign fine_rounded = value + SumWidth'(32'sd128);
  assign color_code = color_rounded[SumWidth-1:16];
  assign fine_code = fine_rounded[SumWidth-1:8];

  logic unused_rounded_fraction;
  assign unused_rounded_fraction = ^{color_rounded[15:0], fine_rounded[7:0]};

  always_comb begin
    attr_o = '0;
    unique case (kind_i)
      2'd0: begin
        if (color_code < 35'sd0) begin
          attr_o = '0;
        end else if (color_code > 35'sd255) begin
          attr_o = 32'd255;
        end else begin
          attr_o = {24'd0, color_code[7:0]};
        end
      end
      2'd1: begin
        if (fine_code < 43'sd0) begin
          attr_o = '0;
        end else if (fine_code > 43'sd16777215) begin
          attr_o = 32'h00ff_ffff;
        end else begin
          attr_o = {8'd0, fine_code[23:0]};
        end
      end
      2'd2: begin
        if (fine_code < -43'sd2147483648) begin
          attr_o = 32'h8000_0000;
        end else if (fine_code > 43'sd2147483647) begin
          attr_o = 32'h7fff_ffff;
        end else begin
          attr_o = fine_code[31:0];
        end
      end
      default: attr_o = '0;
    endcase
  end

endmodule
