// One CU of the array processor: Verilog reference of
// tlm/array/datapath/cu_alu.h, lane semantics as in tlm/array/core/cu_array.h.
//
// The unit holds the CU's architectural state (register file, flags C, Z, S
// and the mask M) and executes one decoded instruction at a time. CMEM is not
// in here: the array reads a CU's memory operands and hands the bytes in
// (a_cmem_i: the bytes at a and a + 1; b_cmem_i: the byte at b), and the CU
// answers with the bytes to store at d, d + 1, d + 2 with a write enable per
// byte that is already gated by M. Register and flag writes happen whatever
// M is. Wide values are big-endian, the high byte at the lower register
// number or address, and so are the byte lanes of the wide ports: bits
// [15:8] of a_cmem_i are the byte at a, bits [23:16] of cmem_wdata_o (and
// bit 2 of cmem_we_o) the byte for d. The ports are flat vectors because
// yosys 0.23 reads no multi-dimensional packed port.
//
// Timing: an instruction is taken when valid_i && ready_o at a rising clock
// edge. Every instruction but the multiply completes on that edge: the state
// outputs show its result and done_o, cmem_we_o and cmem_wdata_o hold for
// the one cycle after it (the divide, div, included: its 8 restoring steps
// are unrolled into one edge's logic, as the Image Blender divides in one
// instruction; so are the 16-bit operations on register pairs, add16,
// sub16, cmp16 and mov16, whose two byte passes are one 16-bit adder here:
// the cycles they cost are the array controller's table, not this unit's
// edges). The multiply (mul, mulm) takes 8 edges, one
// shift-and-add step per edge with ready_o low in between, and raises done_o
// after the eighth. Opcodes that are the array controller's (nop, halt,
// loop, endloop, endloopany) and codes with no instruction complete as no-ops.
module cu_datapath #(
  // The CU's register file is a configuration parameter of the array
  // (array.registers); 8 is the default, at most 16 (the 4-bit register
  // numbers of the instruction word).
  parameter int unsigned Registers = 8,
  // Register numbers are only as wide as the file needs; derived.
  localparam int unsigned RegBits = Registers > 1 ? $clog2(Registers) : 1
) (
  input  logic                         clk_i,
  input  logic                         rst_ni,

  // The decoded instruction, with its operand bytes from CMEM.
  input  logic                         valid_i,
  output logic                         ready_o,
  input  ap_isa_pkg::op_e              opcode_i,
  input  ap_isa_pkg::cond_e            cond_i,
  input  ap_isa_pkg::direction_e       direction_i,
  input  logic                         d_is_cmem_i,
  input  logic                         a_is_cmem_i,
  input  logic                         b_is_cmem_i,
  input  logic [RegBits-1:0]           d_reg_i,
  input  logic [RegBits-1:0]           a_reg_i,
  input  logic [RegBits-1:0]           b_reg_i,
  input  logic [15:0]                  a_cmem_i,
  input  logic [7:0]                   b_cmem_i,
  // The byte at d, for nadds and nadcs with d in CMEM (they add into d).
  input  logic [7:0]                   d_cmem_i,

  // The four neighbours' bytes for nget and nadd (their register or CMEM byte at a),
  // byte k at [8k+7:8k] for direction code k (ap_isa_pkg::direction_e);
  // absent beyond the grid's edge.
  input  logic [31:0]                  neighbour_i,
  input  logic [3:0]                   neighbour_present_i,
  // The same neighbours' bytes at a + 1, for nadds and nadcs: where this
  // CU's S is set they add the neighbour's a + 1 instead of its a (the
  // window's slot shifted by one, van Sinten's step 5).
  input  logic [31:0]                  neighbour_next_i,

  // Completion and the CMEM write of the instruction that completed.
  output logic                         done_o,
  output logic [2:0]                   cmem_we_o,
  output logic [23:0]                  cmem_wdata_o,

  // Architectural state, for the array's status reads and the co-simulation.
  // Register r at [8r+7:8r].
  output logic [Registers*8-1:0]       regs_o,
  output logic                         flag_c_o,
  output logic                         flag_z_o,
  output logic                         flag_s_o,
  output logic                         mask_o
);

  // The multiply walks the 8 bits of the multiplier, one per clock.
  localparam int unsigned MulSteps = 8;
  localparam int unsigned ProductBits = 24;

  logic [Registers*8-1:0] regs_d, regs_q;
  logic c_d, c_q, z_d, z_q, s_d, s_q, m_d, m_q;

  // Multiplier state: busy between the first and the last step.
  logic                        mul_busy_d, mul_busy_q;
  logic [2:0]                  mul_step_d, mul_step_q;
  logic [ProductBits-1:0]      mul_acc_d, mul_acc_q;
  logic [ProductBits-1:0]      mul_mcand_d, mul_mcand_q;
  logic [MulSteps-1:0]         mul_mplier_d, mul_mplier_q;
  logic                        mul_d_cmem_d, mul_d_cmem_q;
  logic [RegBits-1:0]          mul_d_reg_d, mul_d_reg_q;

  logic                        done_d, done_q;
  logic [2:0]                  cmem_we_d, cmem_we_q;
  logic [23:0]                 cmem_wdata_d, cmem_wdata_q;

  logic accept;
  assign accept = valid_i && !mul_busy_q;

  // Operand bytes: a register or the CMEM byte the array read.
  logic [7:0] a_value, a_low_value, b_value;
  logic [RegBits-1:0] a_low_reg;
  assign a_low_reg   = a_reg_i + RegBits'(1);
  assign a_value     = a_is_cmem_i ? a_cmem_i[15:8] : regs_q[8*a_reg_i +: 8];
  assign a_low_value = a_is_cmem_i ? a_cmem_i[7:0] : regs_q[8*a_low_reg +: 8];
  assign b_value     = b_is_cmem_i ? b_cmem_i : regs_q[8*b_reg_i +: 8];

  // The 16-bit operations' register pairs: the high byte at the register
  // the instruction names, the low byte at the next one (the decoder refuses
  // a pair beyond the file).
  logic [RegBits-1:0] b_low_reg, d_low_reg;
  logic [15:0]        a_pair, b_pair;
  assign b_low_reg = b_reg_i + RegBits'(1);
  assign d_low_reg = d_reg_i + RegBits'(1);
  assign a_pair    = {regs_q[8*a_reg_i +: 8], regs_q[8*a_low_reg +: 8]};
  assign b_pair    = {regs_q[8*b_reg_i +: 8], regs_q[8*b_low_reg +: 8]};

  logic is_select_add;
  assign is_select_add = opcode_i == ap_isa_pkg::OpNadds || opcode_i == ap_isa_pkg::OpNadcs;

  logic [7:0] neighbour_value;
  always_comb begin
    neighbour_value = 8'd0;
    if (neighbour_present_i[direction_i]) begin
      neighbour_value = is_select_add && s_q ? neighbour_next_i[8*direction_i +: 8] : neighbour_i[8*direction_i +: 8];
    end
  end

  // The neighbour adds' own operand: d, a register for nadd (its forms are
  // R), a register or the CMEM byte at d for nadds and nadcs.
  logic [7:0] d_value;
  assign d_value = d_is_cmem_i ? d_cmem_i : regs_q[8*d_reg_i +: 8];

  logic is_neighbour_add;
  assign is_neighbour_add = opcode_i == ap_isa_pkg::OpNadd || is_select_add;

  logic is_mul;
  assign is_mul = opcode_i == ap_isa_pkg::OpMul || opcode_i == ap_isa_pkg::OpMulm;

  // The adder of add, adc, sub, sbc, cmp, cmpc and nadd: a subtraction is
  // a + ~b + carry, so C is "no borrow" as in the C++ model; nadd adds the
  // neighbour's byte to d.
  logic       subtract, carry_in;
  logic [8:0] sum;
  always_comb begin
    subtract = 1'b0;
    carry_in = 1'b0;
    unique case (opcode_i)
      ap_isa_pkg::OpAdc, ap_isa_pkg::OpNadcs: carry_in = c_q;
      ap_isa_pkg::OpSub, ap_isa_pkg::OpCmp: begin
        subtract = 1'b1;
        carry_in = 1'b1;
      end
      ap_isa_pkg::OpSbc, ap_isa_pkg::OpCmpc: begin
        subtract = 1'b1;
        carry_in = c_q;
      end
      default: ;
    endcase
  end
  logic [7:0] add_a, add_b;
  assign add_a = is_neighbour_add ? d_value : a_value;
  assign add_b = is_neighbour_add ? neighbour_value : b_value;
  assign sum = {1'b0, add_a} + {1'b0, subtract ? ~add_b : add_b} + {8'd0, carry_in};

  // add16, sub16, cmp16 and mov16: the 16-bit result, whether d:d+1 is
  // written, and the carry. A subtraction is a + ~b + 1, C "no borrow" as in
  // the 8-bit adder; mov16 keeps C. Z and S are those of all 16 bits.
  logic        is_pair_op, pair_writes_d, pair_subtract, pair_carry_out;
  logic [16:0] pair_sum;
  logic [15:0] pair_result;
  assign pair_subtract = opcode_i == ap_isa_pkg::OpSub16 || opcode_i == ap_isa_pkg::OpCmp16;
  assign pair_sum = {1'b0, a_pair} + {1'b0, pair_subtract ? ~b_pair : b_pair} + {16'd0, pair_subtract};
  always_comb begin
    is_pair_op     = 1'b1;
    pair_writes_d  = 1'b1;
    pair_result    = pair_sum[15:0];
    pair_carry_out = pair_sum[16];
    unique case (opcode_i)
      ap_isa_pkg::OpAdd16, ap_isa_pkg::OpSub16: ;
      ap_isa_pkg::OpCmp16: pair_writes_d = 1'b0;
      ap_isa_pkg::OpMov16: begin
        pair_result    = a_pair;
        pair_carry_out = c_q;
      end
      default: begin
        is_pair_op    = 1'b0;
        pair_writes_d = 1'b0;
      end
    endcase
  end

  logic cond_holds;
  always_comb begin
    cond_holds = 1'b0;
    unique case (cond_i)
      ap_isa_pkg::CondC:  cond_holds = c_q;
      ap_isa_pkg::CondNc: cond_holds = !c_q;
      ap_isa_pkg::CondZ:  cond_holds = z_q;
      ap_isa_pkg::CondNz: cond_holds = !z_q;
      ap_isa_pkg::CondS:  cond_holds = s_q;
      ap_isa_pkg::CondNs: cond_holds = !s_q;
      ap_isa_pkg::CondHi: cond_holds = c_q && !z_q;
      ap_isa_pkg::CondLs: cond_holds = !c_q || z_q;
      default:            cond_holds = 1'b0;
    endcase
  end

  // The divide: dividend a:a+1 (a_value the high byte), divisor b, by 8
  // restoring steps. A quotient that does not fit 8 bits (the high byte at
  // least the divisor, a divisor of 0 included) saturates to 0xff with C set.
  // Otherwise the partial remainder stays below the divisor before each
  // step, so 9 bits hold it after the shift.
  logic       div_overflow;
  logic [7:0] div_quotient;
  logic [8:0] div_remainder;
  assign div_overflow = a_value >= b_value;
  always_comb begin
    div_remainder = {1'b0, a_value};
    div_quotient  = '0;
    for (int i = 7; i >= 0; i--) begin
      div_remainder = {div_remainder[7:0], a_low_value[i]};
      if (div_remainder >= {1'b0, b_value}) begin
        div_remainder   = div_remainder - {1'b0, b_value};
        div_quotient[i] = 1'b1;
      end
    end
  end

  // The single-cycle instructions: the byte for d, whether it is written,
  // and the flags.
  logic [7:0] result;
  logic       writes_d, writes_czs, writes_c, carry_out;
  always_comb begin
    result     = 8'd0;
    writes_d   = 1'b1;
    writes_czs = 1'b1;
    writes_c   = 1'b0;
    carry_out  = c_q;
    unique case (opcode_i)
      ap_isa_pkg::OpAdd, ap_isa_pkg::OpAdc, ap_isa_pkg::OpSub, ap_isa_pkg::OpSbc, ap_isa_pkg::OpNadd: begin
        result    = sum[7:0];
        carry_out = sum[8];
      end
      // S chose the source byte; it and Z stay for the wide sum's next byte.
      ap_isa_pkg::OpNadds, ap_isa_pkg::OpNadcs: begin
        result     = sum[7:0];
        carry_out  = sum[8];
        writes_czs = 1'b0;
        writes_c   = 1'b1;
      end
      ap_isa_pkg::OpCmp, ap_isa_pkg::OpCmpc: begin
        result    = sum[7:0];
        carry_out = sum[8];
        writes_d  = 1'b0;
      end
      ap_isa_pkg::OpAnd: result = a_value & b_value;
      ap_isa_pkg::OpOr:  result = a_value | b_value;
      ap_isa_pkg::OpXor: result = a_value ^ b_value;
      ap_isa_pkg::OpNot: result = ~a_value;
      ap_isa_pkg::OpMov: result = a_value;
      ap_isa_pkg::OpShl: begin
        result    = {a_value[6:0], 1'b0};
        carry_out = a_value[7];
      end
      ap_isa_pkg::OpShr: begin
        result    = {1'b0, a_value[7:1]};
        carry_out = a_value[0];
      end
      ap_isa_pkg::OpAsr: begin
        result    = {a_value[7], a_value[7:1]};
        carry_out = a_value[0];
      end
      ap_isa_pkg::OpRol: begin
        result    = {a_value[6:0], c_q};
        carry_out = a_value[7];
      end
      ap_isa_pkg::OpRor: begin
        result    = {c_q, a_value[7:1]};
        carry_out = a_value[0];
      end
      ap_isa_pkg::OpDiv: begin
        result    = div_overflow ? 8'hff : div_quotient;
        carry_out = div_overflow;
      end
      ap_isa_pkg::OpNget: begin
        result     = neighbour_value;
        writes_czs = 1'b0;
      end
      ap_isa_pkg::OpGetm: begin
        result     = {8{m_q}};
        writes_czs = 1'b0;
      end
      default: begin
        writes_d   = 1'b0;
        writes_czs = 1'b0;
      end
    endcase
  end

  // One shift-and-add step. The first step runs on the edge that takes the
  // instruction, from the operand bytes; the others from the registers. The
  // multiplicand is sign-extended to the product's width and shifts left one
  // place per step; bit 7 of the multiplier weighs -128, so the last step
  // subtracts.
  logic [ProductBits-1:0] step_mcand, step_acc, step_addend, step_sum;
  logic                   step_bit, step_last;
  always_comb begin
    if (mul_busy_q) begin
      step_mcand = mul_mcand_q;
      step_acc   = mul_acc_q;
      step_bit   = mul_mplier_q[0];
      step_last  = mul_step_q == 3'(MulSteps - 1);
    end else begin
      step_mcand = {{(ProductBits - 16){a_value[7]}}, a_value, a_low_value};
      step_acc   = '0;
      step_bit   = b_value[0];
      step_last  = 1'b0;
    end
    step_addend = step_bit ? step_mcand : '0;
    step_sum    = step_last ? step_acc - step_addend : step_acc + step_addend;
  end

  logic [RegBits-1:0] mul_d_reg_mid, mul_d_reg_low;
  assign mul_d_reg_mid = mul_d_reg_q + RegBits'(1);
  assign mul_d_reg_low = mul_d_reg_q + RegBits'(2);

  always_comb begin
    regs_d       = regs_q;
    c_d          = c_q;
    z_d          = z_q;
    s_d          = s_q;
    m_d          = m_q;
    mul_busy_d   = mul_busy_q;
    mul_step_d   = mul_step_q;
    mul_acc_d    = mul_acc_q;
    mul_mcand_d  = mul_mcand_q;
    mul_mplier_d = mul_mplier_q;
    mul_d_cmem_d = mul_d_cmem_q;
    mul_d_reg_d  = mul_d_reg_q;
    done_d       = 1'b0;
    cmem_we_d    = '0;
    cmem_wdata_d = cmem_wdata_q;

    if (mul_busy_q) begin
      mul_acc_d    = step_sum;
      mul_mcand_d  = {step_mcand[ProductBits-2:0], 1'b0};
      mul_mplier_d = {1'b0, mul_mplier_q[MulSteps-1:1]};
      mul_step_d   = mul_step_q + 3'd1;
      if (step_last) begin
        mul_busy_d = 1'b0;
        done_d     = 1'b1;
        c_d        = 1'b0;
        z_d        = step_sum == '0;
        s_d        = step_sum[ProductBits-1];
        if (mul_d_cmem_q) begin
          cmem_we_d    = {3{m_q}};
          cmem_wdata_d = step_sum;
        end else begin
          regs_d[8*mul_d_reg_q +: 8]    = step_sum[23:16];
          regs_d[8*mul_d_reg_mid +: 8]  = step_sum[15:8];
          regs_d[8*mul_d_reg_low +: 8]  = step_sum[7:0];
        end
      end
    end else if (accept && is_mul) begin
      mul_busy_d   = 1'b1;
      mul_step_d   = 3'd1;
      mul_acc_d    = step_sum;
      mul_mcand_d  = {step_mcand[ProductBits-2:0], 1'b0};
      mul_mplier_d = {1'b0, b_value[MulSteps-1:1]};
      mul_d_cmem_d = d_is_cmem_i;
      mul_d_reg_d  = d_reg_i;
    end else if (accept) begin
      done_d = 1'b1;
      unique case (opcode_i)
        ap_isa_pkg::OpMset: m_d = 1'b1;
        ap_isa_pkg::OpMclr: m_d = 1'b0;
        ap_isa_pkg::OpMmov: m_d = cond_holds;
        ap_isa_pkg::OpMand: m_d = m_q && cond_holds;
        ap_isa_pkg::OpMor:  m_d = m_q || cond_holds;
        default: ;
      endcase
      if (writes_czs) begin
        c_d = carry_out;
        z_d = result == 8'd0;
        s_d = result[7];
      end
      if (writes_c) begin
        c_d = carry_out;
      end
      if (is_pair_op) begin
        c_d = pair_carry_out;
        z_d = pair_result == 16'd0;
        s_d = pair_result[15];
      end
      if (pair_writes_d) begin
        regs_d[8*d_reg_i +: 8]   = pair_result[15:8];
        regs_d[8*d_low_reg +: 8] = pair_result[7:0];
      end
      if (writes_d) begin
        if (d_is_cmem_i) begin
          cmem_we_d    = {m_q, 2'b00};
          cmem_wdata_d = {result, 16'd0};
        end else begin
          regs_d[8*d_reg_i +: 8] = result;
        end
      end
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      regs_q       <= '0;
      c_q          <= 1'b0;
      z_q          <= 1'b0;
      s_q          <= 1'b0;
      m_q          <= 1'b1;
      mul_busy_q   <= 1'b0;
      mul_step_q   <= '0;
      mul_acc_q    <= '0;
      mul_mcand_q  <= '0;
      mul_mplier_q <= '0;
      mul_d_cmem_q <= 1'b0;
      mul_d_reg_q  <= '0;
      done_q       <= 1'b0;
      cmem_we_q    <= '0;
      cmem_wdata_q <= '0;
    end else begin
      regs_q       <= regs_d;
      c_q          <= c_d;
      z_q          <= z_d;
      s_q          <= s_d;
      m_q          <= m_d;
      mul_busy_q   <= mul_busy_d;
      mul_step_q   <= mul_step_d;
      mul_acc_q    <= mul_acc_d;
      mul_mcand_q  <= mul_mcand_d;
      mul_mplier_q <= mul_mplier_d;
      mul_d_cmem_q <= mul_d_cmem_d;
      mul_d_reg_q  <= mul_d_reg_d;
      done_q       <= done_d;
      cmem_we_q    <= cmem_we_d;
      cmem_wdata_q <= cmem_wdata_d;
    end
  end

  assign ready_o      = !mul_busy_q;
  assign done_o       = done_q;
  assign cmem_we_o    = cmem_we_q;
  assign cmem_wdata_o = cmem_wdata_q;
  assign regs_o       = regs_q;
  assign flag_c_o     = c_q;
  assign flag_z_o     = z_q;
  assign flag_s_o     = s_q;
  assign mask_o       = m_q;

endmodule
