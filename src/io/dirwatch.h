/* SPDX-License-Identifier: MIT */
/* dirwatch.h: "something in these directories changed" through inotify, for
 * `hystviz serve` and `hystviz watch`.
 *
 * Directories are watched rather than files, so that editors that save by
 * writing a new file and renaming it over the old one (Vim, most IDEs) are
 * seen like editors that write in place.  Bursts are debounced: a wait
 * returns once no event arrived for 80 ms (at most 400 ms after the first),
 * with the names that changed.  Hidden names (.x), backups (x~), swap files
 * (.swp) and temporary files (*.tmp.*) are ignored.
 *
 *     hy_dirwatch *w = hy_dirwatch_open(dirs, n, &err);
 *     char names[1024];
 *     while (hy_dirwatch_wait(w, stop_fd, -1, names, sizeof names) == 1) rerender(names);
 *     hy_dirwatch_close(w);
 */
#ifndef HY_DIRWATCH_H
#define HY_DIRWATCH_H

#include <stddef.h>

#include "hy_status.h"

typedef struct hy_dirwatch hy_dirwatch;

/* Watches the n directories; NULL with err set on failure. */
hy_dirwatch *hy_dirwatch_open(const char *const *dirs, size_t n, hy_error *err);

/* Waits for a change, then for the burst to end.  names receives the changed
 * entries as "dir/name" separated by '\n' (truncated to size).  stop_fd (or
 * -1) ends the wait when readable; timeout_ms < 0 waits without limit.
 * Returns 1 on a change, 0 on stop or timeout, -1 on error (err set). */
int hy_dirwatch_wait(hy_dirwatch *w, int stop_fd, int timeout_ms, char *names, size_t size, hy_error *err);

void hy_dirwatch_close(hy_dirwatch *w);

#endif
