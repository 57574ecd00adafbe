@ A hung program: a branch to itself with IRQ and FIQ masked,
@ which nothing can end. The ISS stops it at once, naming the PC, rather
@ than at the instruction limit.
        .syntax unified
        .arm
        .section .text.start, "ax"
        .global _start
_start:
        msr     cpsr_c, #0xd3           @ supervisor mode, IRQ and FIQ masked
        mov     r0, #0
        mov     r0, #1
hang:
        b       hang
