; ap-tile as the study wrote it (docs/spec/study_programs.md, "ap-tile as
; the study wrote it"): the program the vendor's compiler (SEL) made of the
; study's source, so that the board comparisons run a program of the same
; shape. ap_tile.s is the tuned program; the host picks one with
; ap.tile.program (README.md, "The study's program").
;
; What SEL emits, and so what this file is written as:
; - Every variable lives in CMEM. A statement loads its operands into
;   registers, computes and stores its result; nothing stays in a register
;   from one statement to the next.
; - No immediates: 0, 1 come from words the host wrote (XCOUNTER[0] is the
;   0, `one` the 1), as do the counter tables the pixel's x and y are read
;   from.
; - A 16-bit array is two planes of bytes (high, low): the AC's address
;   generator adds a loop variable unscaled, so the element (x, y) of every
;   array is at plane + TILE_H * x + y, the row loop's y indexes it and the
;   hand-unrolled x loop is the constant TILE_H * x.
; - Loops count down, so the tile is walked from the bottom-right pixel
;   (x = 7, y = 35) to the top-left. The first pixel of a row takes the
;   row's start value (the reset); every other pixel steps from its
;   neighbour on the right by the x delta; the row start steps by the y
;   delta. Every step is one 16-bit subtraction, A and B being per pixel
;   right and per row down.
; - A 16 x 8 multiplication of CMEM variables is the calibrated CMEM
;   multiplication (`mulm`: docs/spec/calibration.md's 1093.44 ns, the
;   repeated addition SEL makes of it), its 24-bit product stored and the
;   low 16 bits copied into the 16-bit variable.

.const TILE_W 8
.const TILE_H 36
.const PIXELS TILE_W * TILE_H

; The tile's buffers.
.var rg_hi PIXELS           ; colour, red: the high byte of the red-green array
.var rg_lo PIXELS           ; green: its low byte
.var b PIXELS               ; blue, its own 8-bit array
.var zb_hi PIXELS           ; depth, 16-bit unsigned, smaller is nearer
.var zb_lo PIXELS
.var we PIXELS              ; write enable: 1 where the pixel is drawn
.var s_hi PIXELS            ; texture coordinates s, t in texels, 8.8
.var s_lo PIXELS
.var t_hi PIXELS
.var t_lo PIXELS
.var tid PIXELS             ; the pixel's texture (0: none)

; What the host writes before every pass, each 16-bit value big-endian.
; Line k: E = A x + B y + C, x the tile column from the left, y the row
; from the top, inside where E >= 0.
.var line_a 6               ; A, per pixel right, signed
.var line_b 6               ; B, per row down, signed
.var line_c 6               ; C, the value at the tile's top-left pixel
.var z_start 2              ; depth at the bottom-right pixel
.var z_dx 2                 ; per pixel right
.var z_dy 2                 ; per row down
.var c_start 6              ; red, green, blue in 8.8 at the bottom-right pixel
.var c_dx 6
.var c_dy 6
.var st_start 4             ; s, t in 8.8 at the bottom-right pixel
.var st_dx 4
.var st_dy 4
.var tex 1                  ; the triangle's texture (0: none)

; Constants the host writes once.
.var xpos 1                 ; the CU's column in the grid
.var ypos 1                 ; its row
.var one 1                  ; 0x01
.var ff 1                   ; 0xff
.var xcounter TILE_W        ; 0, 1, .., TILE_W - 1
.var ycounter TILE_H        ; 0, 1, .., TILE_H - 1
.var clear_rg 2             ; what a colour clear stores: red, green
.var clear_b 1              ; blue
.var clear_z 2              ; what a depth clear stores

; The program's own variables.
.var product 3              ; a 16 x 8 product, 24 bits (high, middle, low)
.var px 2                   ; A times the x offset
.var py 2                   ; B times the y offset
.var erow 2                 ; the line's value at the current row's first pixel
.var ev 2                   ; the line's value at the current pixel
.var zrow 2
.var zv 2
.var flag 1                 ; z < the depth buffer's value
.var crow 6
.var cv 6
.var rgw 2                  ; the pixel's colour in the stored format
.var bw 1
.var strow 4
.var stv 4

; Triangle fill: every write enable set to 1, then per line the value at
; the bottom-right pixel from two multiplications (A x XCOUNTER[7],
; B x YCOUNTER[35]) plus C, and a walk over the tile clearing the write
; enable where the value is negative.
fill:
.stage fill
  mset
  loop y, TILE_H - 1, 1
    .rept x, TILE_W - 1, 0
      mov r0, [one]
      mov [we + TILE_H * x + y], r0
    .endr
  endloop
  .rept k, 0, 2
    ; px = A * XCOUNTER[TILE_W - 1]
    mulm [product], [line_a + 2 * k], [xcounter + TILE_W - 1]
    mov r0, [product + 1]
    mov [px], r0
    mov r0, [product + 2]
    mov [px + 1], r0
    ; py = B * YCOUNTER[TILE_H - 1]
    mulm [product], [line_b + 2 * k], [ycounter + TILE_H - 1]
    mov r0, [product + 1]
    mov [py], r0
    mov r0, [product + 2]
    mov [py + 1], r0
    ; erow = C + px; erow = erow + py
    mov r0, [line_c + 2 * k]
    mov r1, [line_c + 2 * k + 1]
    mov r2, [px]
    mov r3, [px + 1]
    add r1, r1, r3
    adc r0, r0, r2
    mov [erow], r0
    mov [erow + 1], r1
    mov r0, [erow]
    mov r1, [erow + 1]
    mov r2, [py]
    mov r3, [py + 1]
    add r1, r1, r3
    adc r0, r0, r2
    mov [erow], r0
    mov [erow + 1], r1
    loop y, TILE_H - 1, 1
      ; ev = erow; erow = erow - B
      mov r0, [erow]
      mov r1, [erow + 1]
      mov [ev], r0
      mov [ev + 1], r1
      mov r0, [erow]
      mov r1, [erow + 1]
      mov r2, [line_b + 2 * k]
      mov r3, [line_b + 2 * k + 1]
      sub r1, r1, r3
      sbc r0, r0, r2
      mov [erow + 1], r1
      mov [erow], r0
      ; the row's first pixel: where (ev < 0) we = 0
      mov r0, [ev]
      mmov ns
      getm r1
      mset
      mov r2, [we + TILE_H * (TILE_W - 1) + y]
      and r2, r2, r1
      mov [we + TILE_H * (TILE_W - 1) + y], r2
      .rept x, TILE_W - 2, 0
        ; ev = ev - A; where (ev < 0) we = 0
        mov r0, [ev]
        mov r1, [ev + 1]
        mov r2, [line_a + 2 * k]
        mov r3, [line_a + 2 * k + 1]
        sub r1, r1, r3
        sbc r0, r0, r2
        mov [ev + 1], r1
        mov [ev], r0              ; S = the value's sign
        mmov ns
        getm r1
        mset
        mov r2, [we + TILE_H * x + y]
        and r2, r2, r1
        mov [we + TILE_H * x + y], r2
      .endr
    endloop
  .endr
  halt

; Depth calculation and test: z < the buffer's value sets a flag, ANDed
; into the write enable; the depth stored where that is set.
depth:
.stage depth
  mset
  mov r0, [z_start]
  mov r1, [z_start + 1]
  mov [zrow], r0
  mov [zrow + 1], r1
  loop y, TILE_H - 1, 1
    mov r0, [zrow]
    mov r1, [zrow + 1]
    mov [zv], r0
    mov [zv + 1], r1
    mov r0, [zrow]
    mov r1, [zrow + 1]
    mov r2, [z_dy]
    mov r3, [z_dy + 1]
    sub r1, r1, r3
    sbc r0, r0, r2
    mov [zrow], r0
    mov [zrow + 1], r1
    ; the row's first pixel: the row start's value
    .rept x, TILE_W - 1, TILE_W - 1
      ; flag = 0; where (z < zbuffer) flag = 1
      mov r0, [xcounter]
      mov [flag], r0
      mov r0, [zv]
      mov r1, [zv + 1]
      mov r2, [zb_hi + TILE_H * x + y]
      mov r3, [zb_lo + TILE_H * x + y]
      sub r1, r1, r3
      sbc r0, r0, r2              ; C: no borrow, z >= zbuffer
      mmov nc
      mov r0, [one]
      mov [flag], r0
      mset
      ; we = we & flag
      mov r0, [we + TILE_H * x + y]
      mov r1, [flag]
      and r0, r0, r1
      mov [we + TILE_H * x + y], r0
      ; where (we) zbuffer = z
      mmov nz
      mov r0, [zv]
      mov r1, [zv + 1]
      mov [zb_hi + TILE_H * x + y], r0
      mov [zb_lo + TILE_H * x + y], r1
      mset
    .endr
    ; the others: one x step each
    .rept x, TILE_W - 2, 0
      mov r0, [zv]
      mov r1, [zv + 1]
      mov r2, [z_dx]
      mov r3, [z_dx + 1]
      sub r1, r1, r3
      sbc r0, r0, r2
      mov [zv], r0
      mov [zv + 1], r1
      ; flag = 0; where (z < zbuffer) flag = 1
      mov r0, [xcounter]
      mov [flag], r0
      mov r0, [zv]
      mov r1, [zv + 1]
      mov r2, [zb_hi + TILE_H * x + y]
      mov r3, [zb_lo + TILE_H * x + y]
      sub r1, r1, r3
      sbc r0, r0, r2              ; C: no borrow, z >= zbuffer
      mmov nc
      mov r0, [one]
      mov [flag], r0
      mset
      ; we = we & flag
      mov r0, [we + TILE_H * x + y]
      mov r1, [flag]
      and r0, r0, r1
      mov [we + TILE_H * x + y], r0
      ; where (we) zbuffer = z
      mmov nz
      mov r0, [zv]
      mov r1, [zv + 1]
      mov [zb_hi + TILE_H * x + y], r0
      mov [zb_lo + TILE_H * x + y], r1
      mset
    .endr
  endloop
  halt

; Colour: red, green and blue stepped in 8.8, their integer parts combined
; into the red-green word and the blue byte, written where the write
; enable is set.
colour:
.stage colour
  mset
  .rept k, 0, 2
    mov r0, [c_start + 2 * k]
    mov r1, [c_start + 2 * k + 1]
    mov [crow + 2 * k], r0
    mov [crow + 2 * k + 1], r1
  .endr
  loop y, TILE_H - 1, 1
    .rept k, 0, 2
      mov r0, [crow + 2 * k]
      mov r1, [crow + 2 * k + 1]
      mov [cv + 2 * k], r0
      mov [cv + 2 * k + 1], r1
      mov r0, [crow + 2 * k]
      mov r1, [crow + 2 * k + 1]
      mov r2, [c_dy + 2 * k]
      mov r3, [c_dy + 2 * k + 1]
      sub r1, r1, r3
      sbc r0, r0, r2
      mov [crow + 2 * k], r0
      mov [crow + 2 * k + 1], r1
    .endr
    ; the row's first pixel: the row start's value
    .rept x, TILE_W - 1, TILE_W - 1
      ; rgw = red << 8 | green; bw = blue (the integer parts)
      mov r0, [cv]
      mov r1, [cv + 2]
      mov [rgw], r0
      mov [rgw + 1], r1
      mov r2, [cv + 4]
      mov [bw], r2
      ; where (we) the pixel = rgw, bw
      mov r0, [we + TILE_H * x + y]
      mmov nz
      mov r0, [rgw]
      mov r1, [rgw + 1]
      mov r2, [bw]
      mov [rg_hi + TILE_H * x + y], r0
      mov [rg_lo + TILE_H * x + y], r1
      mov [b + TILE_H * x + y], r2
      mset
    .endr
    ; the others: one x step each
    .rept x, TILE_W - 2, 0
      .rept k, 0, 2
        mov r0, [cv + 2 * k]
        mov r1, [cv + 2 * k + 1]
        mov r2, [c_dx + 2 * k]
        mov r3, [c_dx + 2 * k + 1]
        sub r1, r1, r3
        sbc r0, r0, r2
        mov [cv + 2 * k], r0
        mov [cv + 2 * k + 1], r1
      .endr
      ; rgw = red << 8 | green; bw = blue (the integer parts)
      mov r0, [cv]
      mov r1, [cv + 2]
      mov [rgw], r0
      mov [rgw + 1], r1
      mov r2, [cv + 4]
      mov [bw], r2
      ; where (we) the pixel = rgw, bw
      mov r0, [we + TILE_H * x + y]
      mmov nz
      mov r0, [rgw]
      mov r1, [rgw + 1]
      mov r2, [bw]
      mov [rg_hi + TILE_H * x + y], r0
      mov [rg_lo + TILE_H * x + y], r1
      mov [b + TILE_H * x + y], r2
      mset
    .endr
  endloop
  halt

; Texture coordinates: s and t stepped in 8.8 and stored, with the
; triangle's texture number, where the write enable is set.
texcoord:
.stage texcoord
  mset
  .rept k, 0, 1
    mov r0, [st_start + 2 * k]
    mov r1, [st_start + 2 * k + 1]
    mov [strow + 2 * k], r0
    mov [strow + 2 * k + 1], r1
  .endr
  loop y, TILE_H - 1, 1
    .rept k, 0, 1
      mov r0, [strow + 2 * k]
      mov r1, [strow + 2 * k + 1]
      mov [stv + 2 * k], r0
      mov [stv + 2 * k + 1], r1
      mov r0, [strow + 2 * k]
      mov r1, [strow + 2 * k + 1]
      mov r2, [st_dy + 2 * k]
      mov r3, [st_dy + 2 * k + 1]
      sub r1, r1, r3
      sbc r0, r0, r2
      mov [strow + 2 * k], r0
      mov [strow + 2 * k + 1], r1
    .endr
    ; the row's first pixel: the row start's value
    .rept x, TILE_W - 1, TILE_W - 1
      mov r0, [we + TILE_H * x + y]
      mmov nz
      mov r0, [stv]
      mov r1, [stv + 1]
      mov r2, [stv + 2]
      mov r3, [stv + 3]
      mov r4, [tex]
      mov [s_hi + TILE_H * x + y], r0
      mov [s_lo + TILE_H * x + y], r1
      mov [t_hi + TILE_H * x + y], r2
      mov [t_lo + TILE_H * x + y], r3
      mov [tid + TILE_H * x + y], r4
      mset
    .endr
    ; the others: one x step each
    .rept x, TILE_W - 2, 0
      .rept k, 0, 1
        mov r0, [stv + 2 * k]
        mov r1, [stv + 2 * k + 1]
        mov r2, [st_dx + 2 * k]
        mov r3, [st_dx + 2 * k + 1]
        sub r1, r1, r3
        sbc r0, r0, r2
        mov [stv + 2 * k], r0
        mov [stv + 2 * k + 1], r1
      .endr
      mov r0, [we + TILE_H * x + y]
      mmov nz
      mov r0, [stv]
      mov r1, [stv + 1]
      mov r2, [stv + 2]
      mov r3, [stv + 3]
      mov r4, [tex]
      mov [s_hi + TILE_H * x + y], r0
      mov [s_lo + TILE_H * x + y], r1
      mov [t_hi + TILE_H * x + y], r2
      mov [t_lo + TILE_H * x + y], r3
      mov [tid + TILE_H * x + y], r4
      mset
    .endr
  endloop
  halt

; Clears: every pixel of the tile takes the value the host wrote.
clear_colour:
.stage transfer
  mset
  loop y, TILE_H - 1, 1
    .rept x, TILE_W - 1, 0
      mov r0, [clear_rg]
      mov r1, [clear_rg + 1]
      mov r2, [clear_b]
      mov r3, [xcounter]
      mov [rg_hi + TILE_H * x + y], r0
      mov [rg_lo + TILE_H * x + y], r1
      mov [b + TILE_H * x + y], r2
      mov [tid + TILE_H * x + y], r3
    .endr
  endloop
  halt

clear_depth:
.stage transfer
  mset
  loop y, TILE_H - 1, 1
    .rept x, TILE_W - 1, 0
      mov r0, [clear_z]
      mov r1, [clear_z + 1]
      mov [zb_hi + TILE_H * x + y], r0
      mov [zb_lo + TILE_H * x + y], r1
    .endr
  endloop
  halt
