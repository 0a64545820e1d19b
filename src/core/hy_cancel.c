/* SPDX-License-Identifier: MIT */
/* hy_cancel.c: the cancellation poll of long loops (hy_cancel.h). */
#include "hy_cancel.h"

#include <stddef.h>

int hy_cancel_poll(const hy_cancel *c, unsigned *tick, unsigned every)
{
    if (!c || !c->fn || !tick || ++*tick < every)
        return 0;
    *tick = 0;
    return c->fn(c->ctx) != 0;
}
