; Eq. 6 after van Sinten's own mapping (README.md, "On the array: the
; chain"): every CU a different texel border of a block, the window's
; partial sums passed down each row's chain, the filter's H table in the
; shared lookup table. Bit for bit what step_borders and resample_line
; compute, for any filter the table holds.
;
; Needs array.issue_skew = lane (the chain), array.row_ring = true (the
; relay), array.features.neighbour_add (nadds, nadcs) and
; array.features.lut with at least 256 F entries: entry 256 j + phase is
; H(phase, j), the FilterTable's value.
;
; One line per CU row. Column 0 of a row is the relay: it holds the window
; the row's last CU left behind in the round before; columns 1 .. 23 take
; borders k = 23 q + c - 1 of the line in round q (the round loop's v =
; rounds - 1 - q). Per round, in every texel CU:
;  1. the border: 57 steps of restoring division (divide_border), as in
;     resample_lines.s; a quotient of 2^30 or more sets err; the border is
;     stored where the next CU reads it;
;  2. the predecessor's border (nget left): a texel wider than one pixel
;     sets err; s = border + offset: the window's last pixel and the phase;
;     the window moved on (`moved`) when the pixel differs from the
;     predecessor's (van Sinten's step 2);
;  3. the F factors: lut at index 256 j + phase (step 3);
;  4. the F scalings H_j dC rounded to q8_8 (step 4), each stored in its
;     window slot: H = G + 16384 with G = H - 16384 a signed 16-bit
;     multiplicand (H is up to 32768), |dC| two bytes each xor 0x80 (a
;     signed multiplier);
;  5. the window's sums down the chain, slot F - 1 first: nadds/nadcs add
;     the predecessor's slot j, or its slot j + 1 where S (= moved) is set,
;     to the CU's own scaling, 24 bits as three bytes (step 5);
;  6. where the window moved on, the pixel it left: the predecessor's slot
;     0 plus C_{k-1}, clamped, stored with the predecessor's last pixel
;     (step 6);
; and then the relay copies the last column's window, border and pixel
; (nget left across the ring: the last column is later in the chain, so the
; relay reads it as it stands after the round).
;
; The host writes the number of rounds - 1 into the round loop (written
; with the start MAX_ROUNDS - 1) and F - 1 into every loop over the window
; (written with the start MAX_WIDTH - 1) before it loads the program.

.const MAX_ROUNDS 48
.const MAX_WIDTH 8

; Per CU, from the host. Multi-byte values big-endian.
.var num 4                  ; this CU's border's numerator, q12_20 (stepped in place)
.var num_step 4             ; 23 times the line's step
.var den 4                  ; its denominator, q2_30, > 0
.var den_step 4
.var prev_hi MAX_ROUNDS     ; C_{k-1} at v (q8_8), 0 before the first texel
.var prev_lo MAX_ROUNDS
.var cur_hi MAX_ROUNDS      ; C_k at v, 0 past the last texel
.var cur_lo MAX_ROUNDS
.var texel_cu 1             ; 0xff in a texel CU, 0 in the relay
.var relay 1                ; 0xff in the relay, 0 in a texel CU
.var started 1              ; 0 in the CU of border 0 (round 0), else 0xff

; The same in every CU.
.var offset 4               ; (F - 1) / 2 pixel plus half a phase step, q16_16
.var slots MAX_WIDTH        ; j at j: the lookup index's high byte
.var zero 1                 ; 0x00
.var ff 1                   ; 0xff
.var c80 1                  ; 0x80
.var c7f 1                  ; 0x7f
.var c40 1                  ; 0x40
.var cc0 1                  ; 0xc0
.var none 1                 ; 0x80: the high byte of "no pixel"
.var limit 4                ; 0x00010001: a texel wider than this is magnified
.var clamp 3                ; 0x00ff01: a sum at least this is above 255 << 8

; Results, per CU.
.var idx_hi MAX_ROUNDS      ; at v: the predecessor's last pixel when the window moved on at this border
.var idx_lo MAX_ROUNDS
.var val_hi MAX_ROUNDS      ; the value of the pixel the window left, q8_8
.var val_lo MAX_ROUNDS
.var err MAX_ROUNDS         ; not 0: this round's border is out of range or its texel wider than a pixel
.var fin_hi MAX_WIDTH       ; after the loop: the window's pixels' values, q8_8
.var fin_lo MAX_WIDTH

