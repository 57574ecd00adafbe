/* An ordinary program's entry point in a shared library: soc_sim runs its
 * main when there is no tessera_app_main. It prints its arguments and ends
 * without drawing. */
#include <stdio.h>

int main(int argc, char** argv) {
  printf("main ran with %d argument(s):", argc - 1);
  for (int i = 1; i < argc; ++i) printf(" %s", argv[i]);
  printf("\n");
  return 0;
}
