@ Console output without a newline (once kept until a newline came,
@ without bound): 10,000 bytes 'x' to the console register, then a read of
@ a device register (test_iss_app's recording host notes how much of the
@ output has been printed by then), then the exit register (status 0).
        .syntax unified
        .arm
        .section .text.start, "ax"
        .global _start
_start:
        ldr     r0, =0xf0000000         @ the console register
        mov     r1, #'x'
        ldr     r2, =10000
1:      str     r1, [r0]
        subs    r2, r2, #1
        bne     1b
        ldr     r3, =0x52000124         @ a device register: the test's mark
        ldr     r3, [r3]
        mov     r1, #0
        str     r1, [r0, #4]            @ the exit register: status 0
2:      b       2b
        .ltorg