; What the next CU of the chain reads (and the relay copies).
.var border 4               ; this round's border, q16_16
.var pixel 2                ; the window's last pixel at this border
.var s_hi MAX_WIDTH + 1     ; the window's sums, 24-bit; slot F stays 0
.var s_mid MAX_WIDTH + 1
.var s_lo MAX_WIDTH + 1

; The program's own.
.var sign 1                 ; 0xff when the numerator is negative
.var mag 4                  ; its magnitude, shifted out bit by bit
.var quot 4
.var overflow 1             ; quotient bits shifted out of quot
.var pred_border 4          ; the predecessor's border
.var pred_pixel 2           ; the predecessor's last pixel
.var phase 1
.var moved 1                ; 0xff when the window moved on at this border
.var dc_sign 1              ; 0xff when dC < 0
.var u_hi 1                 ; the bytes of |dC|, each xor 0x80 (a signed multiplier)
.var u_lo 1
.var base 3                 ; 16384 |dC| >> 8 (its low byte is 0)
.var rounding 4             ; 0x4000 - dc_sign: the rounding of -P as (P xor -1) + 1
.var g128 3                 ; 128 G, G = H_j - 16384
.var p_hi 3                 ; G x (the high byte of |dC|)

resample:
.stage setup
  mset
.rept j, 0, MAX_WIDTH
  mov [s_hi + j], [zero]
  mov [s_mid + j], [zero]
  mov [s_lo + j], [zero]
.endr
.rept b, 0, 3
  mov [border + b], [zero]
.endr
  mov [pixel], [zero]
  mov [pixel + 1], [zero]
  loop v, MAX_ROUNDS - 1, 1
