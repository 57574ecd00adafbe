; ap-object: object-parallel rasterization as on MorphoSys (Davila et al.,
; strategies 3 and 1; README.md). Every CU walks the unit the host gave it:
; UNITS = 1, one half of a triangle (flat top or flat bottom); UNITS = 2, a
; whole triangle as its lower half and then its upper half. For each row it
; emits the row's first and last covered pixel (exact edge stepping, the
; top-left rule), then walks W pixels from the row's start (plus the piece's
; column offset, folded into the record by the host) stepping depth and
; colour, and emits each pixel's depth and colour into a CMEM slot. The host
; reads the row ends and the slots of covered pixels back and does the
; fragment operations.
;
; Assembled once per span class, unit and z path (CMakeLists.txt): W
; (pixels walked per row), RM (rows a region holds: RM * (4 + 13 W) <=
; REGION), UNITS and ZSEND. With ZSEND = 1 (ap.object.zpath=unit) there are
; no slots: each CU decides per pixel whether it covers it (x not past the
; row's right end, the row within its piece), packs z16 and RGB565 as the
; host would and sends it with zsend to the z-buffer unit; the same pieces
; and the same arithmetic, so the frames agree. The host rewrites each row
; loop's start to the batch's longest piece (ObjectLayout::loop_word)
; before START.
;
; Multi-byte values are big-endian. Formats (README.md, "Fixed point"):
; x: signed 16-bit pixels; u: the edge's remainder, unsigned 24-bit, biased
; so that its carry out is the step of one more pixel; z: z24 in a signed
; 32-bit container (its top byte catches rounding beyond 0 .. 2^24 - 1);
; colour: 8.8 unsigned (modulo 2^16) with half a unit of bias; s, t: texels
; in 16.8, signed 24-bit (modulo 2^24).

.const XL 0                 ; left end: first covered pixel of the row
.const UL 2                 ; its remainder, biased by 2^24 - D
.const QL 5                 ; its whole step per row
.const RL 7                 ; its remainder's step per row
.const NL 10                ; 2^24 - D: the remainder's correction on a carry
.const XR 13                ; right end: last covered pixel, and the same
.const UR 15
.const QR 18
.const RR 20
.const NR 23
.const Z 26                 ; depth at the row's start pixel
.const ZGX 30               ; depth step per pixel right
.const ZROW 34              ; depth step per row (one row up, QL pixels right)
.const C 38                 ; R, G, B, A at the row's start pixel
.const CGX 46               ; their steps per pixel right
.const CROW 54              ; and per row
.const S 62                 ; texture coordinates s, t at the row's start pixel
.const SGX 65               ; their steps per pixel right
.const SROW 68              ; and per row
.const T 71
.const TGX 74
.const TROW 77
.const SLOT_BYTES 13        ; per slot: z (top byte, z16 high, z16 low), R, G, B, A, S (3), T (3)
.const ROW_BYTES 4          ; per row: XL, XR

.if ZSEND
; The z path through the unit (README.md, "The z path through the unit"):
; the record goes on with the piece's column offset, its first row's y in
; memory rows (0 at the top) and its rows left, which the walk counts down.
.const OFS 80               ; the walk's offset from the row's left end
.const YW 82                ; the row's y in the frame's memory rows
.const NROWS 84             ; rows of the piece still to walk (0: none)
.const REC 85
; konst, written by the host when it loads these programs: 1, the colour
; masks, and A / 256 of the rounding below.
.const ONE 0
.const F8 1
.const FC 2
.const A5 3
.const A6 4
.var rec 2 * REC
.var zacc 4                 ; the span's depth accumulator (z24, top byte first)
.var cacc 8                 ; the span's colour accumulators
.var pos 4                  ; the pixel sent: x, y
.var pix 4                  ; and its z16, RGB565
.var konst 5
.else
.const REC 80
.const OUT_BYTES 4096 - 2 * REC - 8 - 3

.var rec 2 * REC            ; the units' records (UNITS = 1 uses the first)
.var cacc 8                 ; the span's colour accumulators
.var tacc 3                 ; the span's t accumulator
.var out OUT_BYTES          ; the regions: one per unit

.if UNITS - 1
.const REGION 1962
.else
.const REGION OUT_BYTES
.endif
.endif

; Region h: row plane b at out + REGION h + RM b (b = 0, 1: XL; 2, 3: XR),
; slot plane b of pixel p at out + REGION h + RM (4 + 13 p + b); the row
; loop's variable l indexes both (l = RM - 1 for the piece's first row).
walk:
.stage setup
  mset
