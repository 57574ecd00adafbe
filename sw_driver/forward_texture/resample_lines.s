; Eq. 6 on the array (README.md, "On the array"): one line per CU, every CU
; at the same texel index (a uniform address), bit for bit what
; step_borders and resample_line compute. Two programs from this source,
; told apart by TABLE_FACTORS, which the build defines (ap_asm -D):
;  0: resample_lines, the J2210 as it is: the box filter's factors computed;
;  1: resample_lines_lut, with the shared lookup table (array.features.lut):
;     the factors looked up in the host's table of the filter, any filter.
;
; Per border k = 0 .. n of the line (the texel loop's v = n - k):
;  1. the border: the numerator's sign and magnitude, 57 steps of restoring
;     division by the denominator (divide_border), the sign put back, the
;     errors (a quotient of 2^30 or more, a texel wider than one pixel)
;     kept in `err`; then numerator and denominator step by one addition;
;  2. s = border + offset: its top two bytes are the window's last pixel,
;     its third byte the phase; the window moved on when the pixel changed;
;  3. the F factors H_j, the filter table's row for the phase:
;     computed (TABLE_FACTORS 0): H_j = floor((256 phase + 65536 (F - 1 - j)
;     + F) / 2F), the box's, from the quotient and remainder of 256 phase
;     by 2F (16 restoring steps), plus the host's quotient q_j and remainder
;     r_j of 65536 (F - 1 - j) + F, plus one when the remainders add up to 2F;
;     looked up (TABLE_FACTORS 1): one lut a factor, entry 256 (F - 1 - j) +
;     phase of the host's table (lut_entries in array_lines.h), F lookups a
;     border (Eq. 6's count);
;  4. the F scalings H_j dC rounded to q8_8: two 16 x 8 multiplications of
;     H_j by the bytes of |dC|, the sign put back before the rounding;
;  5. the window's sums: each slot its pixel's (shifted by one slot when the
;     window moved on), plus its scaling;
;  6. the pixel the window left: its sum plus C_{k-1}, clamped, written with
;     its pixel number at the border's output slot (else the number 0x80xx:
;     none). The host scatters them; after the loop it reads the window's
;     last F pixels.
;
; The host writes the line's texel count n into the texel loop (written
; with the start MAX_TEXELS) and F - 1 into every loop over the window
; (written with the start MAX_WIDTH - 1) before it loads the program.
;
; Stages: texcoord = the border (stepping and division), shade = the
; factors (the lookups too) and scalings, transfer = the window's moves and
; the outputs.

.const MAX_TEXELS 512
.const MAX_WIDTH 8

; The line, per CU. Multi-byte values big-endian.
.var num 4                  ; the border's numerator, q12_20 (stepped in place)
.var num_step 4
.var den 4                  ; its denominator, q2_30, > 0
.var den_step 4
.var tex_hi MAX_TEXELS + 2  ; C_k at index n - k (q8_8, high bytes), 0 at index 0 and n + 1
.var tex_lo MAX_TEXELS + 2

; The same in every CU (the host writes them once per filter).
.var offset 4               ; (F - 1) / 2 pixel plus half a phase step, q16_16
.if TABLE_FACTORS
.var slot_hi MAX_WIDTH      ; F - 1 - j: the high byte of slot j's table index
.else
.var q_hi MAX_WIDTH         ; quotient of 65536 (F - 1 - j) + F by 2F, slot j
.var q_lo MAX_WIDTH
.var r_j MAX_WIDTH          ; its remainder
.var two_f 1                ; 2F
.endif
.var zero 1                 ; 0x00
.var ff 1                   ; 0xff
.var c80 1                  ; 0x80
.var c40 1                  ; 0x40
.var cc0 1                  ; 0xc0
.var none 1                 ; 0x80: the high byte of "no pixel"
.var limit 4                ; 0x00010001: a texel wider than this is magnified
.var clamp 3                ; 0x00ff01: a sum at least this is above 255 << 8

; Results, per CU.
.var idx_hi MAX_TEXELS + 1  ; at n - k: the window's last pixel before border k when the window moved on there
.var idx_lo MAX_TEXELS + 1
.var val_hi MAX_TEXELS + 1  ; the value of the pixel the window left, q8_8
.var val_lo MAX_TEXELS + 1
.var last_pixel 2           ; after the loop: the window's last pixel
.var fin_hi MAX_WIDTH       ; the window's pixels' values, q8_8
.var fin_lo MAX_WIDTH
.var err 1                  ; not 0: a border out of range or a texel wider than a pixel

