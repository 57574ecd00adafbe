// Edge-function evaluator: Verilog reference of tlm/raster/datapath/edge_function.h.
//
// Combinational (no latency). For an edge from (x0, y0) to (x1, y1) in
// unsigned 9.4 and the pixel (px, py) with its sample at the centre
// (16 * p + 8 in 9.4 codes) it computes
//   edge_o        E = (x - x0) * dy - (y - y0) * dx, exact, signed q20.8
//   edge_next_x_o E + 16 * dy  (the value at px + 1)
//   edge_next_y_o E - 16 * dx  (the value at py + 1)
//   inside_o      E > 0, or E == 0 and (dy > 0 or (dy == 0 and dx < 0)):
//                 the antisymmetric tie-break that draws a shared edge once
//   l1_length_o   |dx| + |dy|, unsigned 10.4 (input of the reciprocal unit)
//   distance_o    E * recip rounded to nearest (ties up) to 8 fraction bits,
//                 clamped to signed q7.8 (EASA L1-normalised distance)
//   coverage_o    round(clamp(1/2 + distance, 0, 1) * 255), unorm 0.8
// recip_i is 1 / (|dx| + |dy|) from the reciprocal unit, unsigned 5.16.
// Formats and sources are described in edge_function.h.
module edge_function (
  input  logic [12:0] x0_i,
  input  logic [12:0] y0_i,
  input  logic [12:0] x1_i,
  input  logic [12:0] y1_i,
  input  logic [8:0]  px_i,
  input  logic [8:0]  py_i,
  input  logic [20:0] recip_i,
  output logic [28:0] edge_o,
  output logic [28:0] edge_next_x_o,
  output logic [28:0] edge_next_y_o,
  output logic        inside_o,
  output logic [13:0] l1_length_o,
  output logic [15:0] distance_o,
  output logic [7:0]  coverage_o
);

  // The distance keeps 8 of the product's 24 fraction bits; the dropped
  // ones are rounded at this position.
  localparam int unsigned DropBits = 16;

  logic signed [13:0] dx, dy;
  logic signed [13:0] rel_x, rel_y;
  logic signed [27:0] prod_x, prod_y;
  logic signed [28:0] value;

  assign dx = $signed({1'b0, x1_i}) - $signed({1'b0, x0_i});
  assign dy = $signed({1'b0, y1_i}) - $signed({1'b0, y0_i});
  assign rel_x = $signed({1'b0, px_i, 4'b1000}) - $signed({1'b0, x0_i});
  assign rel_y = $signed({1'b0, py_i, 4'b1000}) - $signed({1'b0, y0_i});
  assign prod_x = rel_x * dy;
  assign prod_y = rel_y * dx;
  assign value = {prod_x[27], prod_x} - {prod_y[27], prod_y};

  assign edge_o = value;
  assign edge_next_x_o = value + {{11{dy[13]}}, dy, 4'b0000};
  assign edge_next_y_o = value - {{11{dx[13]}}, dx, 4'b0000};

  logic dy_positive, dy_zero, dx_negative;
  assign dy_positive = !dy[13] && (dy != '0);
  assign dy_zero = (dy == '0);
  assign dx_negative = dx[13];

  always_comb begin
    inside_o = 1'b0;
    if (value != '0) begin
      inside_o = !value[28];
    end else begin
      inside_o = dy_positive || (dy_zero && dx_negative);
    end
  end

  logic [13:0] abs_dx, abs_dy;
  assign abs_dx = dx[13] ? 14'(-dx) : dx;
  assign abs_dy = dy[13] ? 14'(-dy) : dy;
  assign l1_length_o = abs_dx + abs_dy;

  logic signed [49:0] product, product_rounded;
  logic signed [33:0] distance_wide;
  assign product = value * $signed({1'b0, recip_i});
  assign product_rounded = product + 50'sd32768;
  assign distance_wide = product_rounded[49:DropBits];

  logic unused_product_fraction;
  assign unused_product_fraction = ^product_rounded[DropBits-1:0];

  logic signed [15:0] distance;
  always_comb begin
    distance = distance_wide[15:0];
    if (distance_wide > 34'sd32767) begin
      distance = 16'sh7fff;
    end else if (distance_wide < -34'sd32768) begin
      distance = 16'sh8000;
    end
  end
  assign distance_o = distance;

  // 1/2 + distance in 1/256 pixel, clamped to [0, 1] = [0, 256].
  logic signed [16:0] half_plus_distance;
  logic [8:0] clamped;
  logic [16:0] scaled;
  assign half_plus_distance = {distance[15], distance} + 17'sd128;
  always_comb begin
    clamped = half_plus_distance[8:0];
    if (half_plus_distance < 17'sd0) begin
      clamped = 9'd0;
    end else if (half_plus_distance > 17'sd256) begin
      clamped = 9'd256;
    end
  end
  assign scaled = 17'(clamped) * 17'd255 + 17'd128;
  assign coverage_o = scaled[15:8];

  logic unused_scaled;
  assign unused_scaled = ^{scaled[16], scaled[7:0]};

endmodule