.if ZSEND
  xor r6, r6, r6            ; r6 stays 0: the carries' other operand
.endif
.rept h, 0, UNITS - 1
  loop l, RM - 1, 1
.if ZSEND
.stage transfer
    ; The row's walk starts at x = XL + OFS; r0:r1 counts the pixels left
    ; to the right end (XR - x, signed): a pixel is covered while it is not
    ; negative. A CU whose piece has no row left makes it negative.
    add [pos + 1], [rec + REC * h + XL + 1], [rec + REC * h + OFS + 1]
    adc [pos], [rec + REC * h + XL], [rec + REC * h + OFS]
    mov [pos + 2], [rec + REC * h + YW]
    mov [pos + 3], [rec + REC * h + YW + 1]
    sub r1, [rec + REC * h + XR + 1], [pos + 1]
    sbc r0, [rec + REC * h + XR], [pos]
    cmp [rec + REC * h + NROWS], r6
    mmov z
    getm r7
    mmov nz
    sub [rec + REC * h + NROWS], [rec + REC * h + NROWS], [konst + ONE]
    mset
    or r0, r0, r7
.stage shade
    .rept k, 0, 3
    mov [zacc + k], [rec + REC * h + Z + k]
    .endr
    .rept k, 0, 5
    mov [cacc + k], [rec + REC * h + C + k]
    .endr
    loop p, W - 1, 1
      ; z16 as the host reads it: the top byte 0x01..0x7f makes 0xffff,
      ; 0x80..0xff makes 0.
      mov [pix], [zacc + 1]
      mov [pix + 1], [zacc + 2]
      mov r2, [zacc]
      mmov nz
      getm r3
      mov [pix], r3
      mov [pix + 1], r3
      mov r2, r2
      mmov s
      mov [pix], r6
      mov [pix + 1], r6
      mset
      ; RGB565 as pack_pixel rounds: round(c 31 / 255) is the top five bits
      ; of hi(256 c - 7 c + 1024), round(c 63 / 255) the top six of hi(256 c
      ; - 3 c + 512); hi(256 c - k c + A) = c + A / 256 - ceil(k c / 256), and
      ; ceil(k c / 256) = hi((k + 1) c + ~c).
      shl r3, [cacc]
      rol r4, r6
      shl r3, r3
      rol r4, r4
      shl r3, r3
      rol r4, r4
      not r2, [cacc]
      add r3, r3, r2
      adc r4, r4, r6
      sub r2, [cacc], r4
      add r2, r2, [konst + A5]
      and r7, r2, [konst + F8]
      shl r3, [cacc + 2]
      rol r4, r6
      shl r3, r3
      rol r4, r4
      not r2, [cacc + 2]
      add r3, r3, r2
      adc r4, r4, r6
      sub r2, [cacc + 2], r4
      add r2, r2, [konst + A6]
      and r2, r2, [konst + FC]
      shl r2, r2
      rol r5, r6
      shl r2, r2
      rol r5, r5
      shl r2, r2
      rol r5, r5
      or [pix + 2], r7, r5
      shl r3, [cacc + 4]
      rol r4, r6
      shl r3, r3
      rol r4, r4
      shl r3, r3
      rol r4, r4
      not r5, [cacc + 4]
      add r3, r3, r5
      adc r4, r4, r6
      sub r5, [cacc + 4], r4
      add r5, r5, [konst + A5]
      shr r5, r5
      shr r5, r5
      shr r5, r5
      or [pix + 3], r2, r5
      ; Send where covered, then step x, the count, depth and colour.
      mov r0, r0
      mmov ns
      zsend [pos], [pix]
      mset
      add [pos + 1], [pos + 1], [konst + ONE]
      adc [pos], [pos], r6
      sub r1, r1, [konst + ONE]
      sbc r0, r0, r6
      add [zacc + 3], [zacc + 3], [rec + REC * h + ZGX + 3]
      adc [zacc + 2], [zacc + 2], [rec + REC * h + ZGX + 2]
      adc [zacc + 1], [zacc + 1], [rec + REC * h + ZGX + 1]
      adc [zacc], [zacc], [rec + REC * h + ZGX]
      .rept k, 0, 2
      add [cacc + 2 * k + 1], [cacc + 2 * k + 1], [rec + REC * h + CGX + 2 * k + 1]
      adc [cacc + 2 * k], [cacc + 2 * k], [rec + REC * h + CGX + 2 * k]
      .endr
    endloop
    ; The next row is one memory row up.
    sub [rec + REC * h + YW + 1], [rec + REC * h + YW + 1], [konst + ONE]
    sbc [rec + REC * h + YW], [rec + REC * h + YW], r6
