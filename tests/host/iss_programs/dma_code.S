@ Code written by a bus master other than the CPU: the program
@ runs `function` (r0 = 1), has the system DMA copy `mov r0, #2` over its
@ first instruction (mem_to_mem, 4 bytes; soc_sim --set dma.enabled=true),
@ waits for the channel to finish, invalidates the instruction cache as
@ software must and calls it again. Exit status (the exit register): 0 if
@ the calls returned 1 then 2; otherwise 10 * second + first. Run alone on
@ a recording host (test_iss_app), the DMA's status read is where the test
@ writes the word into memory behind the launcher's back.
        .syntax unified
        .arm
        .section .text.start, "ax"
        .global _start
_start:
        bl      function
        mov     r5, r0                  @ 1: the original instruction, decoded and cached
        ldr     r4, =0x52000100         @ the DMA's channel 0 (contract/dma/dma_regs.def)
        mov     r1, #2
        str     r1, [r4, #0x00]         @ D_CTRL: mem_to_mem
        adr     r1, replacement
        str     r1, [r4, #0x04]         @ D_SRC
        adr     r1, function
        str     r1, [r4, #0x08]         @ D_DST
        mov     r1, #4
        str     r1, [r4, #0x0c]         @ D_LENGTH
        mov     r1, #0
        str     r1, [r4, #0x18]         @ D_NEXT: no chain
        mov     r1, #1
        str     r1, [r4, #0x20]         @ START
wait:
        ldr     r1, [r4, #0x24]         @ STATUS: bit 1 done, bit 2 error
        tst     r1, #4
        bne     failed
        tst     r1, #2
        beq     wait
        mov     r1, #0
        mcr     p15, 0, r1, c7, c5, 0   @ invalidate the instruction cache
        bl      function
        cmp     r0, #2
        cmpeq   r5, #1
        movne   r1, #10
        mulne   r0, r1, r0
        addne   r0, r0, r5
        moveq   r0, #0
        b       finish
failed:
        mov     r0, #99
finish:
        ldr     r1, =0xf0000004         @ the exit register
        str     r0, [r1]
hang:
        b       hang

        .balign 32
function:
        mov     r0, #1
        bx      lr
replacement:
        mov     r0, #2
        .ltorg
