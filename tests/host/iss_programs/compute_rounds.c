/* compute.c's workload run ROUNDS times over, for bench_iss: long enough
 * (about 40 million instructions in ARM state) that soc_sim's start-up is
 * small beside the program. Its state (the random seed) carries over from
 * round to round, so each round computes other values. */
#define main compute_main
#include "compute.c"
#undef main

int main(void) {
  for (int round = 0; round < ROUNDS; ++round)
    if (compute_main() != 0) return 1;
  return 0;
}