; The program's own.
.var sign 1                 ; 0xff when the numerator is negative
.var mag 4                  ; its magnitude, shifted out bit by bit
.var quot 4
.var overflow 1             ; quotient bits shifted out of quot
.var previous_border 4
.var pixel 2                ; the window's last pixel at this border
.var phase 1
.var started 1              ; 0xff after the first border
.var moved 1                ; 0xff when the window moved on at this border
.if TABLE_FACTORS
                            ; (the table needs no division of the phase)
.else
.var quotient_256p 2        ; 256 phase / 2F
.var remainder_256p 1
.endif
.var dc_sign 1              ; 0xff when dC < 0
.var u_hi 1                 ; the bytes of |dC|, each xor 0x80 (a signed multiplier)
.var u_lo 1
.var rounding 4             ; 0x4000 - dc_sign: the rounding of -P as (P xor -1) + 1
.var h128 3                 ; 128 H_j
.var p_hi 3                 ; H_j x the high byte of |dC|
.var old_hi MAX_WIDTH + 1   ; the window's sums, 24-bit; slot F stays 0
.var old_mid MAX_WIDTH + 1
.var old_lo MAX_WIDTH + 1
.var new_hi MAX_WIDTH
.var new_mid MAX_WIDTH
.var new_lo MAX_WIDTH

resample:
.stage setup
  mset
  mov [started], [zero]
  mov [err], [zero]
.rept j, 0, MAX_WIDTH
  mov [old_hi + j], [zero]
  mov [old_mid + j], [zero]
  mov [old_lo + j], [zero]
.endr
  loop v, MAX_TEXELS, 1
.stage texcoord
    ; 1. The border: |numerator| into mag, shifted left once (bit 31 is 0).
    mov r0, [num]
    mmov s
    getm r4
    mset
    mov [sign], r4
    xor r3, [num + 3], r4
    xor r2, [num + 2], r4
    xor r1, [num + 1], r4
    xor r0, [num], r4
    sub r3, r3, r4
    sbc r2, r2, r4
    sbc r1, r1, r4
    sbc r0, r0, r4
    shl r3, r3
    rol r2, r2
    rol r1, r1
    rol r0, r0
    mov [mag + 3], r3
    mov [mag + 2], r2
    mov [mag + 1], r1
    mov [mag], r0
    mov r0, [zero]
    mov r1, [zero]
    mov r2, [zero]
    mov r3, [zero]
    mov [quot], [zero]
    mov [quot + 1], [zero]
    mov [quot + 2], [zero]
    mov [quot + 3], [zero]
    mov [overflow], [zero]
    ; The remainder r0..r3; the magnitude's bits 30 .. 0, then (the magnitude
    ; shifted out) 26 zeros: 57 steps.
    loop i, 56, 1
      shl [mag + 3], [mag + 3]
      rol [mag + 2], [mag + 2]
      rol [mag + 1], [mag + 1]
      rol [mag], [mag]
      rol r3, r3
      rol r2, r2
      rol r1, r1
      rol r0, r0
      cmp r3, [den + 3]
      cmpc r2, [den + 2]
      cmpc r1, [den + 1]
      cmpc r0, [den]
      mmov c
      getm r4
      mset
      rol [quot + 3], [quot + 3]
      rol [quot + 2], [quot + 2]
      rol [quot + 1], [quot + 1]
      rol [quot], [quot]
      adc [overflow], [overflow], [zero]
      and r5, r4, [den + 3]
      sub r3, r3, r5
      and r5, r4, [den + 2]
      sbc r2, r2, r5
      and r5, r4, [den + 1]
      sbc r1, r1, r5
      and r5, r4, [den]
      sbc r0, r0, r5
    endloop
    ; A quotient of 2^30 or more is out of range.
    and r0, [quot], [cc0]
    or r0, r0, [overflow]
    mmov nz
    mov [err], [ff]
    mset
    ; The border r0..r3 = the quotient, negated when the numerator is.
    mov r4, [sign]
    xor r3, [quot + 3], r4
    xor r2, [quot + 2], r4
    xor r1, [quot + 1], r4
    xor r0, [quot], r4
    sub r3, r3, r4
    sbc r2, r2, r4
    sbc r1, r1, r4
    sbc r0, r0, r4
    ; A texel wider than one pixel (after the first border).
    sub r4, r3, [previous_border + 3]
    sbc r5, r2, [previous_border + 2]
    sbc r6, r1, [previous_border + 1]
    sbc r7, r0, [previous_border]
    cmp r4, [limit + 3]
    cmpc r5, [limit + 2]
    cmpc r6, [limit + 1]
    cmpc r7, [limit]
    mmov c
    mov r4, [started]
    mand nz
    mov [err], [ff]
    mset
    mov [previous_border + 3], r3
    mov [previous_border + 2], r2
    mov [previous_border + 1], r1
    mov [previous_border], r0
    ; The next border's numerator and denominator.
    add [num + 3], [num + 3], [num_step + 3]
    adc [num + 2], [num + 2], [num_step + 2]
    adc [num + 1], [num + 1], [num_step + 1]
    adc [num], [num], [num_step]
    add [den + 3], [den + 3], [den_step + 3]
    adc [den + 2], [den + 2], [den_step + 2]
    adc [den + 1], [den + 1], [den_step + 1]
    adc [den], [den], [den_step]
    ; 2. s = border + offset.
    add r3, r3, [offset + 3]
    adc r2, r2, [offset + 2]
    adc r1, r1, [offset + 1]
    adc r0, r0, [offset]
    mov [phase], r2
