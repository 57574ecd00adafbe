; ap-pixel's study program: the pixel algorithm
; (docs/spec/array_processor.md, "ap-pixel") as the study's own code ran
; it on the board, in the shape the vendor's compiler (SEL) gives it
; (README.md, "The study program"): every variable in CMEM, each statement
; loading its operands, computing and storing its result, no value kept in
; a register from one statement to the next. Chosen with
; ap.pixel.program=study; ap_pixel.s is the default, `tuned`.
;
; Per attribute, on 16-bit 8.8 values (big-endian, modulo 2^16):
;   t = dC/dy * dy              a signed 16 x 8 multiplication
;   out(0, 0) = C0 + t          a 16-bit addition
;   t = dC/dx * dx              a signed 16 x 8 multiplication
;   out(0, 0) = out(0, 0) + t   a 16-bit addition
; and for a block of k x k pixels each further pixel from its neighbour,
; left or (first column) below: out(u, v) = out(u - 1, v) + dC/dx, or
; out(0, v) = out(0, v - 1) + dC/dy, one addition per attribute and pixel.
;
; The compiler's code (README.md, "The study program", says why):
; - a multiplication loads its operands into registers and runs `mul`, the
;   CU's 16 x 8 repeated addition (8 shift-and-add steps, the study's 40
;   cycles at register level), and stores the product's low 16 bits;
; - an addition is the calibrated 16-bit pair add/adc with every operand
;   in CMEM (the study's 64 ns pass), low byte first;
; - the attribute loop is the language's one loop form, counting down.
;
; Entries: block1 .. block5 (ap.pixel.block = k) evaluate the ATTRS
; attributes of the triangle's 21 values; shade1 .. shade7 evaluate the
; first n attributes of one pixel (the study's shading test ran six:
; study_shading --attributes).
;
; Attributes, in this order: R, G, B, A (0..255), S, T (texels, modulo 256),
; Z (the 16-bit depth / 256): a = 2 * attribute indexes the arrays below.

.const ATTRS 7
.const VALUES 2 * ATTRS
.const MAX_BLOCK 5

; The triangle's values, the same in every CU.
.var c0 VALUES              ; C0 of attribute a at [c0 + a], 8.8
.var gx VALUES              ; dC/dx, 8.8
.var gy VALUES              ; dC/dy, 8.8
; The CU's block: the offset of its bottom-left pixel from the origin, in
; pixels, signed (x to the right, y up).
.var dx 1
.var dy 1
; Results: pixel (u, v) of the block, attribute a at
; out + VALUES * (MAX_BLOCK * v + u) + a, 8.8.
.var out VALUES * MAX_BLOCK * MAX_BLOCK
; The compiler's temporary: a product.
.var t 2

; A block of 1 x 1: the full evaluation only.
block1:
.stage shade
  mset
  loop a, VALUES - 2, 2
    mov r0, [gy + a]            ; t = dC/dy * dy
    mov r1, [gy + a + 1]
    mov r2, [dy]
    mul r3, r0, r2
    mov [t], r4
    mov [t + 1], r5
    add [out + a + 1], [c0 + a + 1], [t + 1]   ; out = C0 + t
    adc [out + a], [c0 + a], [t]
    mov r0, [gx + a]            ; t = dC/dx * dx
    mov r1, [gx + a + 1]
    mov r2, [dx]
    mul r3, r0, r2
    mov [t], r4
    mov [t + 1], r5
    add [out + a + 1], [out + a + 1], [t + 1]  ; out = out + t
    adc [out + a], [out + a], [t]
  endloop
  halt

; A block of 2 x 2: pixel (0, 0) in full, row 0 from the left
; neighbours, each row above from the pixel below its first and then from
; the left.
block2:
.stage shade
  mset
  loop a, VALUES - 2, 2
    mov r0, [gy + a]            ; t = dC/dy * dy
    mov r1, [gy + a + 1]
    mov r2, [dy]
    mul r3, r0, r2
    mov [t], r4
    mov [t + 1], r5
    add [out + a + 1], [c0 + a + 1], [t + 1]   ; out = C0 + t
    adc [out + a], [c0 + a], [t]
    mov r0, [gx + a]            ; t = dC/dx * dx
    mov r1, [gx + a + 1]
    mov r2, [dx]
    mul r3, r0, r2
    mov [t], r4
    mov [t + 1], r5
    add [out + a + 1], [out + a + 1], [t + 1]  ; out = out + t
    adc [out + a], [out + a], [t]
    .rept u, 1, 1
      add [out + VALUES * u + a + 1], [out + VALUES * (u - 1) + a + 1], [gx + a + 1]
      adc [out + VALUES * u + a], [out + VALUES * (u - 1) + a], [gx + a]
    .endr
    .rept v, 1, 1
      add [out + VALUES * MAX_BLOCK * v + a + 1], [out + VALUES * MAX_BLOCK * (v - 1) + a + 1], [gy + a + 1]
      adc [out + VALUES * MAX_BLOCK * v + a], [out + VALUES * MAX_BLOCK * (v - 1) + a], [gy + a]
      .rept u, 1, 1
        add [out + VALUES * (MAX_BLOCK * v + u) + a + 1], [out + VALUES * (MAX_BLOCK * v + u - 1) + a + 1], [gx + a + 1]
        adc [out + VALUES * (MAX_BLOCK * v + u) + a], [out + VALUES * (MAX_BLOCK * v + u - 1) + a], [gx + a]
      .endr
    .endr
  endloop
  halt

; A block of 3 x 3: pixel (0, 0) in full, row 0 from the left
; neighbours, each row above from the pixel below its first and then from
; the left.
block3:
.stage shade
  mset
  loop a, VALUES - 2, 2
    mov r0, [gy + a]            ; t = dC/dy * dy
    mov r1, [gy + a + 1]
    mov r2, [dy]
    mul r3, r0, r2
    mov [t], r4
    mov [t + 1], r5
    add [out + a + 1], [c0 + a + 1], [t + 1]   ; out = C0 + t
    adc [out + a], [c0 + a], [t]
    mov r0, [gx + a]            ; t = dC/dx * dx
    mov r1, [gx + a + 1]
    mov r2, [dx]
    mul r3, r0, r2
    mov [t], r4
    mov [t + 1], r5
    add [out + a + 1], [out + a + 1], [t + 1]  ; out = out + t
    adc [out + a], [out + a], [t]
    .rept u, 1, 2
      add [out + VALUES * u + a + 1], [out + VALUES * (u - 1) + a + 1], [gx + a + 1]
      adc [out + VALUES * u + a], [out + VALUES * (u - 1) + a], [gx + a]
    .endr
    .rept v, 1, 2
      add [out + VALUES * MAX_BLOCK * v + a + 1], [out + VALUES * MAX_BLOCK * (v - 1) + a + 1], [gy + a + 1]
      adc [out + VALUES * MAX_BLOCK * v + a], [out + VALUES * MAX_BLOCK * (v - 1) + a], [gy + a]
      .rept u, 1, 2
        add [out + VALUES * (MAX_BLOCK * v + u) + a + 1], [out + VALUES * (MAX_BLOCK * v + u - 1) + a + 1], [gx + a + 1]
        adc [out + VALUES * (MAX_BLOCK * v + u) + a], [out + VALUES * (MAX_BLOCK * v + u - 1) + a], [gx + a]
      .endr
    .endr
  endloop
  halt

; A block of 4 x 4: pixel (0, 0) in full, row 0 from the left
; neighbours, each row above from the pixel below its first and then from
; the left.
block4:
.stage shade
  mset
  loop a, VALUES - 2, 2
    mov r0, [gy + a]            ; t = dC/dy * dy
    mov r1, [gy + a + 1]
    mov r2, [dy]
    mul r3, r0, r2
    mov [t], r4
    mov [t + 1], r5
    add [out + a + 1], [c0 + a + 1], [t + 1]   ; out = C0 + t
    adc [out + a], [c0 + a], [t]
    mov r0, [gx + a]            ; t = dC/dx * dx
    mov r1, [gx + a + 1]
    mov r2, [dx]
    mul r3, r0, r2
    mov [t], r4
    mov [t + 1], r5
    add [out + a + 1], [out + a + 1], [t + 1]  ; out = out + t
    adc [out + a], [out + a], [t]
    .rept u, 1, 3
      add [out + VALUES * u + a + 1], [out + VALUES * (u - 1) + a + 1], [gx + a + 1]
      adc [out + VALUES * u + a], [out + VALUES * (u - 1) + a], [gx + a]
    .endr
    .rept v, 1, 3
      add [out + VALUES * MAX_BLOCK * v + a + 1], [out + VALUES * MAX_BLOCK * (v - 1) + a + 1], [gy + a + 1]
      adc [out + VALUES * MAX_BLOCK * v + a], [out + VALUES * MAX_BLOCK * (v - 1) + a], [gy + a]
      .rept u, 1, 3
        add [out + VALUES * (MAX_BLOCK * v + u) + a + 1], [out + VALUES * (MAX_BLOCK * v + u - 1) + a + 1], [gx + a + 1]
        adc [out + VALUES * (MAX_BLOCK * v + u) + a], [out + VALUES * (MAX_BLOCK * v + u - 1) + a], [gx + a]
      .endr
    .endr
  endloop
  halt

; A block of 5 x 5: pixel (0, 0) in full, row 0 from the left
; neighbours, each row above from the pixel below its first and then from
; the left.
block5:
.stage shade
  mset
  loop a, VALUES - 2, 2
    mov r0, [gy + a]            ; t = dC/dy * dy
    mov r1, [gy + a + 1]
    mov r2, [dy]
    mul r3, r0, r2
    mov [t], r4
    mov [t + 1], r5
    add [out + a + 1], [c0 + a + 1], [t + 1]   ; out = C0 + t
    adc [out + a], [c0 + a], [t]
    mov r0, [gx + a]            ; t = dC/dx * dx
    mov r1, [gx + a + 1]
    mov r2, [dx]
    mul r3, r0, r2
    mov [t], r4
    mov [t + 1], r5
    add [out + a + 1], [out + a + 1], [t + 1]  ; out = out + t
    adc [out + a], [out + a], [t]
    .rept u, 1, 4
      add [out + VALUES * u + a + 1], [out + VALUES * (u - 1) + a + 1], [gx + a + 1]
      adc [out + VALUES * u + a], [out + VALUES * (u - 1) + a], [gx + a]
    .endr
    .rept v, 1, 4
      add [out + VALUES * MAX_BLOCK * v + a + 1], [out + VALUES * MAX_BLOCK * (v - 1) + a + 1], [gy + a + 1]
      adc [out + VALUES * MAX_BLOCK * v + a], [out + VALUES * MAX_BLOCK * (v - 1) + a], [gy + a]
      .rept u, 1, 4
        add [out + VALUES * (MAX_BLOCK * v + u) + a + 1], [out + VALUES * (MAX_BLOCK * v + u - 1) + a + 1], [gx + a + 1]
        adc [out + VALUES * (MAX_BLOCK * v + u) + a], [out + VALUES * (MAX_BLOCK * v + u - 1) + a], [gx + a]
      .endr
    .endr
  endloop
  halt

; The shading test's entries: one pixel, n attributes (the loop's count
; is a constant of the compiled program, so one entry per count).