.else
.stage transfer
    mov [out + REGION * h + l], [rec + REC * h + XL]
    mov [out + REGION * h + RM + l], [rec + REC * h + XL + 1]
    mov [out + REGION * h + RM * 2 + l], [rec + REC * h + XR]
    mov [out + REGION * h + RM * 3 + l], [rec + REC * h + XR + 1]
.stage shade
    mov r0, [rec + REC * h + Z]
    mov r1, [rec + REC * h + Z + 1]
    mov r2, [rec + REC * h + Z + 2]
    mov r3, [rec + REC * h + Z + 3]
    .rept k, 0, 7
    mov [cacc + k], [rec + REC * h + C + k]
    .endr
    mov r4, [rec + REC * h + S]
    mov r5, [rec + REC * h + S + 1]
    mov r6, [rec + REC * h + S + 2]
    .rept k, 0, 2
    mov [tacc + k], [rec + REC * h + T + k]
    .endr
    .rept p, 0, W - 1
    mov [out + REGION * h + RM * (ROW_BYTES + SLOT_BYTES * p) + l], r0
    mov [out + REGION * h + RM * (ROW_BYTES + SLOT_BYTES * p + 1) + l], r1
    mov [out + REGION * h + RM * (ROW_BYTES + SLOT_BYTES * p + 2) + l], r2
    .rept k, 0, 3
    mov [out + REGION * h + RM * (ROW_BYTES + SLOT_BYTES * p + 3 + k) + l], [cacc + 2 * k]
    .endr
    mov [out + REGION * h + RM * (ROW_BYTES + SLOT_BYTES * p + 7) + l], r4
    mov [out + REGION * h + RM * (ROW_BYTES + SLOT_BYTES * p + 8) + l], r5
    mov [out + REGION * h + RM * (ROW_BYTES + SLOT_BYTES * p + 9) + l], r6
    .rept k, 0, 2
    mov [out + REGION * h + RM * (ROW_BYTES + SLOT_BYTES * p + 10 + k) + l], [tacc + k]
    .endr
    add r3, r3, [rec + REC * h + ZGX + 3]
    adc r2, r2, [rec + REC * h + ZGX + 2]
    adc r1, r1, [rec + REC * h + ZGX + 1]
    adc r0, r0, [rec + REC * h + ZGX]
    .rept k, 0, 3
    add [cacc + 2 * k + 1], [cacc + 2 * k + 1], [rec + REC * h + CGX + 2 * k + 1]
    adc [cacc + 2 * k], [cacc + 2 * k], [rec + REC * h + CGX + 2 * k]
    .endr
    add r6, r6, [rec + REC * h + SGX + 2]
    adc r5, r5, [rec + REC * h + SGX + 1]
    adc r4, r4, [rec + REC * h + SGX]
    add [tacc + 2], [tacc + 2], [rec + REC * h + TGX + 2]
    adc [tacc + 1], [tacc + 1], [rec + REC * h + TGX + 1]
    adc [tacc], [tacc], [rec + REC * h + TGX]
    .endr
.endif
.stage fill
    ; The left end: the remainder's carry is the row with one pixel more;
    ; those CUs also move their start values one pixel right.
    add [rec + REC * h + UL + 2], [rec + REC * h + UL + 2], [rec + REC * h + RL + 2]
    adc [rec + REC * h + UL + 1], [rec + REC * h + UL + 1], [rec + REC * h + RL + 1]
    adc [rec + REC * h + UL], [rec + REC * h + UL], [rec + REC * h + RL]
    mmov c
    getm r7
    add [rec + REC * h + UL + 2], [rec + REC * h + UL + 2], [rec + REC * h + NL + 2]
    adc [rec + REC * h + UL + 1], [rec + REC * h + UL + 1], [rec + REC * h + NL + 1]
    adc [rec + REC * h + UL], [rec + REC * h + UL], [rec + REC * h + NL]
    add [rec + REC * h + Z + 3], [rec + REC * h + Z + 3], [rec + REC * h + ZGX + 3]
    adc [rec + REC * h + Z + 2], [rec + REC * h + Z + 2], [rec + REC * h + ZGX + 2]
    adc [rec + REC * h + Z + 1], [rec + REC * h + Z + 1], [rec + REC * h + ZGX + 1]
    adc [rec + REC * h + Z], [rec + REC * h + Z], [rec + REC * h + ZGX]
    .rept k, 0, 3
    add [rec + REC * h + C + 2 * k + 1], [rec + REC * h + C + 2 * k + 1], [rec + REC * h + CGX + 2 * k + 1]
    adc [rec + REC * h + C + 2 * k], [rec + REC * h + C + 2 * k], [rec + REC * h + CGX + 2 * k]
    .endr
