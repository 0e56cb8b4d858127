/* The exported network's own tanh against the platform's long-double tanhl (a reference a
 * thousand times finer than double's rounding on x86-64), over 2.4e6 points of [-24, 24] and
 * around every switch of its range reduction (2|x| = k ln 2 +- ln 2 / 2, k = 0..58): exits 1
 * if |own - tanhl| exceeds LIMIT units of eps (2^-53 double, 2^-24 float; docs/deploy.md
 * derives 6.6 at first order), and prints the largest. Built with -DT=double|float
 * -DNAME=ff_nn_tanh -DLIMIT=6.6 -include the generated NAME.c (its tanh is file-local). */
#include <math.h>
#include <stdio.h>

static long double worst = 0;
static double worst_at = 0;

static void at(double x) {
  const T xt = (T)x;
  const long double d = fabsl((long double)NAME(xt) - tanhl((long double)xt));
  if (d > worst) {
    worst = d;
    worst_at = (double)xt;
  }
}

int main(void) {
  const long double eps = sizeof(T) == sizeof(double) ? 0x1p-53L : 0x1p-24L;
  long i;
  int k, j;
  for (i = 0; i <= 2400000; ++i) at(-24.0 + 48.0 * (double)i / 2400000.0);
  for (k = 0; k <= 58; ++k)
    for (j = -64; j <= 64; ++j) {
      const double edge = (k + 0.5) * 0.34657359027997264;
      at(edge * (1 + j * 1e-15));
      at(-edge * (1 + j * 1e-15));
    }
  printf("own tanh: max |tanh - tanhl| = %.3Lg eps at x = %.9g (limit %g eps)\n", worst / eps,
         worst_at, (double)LIMIT);
  return worst <= LIMIT * eps ? 0 : 1;
}
