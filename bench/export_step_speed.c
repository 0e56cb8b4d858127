/* ns per call of an exported NAME_step (bench/run_export.sh): reads the inputs of the vectors'
 * rows (whitespace-separated, NAME_INPUTS numbers a row) and calls NAME_step STEPS times over
 * them in order, cycling; CPU time of this thread. Built with -DPFX=NAME -include NAME.h. */
#define _POSIX_C_SOURCE 199309L
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#define CAT2(a, b) a##b
#define CAT(a, b) CAT2(a, b)
#define INPUTS CAT(PFX, _INPUTS)

static double cpu_seconds(void) {
  struct timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int main(int argc, char** argv) {
  static double x[200000][INPUTS];
  long rows = 0, steps, k;
  double sum = 0.0, t0, t1;
  CAT(PFX, _state) state;
  FILE* f;
  if (argc != 3 || (f = fopen(argv[1], "r")) == NULL) {
    fprintf(stderr, "usage: export_step_speed INPUTS.txt STEPS\n");
    return 2;
  }
  steps = atol(argv[2]);
  while (rows < 200000) {
    int i, ok = 1;
    for (i = 0; i < INPUTS; ++i) ok = ok && fscanf(f, "%lf", &x[rows][i]) == 1;
    if (!ok) break;
    ++rows;
  }
  fclose(f);
  if (rows == 0 || steps <= 0) return 2;
  CAT(PFX, _init)(&state);
  t0 = cpu_seconds();
  for (k = 0; k < steps; ++k) {
    const double* in = x[k % rows];
#if INPUTS == 1
    sum += CAT(PFX, _step)(&state, in[0]);
#else
    sum += CAT(PFX, _step)(&state, in[0], in[1]);
#endif
  }
  t1 = cpu_seconds();
  printf("%.2f ns/step (checksum %.6g)\n", 1e9 * (t1 - t0) / (double)steps, sum);
  return 0;
}
