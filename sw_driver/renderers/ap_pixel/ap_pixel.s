; ap-pixel: the array processor as a 96-wide ALU (the study's pixel
; algorithm, docs/spec/array_processor.md). The host scan-converts and
; depth-tests each triangle itself and gives every CU the position of one
; block of K x K pixels it needs shaded; every CU evaluates the triangle's
; seven attribute planes there, C = C0 + dx * dC/dx + dy * dC/dy, once in
; full (two multiplies) and for the block's other pixels by adding the
; gradients. One entry per block size: block1 .. block5 (ap.pixel.block).
;
; Attributes, in this order: R, G, B, A (0..255), S, T (texels), Z (the
; 16-bit depth / 256, 0..255): a = 3 * attribute indexes the planes below.
; Every value is 16.8 fixed point, 24 bits, big-endian (high byte first),
; modulo 2^24.

.const ATTRS 7
.const VALUES 3 * ATTRS
.const MAX_BLOCK 5

; The triangle: its 21 values (README.md, "What the host writes"), the same
; in every CU, at the triangle's origin pixel.
.var c0 VALUES              ; C0 of attribute a at [c0 + a] (16.8)
.var gx VALUES              ; dC/dx, 8.8, at [gx + a + 1] (high), [gx + a + 2];
.var gy VALUES              ; [gx + a] is the sign byte, the program's own
; The CU's block: the offset of its bottom-left pixel from the origin, in
; pixels, signed (x to the right, y up).
.var dx 1
.var dy 1
; Results: pixel (u, v) of the block (u to the right, v up), attribute a at
; out + VALUES * (MAX_BLOCK * v + u) + a, 16.8.
.var out VALUES * MAX_BLOCK * MAX_BLOCK
; Scratch.
.var partial 3

; A block of one pixel: the full evaluation only.
block1:
.stage setup
  mset
  loop a, VALUES - 3, 3       ; the gradients' sign bytes
    mov r6, [gx + a + 1]
    mmov s
    getm r7
    mset
    mov [gx + a], r7
    mov r6, [gy + a + 1]
    mmov s
    getm r7
    mset
    mov [gy + a], r7
  endloop
.stage shade
  loop a, VALUES - 3, 3
    mov r5, [dy]
    mov r6, [gy + a + 1]
    mov r7, [gy + a + 2]
    mul r0, r6, r5            ; r0:r1:r2 = dC/dy * dy
    add r2, r2, [c0 + a + 2]
    adc r1, r1, [c0 + a + 1]
    adc r0, r0, [c0 + a]
    mov [partial], r0         ; no three registers are left for the
    mov [partial + 1], r1     ; second product: the sum waits in CMEM
    mov [partial + 2], r2
    mov r5, [dx]
    mov r6, [gx + a + 1]
    mov r7, [gx + a + 2]
    mul r0, r6, r5            ; r0:r1:r2 = dC/dx * dx
    add r2, r2, [partial + 2]
    adc r1, r1, [partial + 1]
    adc r0, r0, [partial]
    mov [out + a], r0
    mov [out + a + 1], r1
    mov [out + a + 2], r2
  endloop
  halt

; A block of 2 x 2: row 0 from the full evaluation, each row above from
; the one below plus dC/dy, each pixel from its left neighbour plus dC/dx.
block2:
.stage setup
  mset
  loop a, VALUES - 3, 3       ; the gradients' sign bytes
    mov r6, [gx + a + 1]
    mmov s
    getm r7
    mset
    mov [gx + a], r7
    mov r6, [gy + a + 1]
    mmov s
    getm r7
    mset
    mov [gy + a], r7
  endloop