.stage transfer
    ; Moved on: started and the pixel changed.
    xor r4, r0, [pixel]
    xor r5, r1, [pixel + 1]
    or r4, r4, r5
    mmov nz
    mov r4, [started]
    mand nz
    getm r4
    mset
    mov [moved], r4
    ; 6. The pixel the window leaves: its number, and its sum plus C_{k-1} clamped.
    mov [idx_hi + v], [none]
    mov [idx_lo + v], [zero]
    add r4, [old_lo], [tex_lo + v + 1]
    adc r5, [old_mid], [tex_hi + v + 1]
    adc r6, [old_hi], [zero]
    mmov s
    getm r7
    cmp r4, [clamp + 2]
    cmpc r5, [clamp + 1]
    cmpc r6, [clamp]
    mmov c
    getm r6
    mov r2, [moved]
    mmov nz
    mov [idx_hi + v], [pixel]
    mov [idx_lo + v], [pixel + 1]
    mov [val_hi + v], r5
    mov [val_lo + v], r4
    mov r2, r6
    mmov nz
    mov r2, [moved]
    mand nz
    mov [val_hi + v], [ff]
    mov [val_lo + v], [zero]
    mov r2, r7
    mmov nz
    mov r2, [moved]
    mand nz
    mov [val_hi + v], [zero]
    mov [val_lo + v], [zero]
    mset
    mov [pixel], r0
    mov [pixel + 1], r1
    mov [started], [ff]
.stage shade
    ; dC = C_{k-1} - C_k, its sign and magnitude.
    sub r2, [tex_lo + v + 1], [tex_lo + v]
    sbc r1, [tex_hi + v + 1], [tex_hi + v]
    sbc r0, [zero], [zero]
    xor r2, r2, r0
    xor r1, r1, r0
    sub r2, r2, r0
    sbc r1, r1, r0
    mov [dc_sign], r0
    xor [u_hi], r1, [c80]
    xor [u_lo], r2, [c80]
    sub [rounding + 3], [zero], r0
    sbc [rounding + 2], [c40], r0
    sbc [rounding + 1], [zero], r0
    sbc [rounding], [zero], r0
.if TABLE_FACTORS
    ; 3. The factors are looked up in the loop below.
.else
    ; 3. 256 phase = quotient_256p 2F + remainder_256p.
    mov r3, [phase]
    mov r4, [zero]
    mov r5, [zero]
    mov r6, [zero]
.rept b, 0, 15
    shl r3, r3
    rol r4, r4
    cmp r4, [two_f]
    mmov c
    rol r6, r6
    rol r5, r5
    getm r7
    and r7, r7, [two_f]
    sub r4, r4, r7