.if 1 - ZSEND
    .rept v, 0, 1
    add [rec + REC * h + S + 9 * v + 2], [rec + REC * h + S + 9 * v + 2], [rec + REC * h + SGX + 9 * v + 2]
    adc [rec + REC * h + S + 9 * v + 1], [rec + REC * h + S + 9 * v + 1], [rec + REC * h + SGX + 9 * v + 1]
    adc [rec + REC * h + S + 9 * v], [rec + REC * h + S + 9 * v], [rec + REC * h + SGX + 9 * v]
    .endr
.endif
    mset
    ; x - (0xff:0xff where the carry was) + Q: x + Q + carry.
    sub [rec + REC * h + XL + 1], [rec + REC * h + XL + 1], r7
    sbc [rec + REC * h + XL], [rec + REC * h + XL], r7
    add [rec + REC * h + XL + 1], [rec + REC * h + XL + 1], [rec + REC * h + QL + 1]
    adc [rec + REC * h + XL], [rec + REC * h + XL], [rec + REC * h + QL]
    add [rec + REC * h + Z + 3], [rec + REC * h + Z + 3], [rec + REC * h + ZROW + 3]
    adc [rec + REC * h + Z + 2], [rec + REC * h + Z + 2], [rec + REC * h + ZROW + 2]
    adc [rec + REC * h + Z + 1], [rec + REC * h + Z + 1], [rec + REC * h + ZROW + 1]
    adc [rec + REC * h + Z], [rec + REC * h + Z], [rec + REC * h + ZROW]
    .rept k, 0, 3
    add [rec + REC * h + C + 2 * k + 1], [rec + REC * h + C + 2 * k + 1], [rec + REC * h + CROW + 2 * k + 1]
    adc [rec + REC * h + C + 2 * k], [rec + REC * h + C + 2 * k], [rec + REC * h + CROW + 2 * k]
    .endr
.if 1 - ZSEND
    .rept v, 0, 1
    add [rec + REC * h + S + 9 * v + 2], [rec + REC * h + S + 9 * v + 2], [rec + REC * h + SROW + 9 * v + 2]
    adc [rec + REC * h + S + 9 * v + 1], [rec + REC * h + S + 9 * v + 1], [rec + REC * h + SROW + 9 * v + 1]
    adc [rec + REC * h + S + 9 * v], [rec + REC * h + S + 9 * v], [rec + REC * h + SROW + 9 * v]
    .endr
.endif
    ; The right end, the same way (no values follow it).
    add [rec + REC * h + UR + 2], [rec + REC * h + UR + 2], [rec + REC * h + RR + 2]
    adc [rec + REC * h + UR + 1], [rec + REC * h + UR + 1], [rec + REC * h + RR + 1]
    adc [rec + REC * h + UR], [rec + REC * h + UR], [rec + REC * h + RR]
    mmov c
    getm r7
    add [rec + REC * h + UR + 2], [rec + REC * h + UR + 2], [rec + REC * h + NR + 2]
    adc [rec + REC * h + UR + 1], [rec + REC * h + UR + 1], [rec + REC * h + NR + 1]
    adc [rec + REC * h + UR], [rec + REC * h + UR], [rec + REC * h + NR]
    mset
    sub [rec + REC * h + XR + 1], [rec + REC * h + XR + 1], r7
    sbc [rec + REC * h + XR], [rec + REC * h + XR], r7
    add [rec + REC * h + XR + 1], [rec + REC * h + XR + 1], [rec + REC * h + QR + 1]
    adc [rec + REC * h + XR], [rec + REC * h + XR], [rec + REC * h + QR]
  endloop
.endr
  halt
