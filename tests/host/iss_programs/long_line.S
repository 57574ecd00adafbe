@ A line without an end written to one of the launcher's semihosting files
@ (the driver's warnings, ":tessera/warnings"): 100,000 bytes of the zeroed
@ memory at 0x10000 and no newline. The launcher hands such a line on in
@ pieces rather than keeping it without bound (test_iss_app).
        .syntax unified
        .arm
        .section .text.start, "ax"
        .global _start
_start:
        mov     r0, #1                  @ SYS_OPEN
        adr     r1, open_block
        svc     0x123456
        adr     r1, write_block
        str     r0, [r1]                @ the handle
        mov     r0, #5                  @ SYS_WRITE
        svc     0x123456
        ldr     r1, =0xf0000004         @ the exit register: status = what SYS_WRITE left unwritten
        str     r0, [r1]
hang:
        b       hang

open_block:
        .word   name, 4, 17             @ the name, mode "w", its length
write_block:
        .word   0, 0x10000, 100000      @ handle, buffer, length
name:
        .ascii  ":tessera/warnings"
        .balign 4
        .ltorg
