/* Vector table and reset handler for the exported C's check program on QEMU's MPS2 AN386
 * (Cortex-M4F): newlib's rdimon start-up (crt0: zeroes .bss, asks the debugger -- here QEMU's
 * semihosting -- for the command line, calls main and exits with its status) runs after the
 * FPU is switched on, which it must be before the first floating-point instruction. */
extern void _start(void);
extern char __StackTop[];

void Reset_Handler(void);

__attribute__((naked, noreturn)) void Reset_Handler(void) {
  __asm volatile(
      "ldr r0, =0xE000ED88\n" /* CPACR: full access to CP10 and CP11 (the FPU) */
      "ldr r1, [r0]\n"
      "orr r1, r1, #(0xF << 20)\n"
      "str r1, [r0]\n"
      "dsb\n"
      "isb\n"
      "b _start\n");
}

/* A fault stops here; the test's timeout then reports it. */
static void Fault_Handler(void) {
  for (;;) {
  }
}

/* Initial stack pointer, reset, NMI, HardFault, MemManage, BusFault, UsageFault, 4 reserved,
 * SVCall, DebugMonitor, reserved, PendSV, SysTick. */
__attribute__((section(".isr_vector"), used)) static void (*const kVectors[16])(void) = {
    (void (*)(void))__StackTop, Reset_Handler, Fault_Handler, Fault_Handler,
    Fault_Handler,              Fault_Handler, Fault_Handler, 0,
    0,                          0,             0,             Fault_Handler,
    Fault_Handler,              0,             Fault_Handler, Fault_Handler};
