/* Programs that fault, for the launcher's errors: FAULT selects an
 * undefined instruction or a load from an address with no memory behind it. */
#include "console.h"

int main(void) {
  put_text("before the fault\n");
#if FAULT == 1
  __asm__ volatile(".word 0xe7f000f0"); /* permanently undefined */
#else
  return (int)*(volatile unsigned*)0x30000000u; /* inside sysmem's window, past the populated memory */
#endif
  return 0;
}