; One pixel, the first 1 attribute.
shade1:
.stage shade
  mset
  loop a, 2 * (1 - 1), 2
    mov r0, [gy + a]            ; t = dC/dy * dy
    mov r1, [gy + a + 1]
    mov r2, [dy]
    mul r3, r0, r2
    mov [t], r4
    mov [t + 1], r5
    add [out + a + 1], [c0 + a + 1], [t + 1]   ; out = C0 + t
    adc [out + a], [c0 + a], [t]
    mov r0, [gx + a]            ; t = dC/dx * dx
    mov r1, [gx + a + 1]
    mov r2, [dx]
    mul r3, r0, r2
    mov [t], r4
    mov [t + 1], r5
    add [out + a + 1], [out + a + 1], [t + 1]  ; out = out + t
    adc [out + a], [out + a], [t]
  endloop
  halt

; One pixel, the first 2 attributes.
shade2:
.stage shade
  mset
  loop a, 2 * (2 - 1), 2
    mov r0, [gy + a]            ; t = dC/dy * dy
    mov r1, [gy + a + 1]
    mov r2, [dy]
    mul r3, r0, r2
    mov [t], r4
    mov [t + 1], r5
    add [out + a + 1], [c0 + a + 1], [t + 1]   ; out = C0 + t
    adc [out + a], [c0 + a], [t]
    mov r0, [gx + a]            ; t = dC/dx * dx
    mov r1, [gx + a + 1]
    mov r2, [dx]
    mul r3, r0, r2
    mov [t], r4
    mov [t + 1], r5
    add [out + a + 1], [out + a + 1], [t + 1]  ; out = out + t
    adc [out + a], [out + a], [t]
  endloop
  halt

