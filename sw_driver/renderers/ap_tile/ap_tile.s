; ap-tile: the array processor as an intelligent frame buffer (the study's
; tile algorithm, docs/spec/array_processor.md). Every CU owns one tile of
; TILE_W x TILE_H pixels and draws into it the one triangle the host gave it
; for this pass. The host runs the stages as separate entries, in order:
; fill, depth, colour, texcoord (README.md, "The program").
;
; Pixels are addressed [plane + TILE_H * x + l]: one plane of TILE_H bytes
; per tile column x (0 = left), l the row in the tile (0 = top). The row
; loops count l down, TILE_H - 1 first, so a tile is walked bottom to top,
; and each row is unrolled right to left (x = TILE_W - 1 first), as the
; study did. 16- and 24-bit values are big-endian (the high byte first);
; colour, depth and texture coordinates are kept in separate planes for
; their high and low bytes, so that one CIU word holds the same byte of four
; CUs' pixels.

.const TILE_W 8
.const TILE_H 36
.const PIXELS TILE_W * TILE_H

; The tile's buffers.
.var chi PIXELS             ; colour, RGB565: R4..0 G5..3
.var clo PIXELS             ; G2..0 B4..0
.var zhi PIXELS             ; depth, 16-bit unsigned, smaller is nearer
.var zlo PIXELS
.var shi PIXELS             ; texture coordinate s in texels, 8.8
.var slo PIXELS
.var thi PIXELS             ; texture coordinate t in texels, 8.8
.var tlo PIXELS
.var tid PIXELS             ; the pixel's texture (0: none)
.var we PIXELS              ; write enable: 0xff where the pixel is drawn

; The triangle record, written by the host before every pass. Values at the
; tile's bottom-right pixel (x = TILE_W - 1, l = TILE_H - 1), steps per
; pixel to the left (du) and per row up (dv).
.var live 1                 ; 0xff: this CU has a triangle in this pass
.var e0 6                   ; three edge functions, signed 16-bit
.var edu 6
.var edv 6
.var z0 3                   ; depth, 16.8 unsigned (modulo 2^24)
.var zdu 3
.var zdv 3
.var c0 6                   ; R, G, B scaled to 5, 6, 5 bits, 8.8
.var cdu 6
.var cdv 6
.var st0 4                  ; s, t in texels, 8.8 (modulo 2^16)
.var stdu 4
.var stdv 4
.var tex 1                  ; the triangle's texture (0: none)
.var zlequal 1              ; 0xff: the depth test passes on equal depths (GL_LEQUAL)
.var zoff 1                 ; 0xff: no depth test
.var zwrite 1               ; 0xff: depth writes on

; Constants the host writes once: yc[l] = TILE_H - 1 - l, the row's height
; above the tile's bottom row, and 0; and the values a clear stores.
.var yc TILE_H
.var zero 1
.var clear_c 2
.var clear_z 2

; Scratch: the values at the first pixel of the current row.
.var erow 6
.var crow 6
.var strow 4

; Fill: the write enable of every pixel from the three edge functions. Each
; row starts from the bottom-right value plus edv times the row's height
; (one multiply per edge per row), then steps edu per pixel to the left.
fill:
.stage fill
  loop l, TILE_H - 1, 1
    mset
    mov r5, [yc + l]
    .rept e, 0, 2
      mov r6, [edv + 2 * e]
      mov r7, [edv + 2 * e + 1]
      mul r2, r6, r5              ; r2:r3:r4 = edv * rows above the bottom
      add r4, r4, [e0 + 2 * e + 1]
      adc r3, r3, [e0 + 2 * e]
      mov [erow + 2 * e], r3
      mov [erow + 2 * e + 1], r4
    .endr
    mov r0, [erow]
    mov r1, [erow + 1]
    mov r2, [erow + 2]
    mov r3, [erow + 3]
    mov r4, [erow + 4]
    mov r5, [erow + 5]
    .rept x, TILE_W - 1, 0
      mov r7, [live]
      mmov s
      mov r7, r0                  ; S: edge 0 negative
      mand ns
      mov r7, r2
      mand ns
      mov r7, r4
      mand ns
      getm r7
      mset
      mov [we + TILE_H * x + l], r7
      add r1, r1, [edu + 1]
      adc r0, r0, [edu]
      add r3, r3, [edu + 3]
      adc r2, r2, [edu + 2]
      add r5, r5, [edu + 5]
      adc r4, r4, [edu + 4]
    .endr
  endloop
  halt

