/* SPDX-License-Identifier: MIT */
/* rcheck.h: the render, GL, io and cli tests' name for tests/hy_test.h's
 * check: CHECK(cond, fmt, ...) counts and says what failed; a test ends with
 * return hy_test_finish("name"). */
#ifndef HY_RCHECK_H
#define HY_RCHECK_H

#include "../hy_test.h"

#define CHECK HY_CHECK

#endif
