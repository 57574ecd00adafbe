.const N 4
.var v 8
entry:
.stage setup
  mset
  mov r0, [v]
  mov r1, 3
.stage shade
  loop i, 6, 2
    add [v + 1 + i], [v + i], r1
    sub r2, r0, r1
  endloop
.stage transfer
  mov [v], r0
  halt
other:
  nop
  halt
