/* SPDX-License-Identifier: MIT */
/* contracts.h: what lib-contracts' two files share (test_contracts.c: hystviz.h
 * and the readers' headers; test_core_contracts.c: the other installed core
 * headers).  Each call made with a NULL pointer or an edge value goes through
 * NC() or REFUSED(), which record the function's name; tc_coverage() then
 * fails for every symbol of the committed ABI list (tests/libhystviz/abi.txt,
 * the one list of the exported functions) that no such call reached, so a
 * new exported function without its NULL case fails the test. */
#ifndef HY_TEST_CONTRACTS_H
#define HY_TEST_CONTRACTS_H

#include <string.h>

#include "hy_status.h"

/* Records the function called by the text of call ("hy_x(NULL, 1)": hy_x). */
void tc_mark(const char *call);

/* The value of call, its function recorded as reached with NULL or an edge. */
#define NC(call) (tc_mark(#call), (call))

/* rc is HY_EINVAL and err.msg holds needle (rc's function recorded). */
#define REFUSED(rc, err, needle)                                                                                       \
    do {                                                                                                               \
        int refused_rc_ = NC(rc);                                                                                      \
        CHECK(refused_rc_ == HY_EINVAL && strstr((err).msg, (needle)), "%s:%d: want HY_EINVAL with '%s', got %d '%s'", \
              __FILE__, __LINE__, (needle), refused_rc_, (err).msg);                                                   \
    } while (0)

/* The installed core headers other than the readers': every function with
 * each pointer argument NULL in turn and with edge numbers.  Returns 1 when
 * one of its checks failed, else 0 (it prints its own count). */
int tc_core(void);

/* Every "symbol NAME@..." line of the ABI list at path was reached through
 * NC() or REFUSED(); each that was not is printed.  Returns the number of
 * misses (and 1 when path cannot be read). */
int tc_coverage(const char *path);

#endif
