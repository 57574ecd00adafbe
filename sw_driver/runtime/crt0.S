@ Start-up of a bare-metal program for the ARM922T on the ISS
@ (sw_driver/runtime/README.md): the exception vectors at address 0, a stack
@ for each exception mode at the top of the application's memory
@ (__stack_top, from the generated linker script), .bss cleared, then C++
@ (tessera_runtime_start) in supervisor mode with IRQ and FIQ masked: the
@ runtime waits for interrupts with CP15's wait-for-interrupt, which needs
@ a privileged mode, and takes no interrupt exceptions unless an
@ application unmasks them and defines tessera_irq_handler.
    .syntax unified
    .arm

    .equ MODE_FIQ, 0x11
    .equ MODE_IRQ, 0x12
    .equ MODE_SVC, 0x13
    .equ MODE_ABT, 0x17
    .equ MODE_UND, 0x1b
    .equ MASKED, 0xc0            @ I and F
    .equ EXCEPTION_STACK, 1024   @ bytes for each exception mode

    .section .vectors, "ax"
    .global _vectors
_vectors:
    b _start
    b undefined_entry
    b swi_entry
    b prefetch_abort_entry
    b data_abort_entry
    b .                          @ reserved
    b irq_entry
    b fiq_entry

    .text
    .global _start
    .type _start, %function
_start:
    ldr r0, =__stack_top
    msr cpsr_c, #(MODE_FIQ | MASKED)
    mov sp, r0
    sub r0, r0, #EXCEPTION_STACK
    msr cpsr_c, #(MODE_IRQ | MASKED)
    mov sp, r0
    sub r0, r0, #EXCEPTION_STACK
    msr cpsr_c, #(MODE_ABT | MASKED)
    mov sp, r0
    sub r0, r0, #EXCEPTION_STACK
    msr cpsr_c, #(MODE_UND | MASKED)
    mov sp, r0
    sub r0, r0, #EXCEPTION_STACK
    msr cpsr_c, #(MODE_SVC | MASKED)
    mov sp, r0
    ldr r1, =__bss_start__
    ldr r2, =__bss_end__
    mov r3, #0
1:  cmp r1, r2
    strlo r3, [r1], #4
    blo 1b
    bl tessera_runtime_start     @ does not return
    b .

@ Exceptions the runtime has no use for end the program with a message
@ (tessera_runtime_exception, the exception's vector offset in r0). The ISS
@ launcher stops a program at an undefined instruction or an abort before
@ it reaches these vectors; another host (a debugger's) would come here.
undefined_entry:
    mov r0, #0x04
    b tessera_runtime_exception
swi_entry:
    mov r0, #0x08
    b tessera_runtime_exception
prefetch_abort_entry:
    mov r0, #0x0c
    b tessera_runtime_exception
data_abort_entry:
    mov r0, #0x10
    b tessera_runtime_exception
fiq_entry:
    mov r0, #0x1c
    b tessera_runtime_exception

@ IRQ: an application that unmasks IRQ defines tessera_irq_handler (a
@ plain function); its caller-saved registers are saved here.
irq_entry:
    sub lr, lr, #4
    stmfd sp!, {r0-r3, r12, lr}
    ldr r0, =tessera_irq_handler
    mov lr, pc
    bx r0
    ldmfd sp!, {r0-r3, r12, pc}^
    .weak tessera_irq_handler
    .set tessera_irq_handler, irq_unhandled
irq_unhandled:
    mov r0, #0x18
    b tessera_runtime_exception
    .ltorg

@ The .init/.fini hooks newlib's __libc_init_array and atexit call; the
@ start files that usually provide them (crti.o, crtn.o) are not linked,
@ and the constructors run from .init_array.
    .global _init
    .global _fini
_init:
_fini:
    bx lr

@ The handle C++ registers static destructors with (__cxa_atexit): one
@ module, so any address will do; crtbegin.o would define it.
    .data
    .global __dso_handle
    .hidden __dso_handle
    .align 2
__dso_handle:
    .word 0
