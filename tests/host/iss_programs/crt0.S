@ Start-up for the ISS test programs (ARM state): a stack at the top of the
@ 1 MiB test memory, .bss cleared, main() called (BLX-free: ARMv4T), its
@ status written to the test machine's exit register.
        .syntax unified
        .arm
        .section .text.start, "ax"
        .global _start
_start:
        ldr     sp, =__stack_top
        ldr     r0, =__bss_start
        ldr     r1, =__bss_end
        mov     r2, #0
1:      cmp     r0, r1
        strlo   r2, [r0], #4
        blo     1b
        ldr     r3, =main
        mov     lr, pc
        bx      r3              @ main may be Thumb code
        ldr     r1, =0xf0000004 @ exit register
        str     r0, [r1]
2:      b       2b