; Depth: z interpolated in 16.8 and compared with the buffer; the write
; enable keeps the pixels that pass (all of them when zoff is set), and the
; depth buffer takes their depth when zwrite is set.
depth:
.stage depth
  mov r0, [z0]
  mov r1, [z0 + 1]
  mov r2, [z0 + 2]
  loop l, TILE_H - 1, 1
    mov r3, r0
    mov r4, r1
    mov r5, r2
    .rept x, TILE_W - 1, 0
      mov r7, [we + TILE_H * x + l]
      mmov s
      sub r6, [zlo + TILE_H * x + l], r4
      sbc r7, [zhi + TILE_H * x + l], r3
      mand c                      ; buffer >= z
      or r6, r6, r7
      or r6, r6, [zlequal]
      mand nz                     ; and not equal, unless the test is GL_LEQUAL
      getm r7
      mov r6, [we + TILE_H * x + l]
      and r6, r6, [zoff]
      or r7, r7, r6               ; pass, or drawn with the test off
      mset
      mov [we + TILE_H * x + l], r7
      and r7, r7, [zwrite]
      mmov s
      mov [zhi + TILE_H * x + l], r3
      mov [zlo + TILE_H * x + l], r4
      add r5, r5, [zdu + 2]
      adc r4, r4, [zdu + 1]
      adc r3, r3, [zdu]
    .endr
    add r2, r2, [zdv + 2]
    adc r1, r1, [zdv + 1]
    adc r0, r0, [zdv]
  endloop
  halt

; Colour: R, G, B interpolated in 8.8 (already scaled to 31, 63, 31 and
; rounded by the host's bias), packed to RGB565 and stored where the write
; enable is set.
colour:
.stage colour
  mset
  .rept k, 0, 5
    mov [crow + k], [c0 + k]
  .endr
  loop l, TILE_H - 1, 1
    mov r0, [crow]
    mov r1, [crow + 1]
    mov r2, [crow + 2]
    mov r3, [crow + 3]
    mov r4, [crow + 4]
    mov r5, [crow + 5]
    .rept x, TILE_W - 1, 0
      mov r7, [we + TILE_H * x + l]
      mmov s
      mov r6, r0                  ; R << 3
      shl r6, r6
      shl r6, r6
      shl r6, r6
      mov r7, r2                  ; G >> 3
      shr r7, r7
      shr r7, r7
      shr r7, r7
      or r6, r6, r7
      mov [chi + TILE_H * x + l], r6
      mov r6, r2                  ; G << 5
      shl r6, r6
      shl r6, r6
      shl r6, r6
      shl r6, r6
      shl r6, r6
      or r6, r6, r4
      mov [clo + TILE_H * x + l], r6
      add r1, r1, [cdu + 1]
      adc r0, r0, [cdu]
      add r3, r3, [cdu + 3]
      adc r2, r2, [cdu + 2]
      add r5, r5, [cdu + 5]
      adc r4, r4, [cdu + 4]
    .endr
    mset
    .rept k, 0, 2
      add [crow + 2 * k + 1], [crow + 2 * k + 1], [cdv + 2 * k + 1]
      adc [crow + 2 * k], [crow + 2 * k], [cdv + 2 * k]
    .endr
  endloop
  halt

; Texture coordinates: s and t interpolated in 8.8 texels and stored with
; the triangle's texture number where the write enable is set; the host
; looks the texels up when it reads the frame back.
texcoord:
.stage texcoord
  mset
  .rept k, 0, 3
    mov [strow + k], [st0 + k]
  .endr
  loop l, TILE_H - 1, 1
    mov r0, [strow]
    mov r1, [strow + 1]
    mov r2, [strow + 2]
    mov r3, [strow + 3]
    .rept x, TILE_W - 1, 0
      mov r7, [we + TILE_H * x + l]
      mmov s
      mov [shi + TILE_H * x + l], r0
      mov [slo + TILE_H * x + l], r1
      mov [thi + TILE_H * x + l], r2
      mov [tlo + TILE_H * x + l], r3
      mov [tid + TILE_H * x + l], [tex]
      add r1, r1, [stdu + 1]
      adc r0, r0, [stdu]
      add r3, r3, [stdu + 3]
      adc r2, r2, [stdu + 2]
    .endr
    mset
    .rept k, 0, 1
      add [strow + 2 * k + 1], [strow + 2 * k + 1], [stdv + 2 * k + 1]
      adc [strow + 2 * k], [strow + 2 * k], [stdv + 2 * k]
    .endr
  endloop
  halt

; Clears: every pixel of the tile takes the value the host wrote.
clear_colour:
.stage transfer
  mset
  loop l, TILE_H - 1, 1
    .rept x, TILE_W - 1, 0
      mov [chi + TILE_H * x + l], [clear_c]
      mov [clo + TILE_H * x + l], [clear_c + 1]
      mov [tid + TILE_H * x + l], [zero]
    .endr
  endloop
  halt

clear_depth:
.stage transfer
  mset
  loop l, TILE_H - 1, 1
    .rept x, TILE_W - 1, 0
      mov [zhi + TILE_H * x + l], [clear_z]
      mov [zlo + TILE_H * x + l], [clear_z + 1]
    .endr
  endloop
  halt
