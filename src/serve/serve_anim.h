/* SPDX-License-Identifier: MIT */
/* serve_anim.h: what serve asks hystviz-animate, out of process: the
 * built-in animations (`--list`, once at start-up) and an animation's frame
 * count and rate (`--info`, asked of a frame worker and cached by the
 * scene's hash). */
#ifndef SERVE_ANIM_H
#define SERVE_ANIM_H

#include "serve_types.h"

/* Reads the built-in animations into s (none without hystviz-animate or
 * OSMesa); -1 when a signal came meanwhile (stop_fd readable), else 0. */
int sv_list_builtins(sv_server *s, int stop_fd);

/* "@NAME" of a built-in animation: its index, or -1. */
int sv_builtin_index(const sv_server *s, const char *name);

/* FNV-1a of a built-in animation's name (its cache key). */
uint64_t sv_name_hash(const char *name);

/* Appends ,"anim":{"frames":N,"fps":F} (or {"frames":0,"error":...}) for
 * the animation what (the scene's text and len, NULL for a built-in) whose
 * cache key is hash; a question not cached runs in a render slot. */
void sv_json_anim(sv_buf *b, sv_server *s, struct MHD_Connection *c, uint64_t hash, const char *what,
                  const char *text, size_t len);

#endif
