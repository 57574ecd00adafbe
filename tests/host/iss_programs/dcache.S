@ The data side of the ARM922T under a program's control (test_iss_dcache):
@ CP15 c1's C and RR bits and c7's data-side operations, run by soc_sim's
@ launcher against the host's data cache and write buffer. No stack and no
@ literal pool, so that every data access is one written here; the counts
@ each block adds to the host's statistics are in its comments, and
@ test_iss_dcache.cpp adds them up.
        .syntax unified
        .arm
        .section .text.start, "ax"
        .global _start
_start:
        mov     r4, #0x80000            @ line A (set 0)
        mov     r8, #0

        @ Read-allocate, hits, a dirty half, clean by address, drain.
        ldr     r0, [r4]                @ miss: fill A
        ldr     r0, [r4, #4]            @ hit
        str     r0, [r4, #20]           @ hit: the second half dirty
        mcr     p15, 0, r4, c7, c10, 1  @ clean A: 16 bytes written back (A + 16)
        mcr     p15, 0, r8, c7, c10, 4  @ drain the write buffer
        mcr     p15, 0, r4, c7, c10, 1  @ clean A again: nothing to write

        @ The data cache off (C clear): uncached, the line kept.
        str     r0, [r4]                @ hit: the first half dirty
        mrc     p15, 0, r1, c1, c0, 0
        bic     r2, r1, #4
        mcr     p15, 0, r2, c1, c0, 0   @ C off
        ldr     r0, [r4, #8]            @ uncached read of 4 bytes
        str     r0, [r4, #24]           @ uncached write of 4 bytes, through the write buffer
        mcr     p15, 0, r1, c1, c0, 0   @ C on
        ldr     r0, [r4, #8]            @ hit: the line was kept
        mcr     p15, 0, r4, c7, c14, 1  @ clean and invalidate A: 16 bytes (A)
        ldr     r0, [r4]                @ miss
        mcr     p15, 0, r4, c7, c6, 1   @ invalidate A
        ldr     r0, [r4]                @ miss
        str     r0, [r4]                @ hit: dirty
        mcr     p15, 0, r8, c7, c6, 0   @ invalidate the data cache: the dirty half dropped
        ldr     r0, [r4]                @ miss
        str     r0, [r4, #28]           @ hit: the second half dirty

        @ Clean every way of set 0 by index (way in bits 31:26): one write-back (16 bytes).
        mov     r3, #0
1:      mcr     p15, 0, r3, c7, c10, 2
        adds    r3, r3, #(1 << 26)
        bne     1b

        @ Round-robin (RR set): 65 lines of set 1 after an invalidation fill
        @ the 64 ways once each and the 65th replaces the first.
        orr     r1, r1, #0x4000
        mcr     p15, 0, r1, c1, c0, 0   @ RR on (C on)
        mcr     p15, 0, r8, c7, c6, 0
        add     r5, r4, #0x20           @ B0 = A + 32: set 1
        mov     r6, #65
2:      ldr     r0, [r5], #128          @ 65 misses: B0 ... B64
        subs    r6, r6, #1
        bne     2b
        add     r5, r4, #0x20
        ldr     r0, [r5]                @ B0: miss (replaced by B64; replaces B1)
        ldr     r0, [r5, #256]          @ B2: hit

        @ Five uncached stores in one instruction-cache line: the write
        @ buffer holds four addresses, so the fifth waits (one stall).
        bic     r2, r1, #4
        mcr     p15, 0, r2, c1, c0, 0   @ C off
        .balign 32
        str     r0, [r4]
        str     r0, [r4, #4]
        str     r0, [r4, #8]
        str     r0, [r4, #12]
        str     r0, [r4, #16]
        mcr     p15, 0, r8, c7, c10, 4  @ drain
        mov     r1, #0xf0000000
        mov     r0, #0
        str     r0, [r1, #4]            @ the exit register (the launcher's, not the host's)
3:      b       3b