; One pixel, the first 3 attributes.
shade3:
.stage shade
  mset
  loop a, 2 * (3 - 1), 2
    mov r0, [gy + a]            ; t = dC/dy * dy
    mov r1, [gy + a + 1]
    mov r2, [dy]
    mul r3, r0, r2
    mov [t], r4
    mov [t + 1], r5
    add [out + a + 1], [c0 + a + 1], [t + 1]   ; out = C0 + t
    adc [out + a], [c0 + a], [t]
    mov r0, [gx + a]            ; t = dC/dx * dx
    mov r1, [gx + a + 1]
    mov r2, [dx]
    mul r3, r0, r2
    mov [t], r4
    mov [t + 1], r5
    add [out + a + 1], [out + a + 1], [t + 1]  ; out = out + t
    adc [out + a], [out + a], [t]
  endloop
  halt

; One pixel, the first 4 attributes.
shade4:
.stage shade
  mset
  loop a, 2 * (4 - 1), 2
    mov r0, [gy + a]            ; t = dC/dy * dy
    mov r1, [gy + a + 1]
    mov r2, [dy]
    mul r3, r0, r2
    mov [t], r4
    mov [t + 1], r5
    add [out + a + 1], [c0 + a + 1], [t + 1]   ; out = C0 + t
    adc [out + a], [c0 + a], [t]
    mov r0, [gx + a]            ; t = dC/dx * dx
    mov r1, [gx + a + 1]
    mov r2, [dx]
    mul r3, r0, r2
    mov [t], r4
    mov [t + 1], r5
    add [out + a + 1], [out + a + 1], [t + 1]  ; out = out + t
    adc [out + a], [out + a], [t]
  endloop
  halt

