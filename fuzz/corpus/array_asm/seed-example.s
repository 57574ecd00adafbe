; The example of the assembly language (tlm/array/README.md): every CU adds
; two vectors of 16-bit values in its CMEM. Values are big-endian, the high
; byte first, as the CIU packs them.

.const COUNT 8
.const LAST 14        ; the byte offset of the last value, 2 * (COUNT - 1)
.var a COUNT + COUNT
.var b COUNT + COUNT
.var sum COUNT + COUNT

add16:
.stage setup
  mset                ; every CU stores its sums
.stage shade
  loop k, LAST, 2     ; k = 14, 12, ..., 0: the byte offset of each value
    add [sum + 1 + k], [a + 1 + k], [b + 1 + k]   ; low bytes first: their carry feeds adc
    adc [sum + k], [a + k], [b + k]
  endloop
  halt