.stage shade
  loop a, VALUES - 3, 3
    mov r5, [dy]
    mov r6, [gy + a + 1]
    mov r7, [gy + a + 2]
    mul r0, r6, r5            ; r0:r1:r2 = dC/dy * dy
    add r2, r2, [c0 + a + 2]
    adc r1, r1, [c0 + a + 1]
    adc r0, r0, [c0 + a]
    mov [partial], r0         ; no three registers are left for the
    mov [partial + 1], r1     ; second product: the sum waits in CMEM
    mov [partial + 2], r2
    mov r5, [dx]
    mov r6, [gx + a + 1]
    mov r7, [gx + a + 2]
    mul r0, r6, r5            ; r0:r1:r2 = dC/dx * dx
    add r2, r2, [partial + 2]
    adc r1, r1, [partial + 1]
    adc r0, r0, [partial]
    mov r3, r0
    mov r4, r1
    mov r5, r2
    mov [out + a], r0
    mov [out + a + 1], r1
    mov [out + a + 2], r2
    .rept u, 1, 1
      add r2, r2, [gx + a + 2]
      adc r1, r1, [gx + a + 1]
      adc r0, r0, [gx + a]
      mov [out + VALUES * u + a], r0
      mov [out + VALUES * u + a + 1], r1
      mov [out + VALUES * u + a + 2], r2
    .endr
    .rept v, 1, 1
      add r5, r5, [gy + a + 2]
      adc r4, r4, [gy + a + 1]
      adc r3, r3, [gy + a]
      mov r0, r3
      mov r1, r4
      mov r2, r5
      mov [out + VALUES * MAX_BLOCK * v + a], r0
      mov [out + VALUES * MAX_BLOCK * v + a + 1], r1
      mov [out + VALUES * MAX_BLOCK * v + a + 2], r2
      .rept u, 1, 1
        add r2, r2, [gx + a + 2]
        adc r1, r1, [gx + a + 1]
        adc r0, r0, [gx + a]
        mov [out + VALUES * (MAX_BLOCK * v + u) + a], r0
        mov [out + VALUES * (MAX_BLOCK * v + u) + a + 1], r1
        mov [out + VALUES * (MAX_BLOCK * v + u) + a + 2], r2
      .endr
    .endr
  endloop
  halt

; A block of 3 x 3: row 0 from the full evaluation, each row above from
; the one below plus dC/dy, each pixel from its left neighbour plus dC/dx.
block3:
.stage setup
  mset
  loop a, VALUES - 3, 3       ; the gradients' sign bytes
    mov r6, [gx + a + 1]
    mmov s
    getm r7
    mset
    mov [gx + a], r7
    mov r6, [gy + a + 1]
    mmov s
    getm r7
    mset
    mov [gy + a], r7
  endloop
.stage shade
  loop a, VALUES - 3, 3
    mov r5, [dy]
    mov r6, [gy + a + 1]
    mov r7, [gy + a + 2]
    mul r0, r6, r5            ; r0:r1:r2 = dC/dy * dy
    add r2, r2, [c0 + a + 2]
    adc r1, r1, [c0 + a + 1]
    adc r0, r0, [c0 + a]
    mov [partial], r0         ; no three registers are left for the
    mov [partial + 1], r1     ; second product: the sum waits in CMEM
    mov [partial + 2], r2
    mov r5, [dx]
    mov r6, [gx + a + 1]
    mov r7, [gx + a + 2]
    mul r0, r6, r5            ; r0:r1:r2 = dC/dx * dx
    add r2, r2, [partial + 2]
    adc r1, r1, [partial + 1]
    adc r0, r0, [partial]
    mov r3, r0
    mov r4, r1
    mov r5, r2
    mov [out + a], r0
    mov [out + a + 1], r1
    mov [out + a + 2], r2
    .rept u, 1, 2
      add r2, r2, [gx + a + 2]
      adc r1, r1, [gx + a + 1]
      adc r0, r0, [gx + a]
      mov [out + VALUES * u + a], r0
      mov [out + VALUES * u + a + 1], r1
      mov [out + VALUES * u + a + 2], r2
    .endr
    .rept v, 1, 2
      add r5, r5, [gy + a + 2]
      adc r4, r4, [gy + a + 1]
      adc r3, r3, [gy + a]
      mov r0, r3
      mov r1, r4
      mov r2, r5
      mov [out + VALUES * MAX_BLOCK * v + a], r0
      mov [out + VALUES * MAX_BLOCK * v + a + 1], r1
      mov [out + VALUES * MAX_BLOCK * v + a + 2], r2
      .rept u, 1, 2
        add r2, r2, [gx + a + 2]
        adc r1, r1, [gx + a + 1]
        adc r0, r0, [gx + a]
        mov [out + VALUES * (MAX_BLOCK * v + u) + a], r0
        mov [out + VALUES * (MAX_BLOCK * v + u) + a + 1], r1
        mov [out + VALUES * (MAX_BLOCK * v + u) + a + 2], r2
      .endr
    .endr
  endloop
  halt

; A block of 4 x 4: row 0 from the full evaluation, each row above from
; the one below plus dC/dy, each pixel from its left neighbour plus dC/dx.
block4:
.stage setup
  mset
  loop a, VALUES - 3, 3       ; the gradients' sign bytes
    mov r6, [gx + a + 1]
    mmov s
    getm r7
    mset
    mov [gx + a], r7
    mov r6, [gy + a + 1]
    mmov s
    getm r7
    mset
    mov [gy + a], r7
  endloop
