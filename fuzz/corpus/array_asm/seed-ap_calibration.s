; The array micro-benchmarks of docs/spec/calibration.md (calib_array, sw_driver/apps/ap_calibration.cpp).
; Each figure is measured as the difference of two runs of different
; lengths, so the loads, stores, loop set-up and halt around the measured
; operation cancel out.
;
; Multi-byte values are big-endian: high byte at the lower address/register.

.const RECORDS 128
.const RECORD 6
.const LAST_RECORD 762        ; RECORD x (RECORDS - 1)
.const LAST_HALF 378          ; RECORD x (RECORDS / 2 - 1)

; Register level: r0:r1 += r2:r3 (16-bit), and r0:r1:r2 = r3:r4 x r5.
.var sum 2                    ; the 16-bit accumulator: start value in, result out
.var increment 2
.var multiplicand 2
.var multiplier 1
.var product 3

; CMEM level: RECORDS records of RECORD bytes.
;   addition:       a_hi a_lo b_hi b_lo c_hi c_lo        c = a + b
;   multiplication: a_hi a_lo b p_hi p_mid p_lo          p = a x b (16 x 8 signed -> 24 bits)
.var records 768

add_registers_1000:
.stage setup
  mov r0, [sum]
  mov r1, [sum + 1]
  mov r2, [increment]
  mov r3, [increment + 1]
.stage shade
  loop n, 999, 1
    add r1, r1, r3
    adc r0, r0, r2
  endloop
.stage transfer
  mov [sum], r0
  mov [sum + 1], r1
  halt

add_registers_2000:
.stage setup
  mov r0, [sum]
  mov r1, [sum + 1]
  mov r2, [increment]
  mov r3, [increment + 1]
.stage shade
  loop n, 1999, 1
    add r1, r1, r3
    adc r0, r0, r2
  endloop
.stage transfer
  mov [sum], r0
  mov [sum + 1], r1
  halt

mul_registers_1000:
.stage setup
  mov r3, [multiplicand]
  mov r4, [multiplicand + 1]
  mov r5, [multiplier]
.stage shade
  loop n, 999, 1
    mul r0, r3, r5
  endloop
.stage transfer
  mov [product], r0
  mov [product + 1], r1
  mov [product + 2], r2
  halt

mul_registers_2000:
.stage setup
  mov r3, [multiplicand]
  mov r4, [multiplicand + 1]
  mov r5, [multiplier]
.stage shade
  loop n, 1999, 1
    mul r0, r3, r5
  endloop
.stage transfer
  mov [product], r0
  mov [product + 1], r1
  mov [product + 2], r2
  halt

; One pass: every CU adds one record's a and b and stores c; the "all"
; program makes RECORDS passes, the "half" one RECORDS / 2.
add_cmem_all:
.stage shade
  loop k, LAST_RECORD, RECORD
    add [records + 5 + k], [records + 1 + k], [records + 3 + k]
    adc [records + 4 + k], [records + 0 + k], [records + 2 + k]
  endloop
  halt

add_cmem_half:
.stage shade
  loop k, LAST_HALF, RECORD
    add [records + 5 + k], [records + 1 + k], [records + 3 + k]
    adc [records + 4 + k], [records + 0 + k], [records + 2 + k]
  endloop
  halt

mul_cmem_all:
.stage shade
  loop k, LAST_RECORD, RECORD
    mulm [records + 3 + k], [records + 0 + k], [records + 2 + k]
  endloop
  halt

mul_cmem_half:
.stage shade
  loop k, LAST_HALF, RECORD
    mulm [records + 3 + k], [records + 0 + k], [records + 2 + k]
  endloop
  halt