.endr
    mset
    mov [quotient_256p], r5
    mov [quotient_256p + 1], r6
    mov [remainder_256p], r4
.endif
    loop j, MAX_WIDTH - 1, 1
      ; H_j in r0:r1.
.if TABLE_FACTORS
      mov r0, [slot_hi + j]
      mov r1, [phase]
      lut r0, r0
      ; A table may hold H = 1.0 = 0x8000 (the tent's does), which mul takes
      ; for -32768, 65536 too little: with r7 = 0xff then, each product gets
      ; 65536 times its multiplier back (the multiplier added to its top byte).
      shl r7, r0
      sbc r7, [zero], [zero]
      not r7, r7
.else
      add r2, [remainder_256p], [r_j + j]
      cmp r2, [two_f]
      adc r1, [quotient_256p + 1], [q_lo + j]
      adc r0, [quotient_256p], [q_hi + j]
.endif
      ; 128 H_j.
      mov r2, r0
      mov r3, r1
      mov r4, [zero]
      shr r2, r2
      ror r3, r3
      ror r4, r4
      mov [h128], r2
      mov [h128 + 1], r3
      mov [h128 + 2], r4
      ; 4. P = H_j |dC|: H_j (u - 128) + 128 H_j for each byte u of |dC|.
      mov r2, [u_hi]
      mul r3, r0, r2
.if TABLE_FACTORS
      and r2, r2, r7
      add r3, r3, r2
.endif
      add r5, r5, [h128 + 2]
      adc r4, r4, [h128 + 1]
      adc r3, r3, [h128]
      mov [p_hi], r3
      mov [p_hi + 1], r4
      mov [p_hi + 2], r5
      mov r2, [u_lo]
      mul r3, r0, r2
.if TABLE_FACTORS
      and r2, r2, r7
      add r3, r3, r2
.endif
      add r5, r5, [h128 + 2]
      adc r4, r4, [h128 + 1]
      adc r3, r3, [h128]
      add r4, r4, [p_hi + 2]
      adc r3, r3, [p_hi + 1]
      adc r2, [p_hi], [zero]
      ; Y = +-P + 0x4000 in r2..r5, then Y >> 15 in r6:r2:r3.
      mov r6, [dc_sign]
      xor r5, r5, r6
      xor r4, r4, r6
      xor r3, r3, r6
      xor r2, r2, r6
      add r5, r5, [rounding + 3]
      adc r4, r4, [rounding + 2]
      adc r3, r3, [rounding + 1]
      adc r2, r2, [rounding]
      shl r4, r4
      rol r3, r3
      rol r2, r2
      sbc r6, [zero], [zero]
      not r6, r6
.stage transfer
      ; 5. The slot's sum: the next slot's when the window moved on, plus the scaling.
      mov r7, [moved]
      mmov nz
      add [new_lo + j], [old_lo + j + 1], r3
      adc [new_mid + j], [old_mid + j + 1], r2
      adc [new_hi + j], [old_hi + j + 1], r6
      mov r7, [moved]
      mmov z
      add [new_lo + j], [old_lo + j], r3
      adc [new_mid + j], [old_mid + j], r2
      adc [new_hi + j], [old_hi + j], r6
      mset
.stage shade
    endloop
.stage transfer
    loop j, MAX_WIDTH - 1, 1
      mov [old_lo + j], [new_lo + j]
      mov [old_mid + j], [new_mid + j]
      mov [old_hi + j], [new_hi + j]
    endloop
  endloop
  ; The window's last pixels, clamped.
  mov [last_pixel], [pixel]
  mov [last_pixel + 1], [pixel + 1]
  loop j, MAX_WIDTH - 1, 1
    mov r2, [old_lo + j]
    mov r1, [old_mid + j]
    mov r0, [old_hi + j]
    mmov s
    getm r3
    cmp r2, [clamp + 2]
    cmpc r1, [clamp + 1]
    cmpc r0, [clamp]
    mmov c
    getm r4
    mset
    mov [fin_hi + j], r1
    mov [fin_lo + j], r2
    mov r5, r4
    mmov nz
    mov [fin_hi + j], [ff]
    mov [fin_lo + j], [zero]
    mov r5, r3
    mmov nz
    mov [fin_hi + j], [zero]
    mov [fin_lo + j], [zero]
    mset
  endloop
  halt