; One pixel, the first 5 attributes.
shade5:
.stage shade
  mset
  loop a, 2 * (5 - 1), 2
    mov r0, [gy + a]            ; t = dC/dy * dy
    mov r1, [gy + a + 1]
    mov r2, [dy]
    mul r3, r0, r2
    mov [t], r4
    mov [t + 1], r5
    add [out + a + 1], [c0 + a + 1], [t + 1]   ; out = C0 + t
    adc [out + a], [c0 + a], [t]
    mov r0, [gx + a]            ; t = dC/dx * dx
    mov r1, [gx + a + 1]
    mov r2, [dx]
    mul r3, r0, r2
    mov [t], r4
    mov [t + 1], r5
    add [out + a + 1], [out + a + 1], [t + 1]  ; out = out + t
    adc [out + a], [out + a], [t]
  endloop
  halt

; One pixel, the first 6 attributes.
shade6:
.stage shade
  mset
  loop a, 2 * (6 - 1), 2
    mov r0, [gy + a]            ; t = dC/dy * dy
    mov r1, [gy + a + 1]
    mov r2, [dy]
    mul r3, r0, r2
    mov [t], r4
    mov [t + 1], r5
    add [out + a + 1], [c0 + a + 1], [t + 1]   ; out = C0 + t
    adc [out + a], [c0 + a], [t]
    mov r0, [gx + a]            ; t = dC/dx * dx
    mov r1, [gx + a + 1]
    mov r2, [dx]
    mul r3, r0, r2
    mov [t], r4
    mov [t + 1], r5
    add [out + a + 1], [out + a + 1], [t + 1]  ; out = out + t
    adc [out + a], [out + a], [t]
  endloop
  halt

; One pixel, the first 7 attributes.
shade7:
.stage shade
  mset
  loop a, 2 * (7 - 1), 2
    mov r0, [gy + a]            ; t = dC/dy * dy
    mov r1, [gy + a + 1]
    mov r2, [dy]
    mul r3, r0, r2
    mov [t], r4
    mov [t + 1], r5
    add [out + a + 1], [c0 + a + 1], [t + 1]   ; out = C0 + t
    adc [out + a], [c0 + a], [t]
    mov r0, [gx + a]            ; t = dC/dx * dx
    mov r1, [gx + a + 1]
    mov r2, [dx]
    mul r3, r0, r2
    mov [t], r4
    mov [t + 1], r5
    add [out + a + 1], [out + a + 1], [t + 1]  ; out = out + t
    adc [out + a], [out + a], [t]
  endloop
  halt