.stage texcoord
    mset
    mov [err + v], [zero]
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
    mov [err + v], [ff]
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
    ; Stored for the next CU (not in the relay, which holds the last column's).
    mov r4, [texel_cu]
    mmov nz
    mov [border + 3], r3
    mov [border + 2], r2
    mov [border + 1], r1
    mov [border], r0
    mset
    ; 2. A texel wider than one pixel: this border minus the predecessor's.
    nget [pred_border + 3], left, [border + 3]
    nget [pred_border + 2], left, [border + 2]
    nget [pred_border + 1], left, [border + 1]
    nget [pred_border], left, [border]
    sub r4, r3, [pred_border + 3]
    sbc r5, r2, [pred_border + 2]
    sbc r6, r1, [pred_border + 1]
    sbc r7, r0, [pred_border]
    cmp r4, [limit + 3]
    cmpc r5, [limit + 2]
    cmpc r6, [limit + 1]
    cmpc r7, [limit]
    mmov c
    mov r4, [started]
    mand nz
    mov [err + v], [ff]
    mset
    ; The next round's numerator and denominator.
    add [num + 3], [num + 3], [num_step + 3]
    adc [num + 2], [num + 2], [num_step + 2]
    adc [num + 1], [num + 1], [num_step + 1]
    adc [num], [num], [num_step]
    add [den + 3], [den + 3], [den_step + 3]
    adc [den + 2], [den + 2], [den_step + 2]
    adc [den + 1], [den + 1], [den_step + 1]
    adc [den], [den], [den_step]
    ; s = border + offset: the window's last pixel r0:r1, the phase r2.
    add r3, r3, [offset + 3]
    adc r2, r2, [offset + 2]
    adc r1, r1, [offset + 1]
    adc r0, r0, [offset]
    mov [phase], r2
.stage transfer
    mov r4, [texel_cu]
    mmov nz
    mov [pixel], r0
    mov [pixel + 1], r1
    mset
    ; Moved on: not the first border, and the pixel is not the predecessor's.
    nget [pred_pixel], left, [pixel]
    nget [pred_pixel + 1], left, [pixel + 1]
    xor r4, r0, [pred_pixel]
    xor r5, r1, [pred_pixel + 1]
    or r4, r4, r5
    mmov nz
    mov r4, [started]
    mand nz
    getm r4
    mset
    mov [moved], r4
.stage shade
    ; dC = C_{k-1} - C_k, its sign and magnitude.
    sub r2, [prev_lo + v], [cur_lo + v]
    sbc r1, [prev_hi + v], [cur_hi + v]
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
    ; 16384 |dC| = (|dC| << 6) << 8.
    mov r3, [zero]
    shr r1, r1
    ror r2, r2
    ror r3, r3
    shr r1, r1
    ror r2, r2
    ror r3, r3
    mov [base], r1
    mov [base + 1], r2
    mov [base + 2], r3
    loop j, MAX_WIDTH - 1, 1
      ; 3. H_j = the table's entry 256 j + phase; G = H_j - 16384 in r0:r1.
      mov r0, [slots + j]
      mov r1, [phase]
      lut r0, r0
      sub r0, r0, [c40]
      ; 128 G, sign-extended to 24 bits.
      mov r2, r0
      mov r3, r1
      mov r4, [zero]
      asr r2, r2
      ror r3, r3
      ror r4, r4
      mov [g128], r2
      mov [g128 + 1], r3
      mov [g128 + 2], r4
      ; 4. G |dC|: G (u - 128) + 128 G for each byte u of |dC|, 24 bits each.
      mov r2, [u_hi]
      mul r3, r0, r2
      add r5, r5, [g128 + 2]
      adc r4, r4, [g128 + 1]
      adc r3, r3, [g128]
      mov [p_hi], r3
      mov [p_hi + 1], r4
      mov [p_hi + 2], r5
      mov r2, [u_lo]
      mul r3, r0, r2
      add r5, r5, [g128 + 2]
      adc r4, r4, [g128 + 1]
      adc r3, r3, [g128]
      ; r6 = the low product's sign extension.
      cmp [c7f], r3
      sbc r6, [zero], [zero]
      ; P = 256 (G u_hi) + G u_lo + 16384 |dC| in r2..r5 (0 <= P < 2^31).
      add r4, r4, [p_hi + 2]
      adc r3, r3, [p_hi + 1]
      adc r2, r6, [p_hi]
      add r4, r4, [base + 2]
      adc r3, r3, [base + 1]
      adc r2, r2, [base]
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
      ; Into the window's slot, where step 5 adds the chain's sum to it.
      mov r7, [texel_cu]
      mmov nz
      mov [s_lo + j], r3
      mov [s_mid + j], r2
      mov [s_hi + j], r6
      mset
    endloop
.stage transfer
    ; 5. Down the chain, slot F - 1 first: a CU whose window moved on (S)
    ; adds its predecessor's slot j + 1 (final: written before slot j),
    ; else its slot j (final: the predecessor ran this instruction first).
    mov r7, [texel_cu]
    mmov nz
    mov r7, [moved]
    loop j, MAX_WIDTH - 1, 1
      nadds [s_lo + j], left, [s_lo + j]
      nadcs [s_mid + j], left, [s_mid + j]
      nadcs [s_hi + j], left, [s_hi + j]
    endloop
    mset
    ; 6. The pixel the window left: the predecessor's slot 0 plus C_{k-1}.
    nget r4, left, [s_lo]
    nget r5, left, [s_mid]
    nget r6, left, [s_hi]
    mov [idx_hi + v], [none]
    mov [idx_lo + v], [zero]
    add r4, r4, [prev_lo + v]
    adc r5, r5, [prev_hi + v]
    adc r6, r6, [zero]
    mmov s
    getm r7
    cmp r4, [clamp + 2]
    cmpc r5, [clamp + 1]
    cmpc r6, [clamp]
    mmov c
    getm r6
    mov r2, [moved]
    mmov nz
    mov [idx_hi + v], [pred_pixel]
    mov [idx_lo + v], [pred_pixel + 1]
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
    ; The relay takes the last column's window, border and pixel.
    mov r2, [relay]
    mmov nz
    loop j, MAX_WIDTH - 1, 1
      nget [s_lo + j], left, [s_lo + j]
      nget [s_mid + j], left, [s_mid + j]
      nget [s_hi + j], left, [s_hi + j]
    endloop
    nget [border + 3], left, [border + 3]
    nget [border + 2], left, [border + 2]
    nget [border + 1], left, [border + 1]
    nget [border], left, [border]
    nget [pixel], left, [pixel]
    nget [pixel + 1], left, [pixel + 1]
    mset
    mov [started], [ff]
  endloop
  ; The window's pixels, clamped (the host reads the CU of the last border).
.stage transfer
  loop j, MAX_WIDTH - 1, 1
    mov r2, [s_lo + j]
    mov r1, [s_mid + j]
    mov r0, [s_hi + j]
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
