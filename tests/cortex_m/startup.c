/*
 * Minimal startup for running C99 test programs on qemu-system-arm
 * -M lm3s6965evb (Cortex-M3) with newlib + librdimon semihosting.
 *
 * Reset_Handler does what newlib's rdimon crt0 would do, but without
 * relying on the debugger's SYS_HEAPINFO answer for the stack/heap, which
 * differs between QEMU versions: the stack starts at the top of RAM
 * (linker script), and sbrk grows the heap from `end` up to the stack.
 * main's return value goes to exit(), which librdimon turns into a
 * semihosting exit, so QEMU terminates with main's status.
 */
#include <stdint.h>
#include <stdlib.h>

extern uint32_t __data_start__, __data_end__, __data_load__;
extern uint32_t __bss_start__, __bss_end__;
extern uint32_t __stack;

extern int main(void);
extern void initialise_monitor_handles(void); /* librdimon: opens :tt */
extern void __libc_init_array(void);          /* newlib: constructors */

/* crti.o supplies these unless linked with -nostartfiles. */
__attribute__((weak)) void _init(void) {}
__attribute__((weak)) void _fini(void) {}

void Reset_Handler(void);
void Fault_Handler(void);

/* Semihosting call: QEMU traps BKPT 0xAB on M-profile cores. */
static void semihost(uint32_t op, const void *arg)
{
    register uint32_t r0 __asm__("r0") = op;
    register const void *r1 __asm__("r1") = arg;
    __asm__ volatile("bkpt 0xab" : "+r"(r0) : "r"(r1) : "memory");
}

void Reset_Handler(void)
{
    uint32_t *src = &__data_load__;
    uint32_t *dst = &__data_start__;

    while (dst < &__data_end__)
        *dst++ = *src++;
    for (dst = &__bss_start__; dst < &__bss_end__; )
        *dst++ = 0;

    initialise_monitor_handles();
    __libc_init_array();
    exit(main());
}

/*
 * Any fault ends the run with a nonzero QEMU exit status instead of a
 * silent hang or "Lockup".  SYS_EXIT with a reason other than
 * ADP_Stopped_ApplicationExit makes QEMU exit with status 1.
 */
void Fault_Handler(void)
{
    static const uint32_t reason = 0x20023; /* ADP_Stopped_RunTimeErrorUnknown */

    semihost(0x04, "\n*** HardFault / CPU exception ***\n"); /* SYS_WRITE0 */
    semihost(0x18, (const void *)reason);                    /* SYS_EXIT */
    for (;;)
        ;
}

/* Core exception vectors only; no peripheral interrupts are enabled. */
struct vector_table {
    void *initial_sp;
    void (*handler[15])(void);
};

__attribute__((section(".isr_vector"), used))
static const struct vector_table vectors = {
    &__stack,                 /* initial SP: top of RAM */
    {
        Reset_Handler,
        Fault_Handler,        /* NMI */
        Fault_Handler,        /* HardFault */
        Fault_Handler,        /* MemManage */
        Fault_Handler,        /* BusFault */
        Fault_Handler,        /* UsageFault */
        0, 0, 0, 0,           /* reserved */
        Fault_Handler,        /* SVCall */
        Fault_Handler,        /* DebugMon */
        0,                    /* reserved */
        Fault_Handler,        /* PendSV */
        Fault_Handler,        /* SysTick */
    },
};
