/* SPDX-License-Identifier: MIT */
/* minor_loop_area.c: the area of Fig. 15's minor loop (Example 4: LuGre,
 * σ0 = 6, bimodal input 0, 0.5, 1, 1.5) from libhystviz's core.
 *
 *     cc minor_loop_area.c $(pkg-config --cflags --libs hystviz) -o area && ./area */
#include <stdio.h>

#include <hystviz.h>

int main(void)
{
    hy_model m;
    hy_input in;
    hy_steady st;
    hy_loops loops;
    hy_error err;
    hy_model_lugre_init(&m, 6, 1, 1, 2, 1, 1);
    if (hy_input_bimodal(&in, 0, 0.5, 1, 1.5, NULL, HY_SHAPE_LINEAR, &err) || hy_steady_init(&st, &m, &in, &err) ||
        hy_loops_find(&st, &loops, &err))
        return fprintf(stderr, "minor_loop_area: %s\n", err.msg), 2;
    printf("%.17g\n", loops.nminor ? loops.minor[0].area : 0.0);
    hy_loops_free(&loops);
    hy_steady_free(&st);
    hy_input_free(&in);
    return 0;
}
