/* SPDX-License-Identifier: MIT */
/* test_table2.c: Table 2 of the benchmark from Table 1 (linearised stiffness
 * k + α): 35.59 Hz and 1.12 %. */
#include "bw_test.h"
#include "hy_boucwen.h"

#include <math.h>

int main(void)
{
    hy_boucwen_params p;
    hy_boucwen_modal md;
    hy_error err;
    hy_boucwen_params_default(&p);
    CHECK(p.m == 2 && p.c == 10 && p.k == 5e4 && p.alpha == 5e4 && p.beta == 1e3 &&
          p.gamma == 0.8 && p.delta == -1.1 && p.nu == 1, "Table 1 defaults changed");
    CHECK(hy_boucwen_table2(&p, &md, &err) == HY_OK, "%s", err.msg);
    /* Table 2 prints 2 decimals: the value must round to it. */
    CHECK(fabs(md.f0_hz - 35.59) < 0.005, "f0 = %.6f Hz", md.f0_hz);
    CHECK(fabs(100 * md.zeta - 1.12) < 0.005, "zeta = %.6f %%", 100 * md.zeta);
    /* and equal the closed forms to rounding */
    CHECK(fabs(md.f0_hz - sqrt(1e5 / 2) / (2 * M_PI)) < 1e-12, "f0 = %.17g", md.f0_hz);
    CHECK(fabs(md.zeta - 10 / (2 * sqrt(2e5))) < 1e-15, "zeta = %.17g", md.zeta);
    /* with k alone (the static stiffness, not Table 2's) it would be 25.16 Hz */
    CHECK(fabs(md.f0_hz - 25.16) > 1, "f0 uses k + alpha");
    printf("Table 2: f0 = %.4f Hz, zeta = %.4f %%\n", md.f0_hz, 100 * md.zeta);
    return hy_test_finish("test_table2");
}
