/* A library with both entry points: soc_sim runs tessera_app_main, and the
 * run would fail if it ran main instead. */
#include <stdio.h>

int tessera_app_main(int argc, char** argv) {
  (void)argc;
  (void)argv;
  printf("tessera_app_main ran\n");
  return 0;
}

int main(int argc, char** argv) {
  (void)argc;
  (void)argv;
  printf("main ran instead of tessera_app_main\n");
  return 1;
}