.stage shade
  loop a, VALUES - 3, 3
    mov r5, [dy]
    mov r6, [gy + a + 1]
    mov r7, [gy + a + 2]
    mul r0, r6, r5            ; r0:r1:r2 = dC/dy * dy
    add r2, r2, [c0 + a + 2]
    adc r1, r1, [c0 + a + 1]
    adc r0, r0, [c0 + a]
    mov [partial], r0         ; no three registers are left for the
    mov [partial + 1], r1     ; second product: the sum waits in CMEM
    mov [partial + 2], r2
    mov r5, [dx]
    mov r6, [gx + a + 1]
    mov r7, [gx + a + 2]
    mul r0, r6, r5            ; r0:r1:r2 = dC/dx * dx
    add r2, r2, [partial + 2]
    adc r1, r1, [partial + 1]
    adc r0, r0, [partial]
    mov r3, r0
    mov r4, r1
    mov r5, r2
    mov [out + a], r0
    mov [out + a + 1], r1
    mov [out + a + 2], r2
    .rept u, 1, 3
      add r2, r2, [gx + a + 2]
      adc r1, r1, [gx + a + 1]
      adc r0, r0, [gx + a]
      mov [out + VALUES * u + a], r0
      mov [out + VALUES * u + a + 1], r1
      mov [out + VALUES * u + a + 2], r2
    .endr
    .rept v, 1, 3
      add r5, r5, [gy + a + 2]
      adc r4, r4, [gy + a + 1]
      adc r3, r3, [gy + a]
      mov r0, r3
      mov r1, r4
      mov r2, r5
      mov [out + VALUES * MAX_BLOCK * v + a], r0
      mov [out + VALUES * MAX_BLOCK * v + a + 1], r1
      mov [out + VALUES * MAX_BLOCK * v + a + 2], r2
      .rept u, 1, 3
        add r2, r2, [gx + a + 2]
        adc r1, r1, [gx + a + 1]
        adc r0, r0, [gx + a]
        mov [out + VALUES * (MAX_BLOCK * v + u) + a], r0
        mov [out + VALUES * (MAX_BLOCK * v + u) + a + 1], r1
        mov [out + VALUES * (MAX_BLOCK * v + u) + a + 2], r2
      .endr
    .endr
  endloop
  halt

; A block of 5 x 5: row 0 from the full evaluation, each row above from
; the one below plus dC/dy, each pixel from its left neighbour plus dC/dx.
block5:
.stage setup
  mset
  loop a, VALUES - 3, 3       ; the gradients' sign bytes
    mov r6, [gx + a + 1]
    mmov s
    getm r7
    mset
    mov [gx + a], r7
    mov r6, [gy + a + 1]
    mmov s
    getm r7
    mset
    mov [gy + a], r7
  endloop
.stage shade
  loop a, VALUES - 3, 3
    mov r5, [dy]
    mov r6, [gy + a + 1]
    mov r7, [gy + a + 2]
    mul r0, r6, r5            ; r0:r1:r2 = dC/dy * dy
    add r2, r2, [c0 + a + 2]
    adc r1, r1, [c0 + a + 1]
    adc r0, r0, [c0 + a]
    mov [partial], r0         ; no three registers are left for the
    mov [partial + 1], r1     ; second product: the sum waits in CMEM
    mov [partial + 2], r2
    mov r5, [dx]
    mov r6, [gx + a + 1]
    mov r7, [gx + a + 2]
    mul r0, r6, r5            ; r0:r1:r2 = dC/dx * dx
    add r2, r2, [partial + 2]
    adc r1, r1, [partial + 1]
    adc r0, r0, [partial]
    mov r3, r0
    mov r4, r1
    mov r5, r2
    mov [out + a], r0
    mov [out + a + 1], r1
    mov [out + a + 2], r2
    .rept u, 1, 4
      add r2, r2, [gx + a + 2]
      adc r1, r1, [gx + a + 1]
      adc r0, r0, [gx + a]
      mov [out + VALUES * u + a], r0
      mov [out + VALUES * u + a + 1], r1
      mov [out + VALUES * u + a + 2], r2
    .endr
    .rept v, 1, 4
      add r5, r5, [gy + a + 2]
      adc r4, r4, [gy + a + 1]
      adc r3, r3, [gy + a]
      mov r0, r3
      mov r1, r4
      mov r2, r5
      mov [out + VALUES * MAX_BLOCK * v + a], r0
      mov [out + VALUES * MAX_BLOCK * v + a + 1], r1
      mov [out + VALUES * MAX_BLOCK * v + a + 2], r2
      .rept u, 1, 4
        add r2, r2, [gx + a + 2]
        adc r1, r1, [gx + a + 1]
        adc r0, r0, [gx + a]
        mov [out + VALUES * (MAX_BLOCK * v + u) + a], r0
        mov [out + VALUES * (MAX_BLOCK * v + u) + a + 1], r1
        mov [out + VALUES * (MAX_BLOCK * v + u) + a + 2], r2
      .endr
    .endr
  endloop
  halt
