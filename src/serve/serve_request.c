/* SPDX-License-Identifier: MIT */
/* serve_request.c: a request's basics (serve_request.h): the clock, the
 * query arguments, Host and token, the scene beneath the directory, a client
 * gone. */
#define _GNU_SOURCE /* POLLRDHUP: a peer that closed its end */
#include "serve_request.h"

#include <arpa/inet.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <time.h>

#include "hy_scene.h"

double sv_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* CPU seconds of the calling thread (a render runs on its connection's
 * thread): on a loaded machine its wall time is mostly waiting for a core */
double sv_thread_cpu(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Waits on cond (mu held) for at most 0.2 s, so the caller can look at its
 * client or the stop flag between slices. */
void sv_cond_wait_slice(pthread_cond_t *cond, pthread_mutex_t *mu)
{
    struct timespec until;
    clock_gettime(CLOCK_REALTIME, &until);
    until.tv_nsec += 200000000L;
    if (until.tv_nsec >= 1000000000L)
        until.tv_sec++, until.tv_nsec -= 1000000000L;
    pthread_cond_timedwait(cond, mu, &until);
}

/* The query arguments an endpoint reads (each once; "set" repeats). */
static const struct {
    const char *key;
    size_t off;
} arg_keys[] = {
    {"scene", offsetof(sv_args, scene)}, {"fmt", offsetof(sv_args, fmt)},     {"page", offsetof(sv_args, page)},
    {"seq", offsetof(sv_args, seq)},     {"frame", offsetof(sv_args, frame)}, {"name", offsetof(sv_args, name)},
    {"hover", offsetof(sv_args, hover)}, {"from", offsetof(sv_args, from)},   {"to", offsetof(sv_args, to)},
    {"free", offsetof(sv_args, free)},
};

enum MHD_Result sv_arg_it(void *cls, enum MHD_ValueKind kind, const char *key, size_t key_size, const char *value,
                              size_t value_size)
{
    (void)kind;
    sv_args *a = cls;
    if (++a->n > MAX_ARGS) {
        a->too_many = 1;
        return MHD_NO;
    }
    if (!value)
        value = "";
    if (strlen(key) != key_size || strlen(value) != value_size) { /* an encoded NUL (%00) */
        a->bad_nul = 1;
        return MHD_NO;
    }
    if (!strcmp(key, "set")) {
        a->sets[a->nsets++] = value; /* nsets <= n <= MAX_ARGS */
        return MHD_YES;
    }
    for (size_t i = 0; i < sizeof arg_keys / sizeof arg_keys[0]; i++)
        if (!strcmp(key, arg_keys[i].key)) {
            *(const char **)(void *)((char *)a + arg_keys[i].off) = value;
            break;
        }
    return MHD_YES;
}

/* The Host header names this server: localhost or the bound address (with
 * our port, if a port is given); with --public any IP literal (a DNS
 * rebinding attack needs a name, never an address). */
int sv_host_ok(const sv_server *s, const char *h)
{
    if (!h || !*h || strlen(h) > 300)
        return 0;
    char name[320];
    const char *port = NULL;
    if (h[0] == '[') { /* [v6]:port */
        const char *close = strchr(h, ']');
        if (!close || (close[1] && close[1] != ':'))
            return 0;
        snprintf(name, sizeof name, "%.*s", (int)(close - h - 1), h + 1);
        port = close[1] == ':' ? close + 2 : NULL;
    } else {
        const char *colon = strchr(h, ':');
        if (colon && strchr(colon + 1, ':'))
            return 0; /* a bare IPv6 address is not a valid Host */
        snprintf(name, sizeof name, "%.*s", (int)(colon ? colon - h : (long)strlen(h)), h);
        port = colon ? colon + 1 : NULL;
    }
    if (port) {
        char *end;
        long p = strtol(port, &end, 10);
        if (*end || p != s->port)
            return 0;
    }
    if (!strcasecmp(name, "localhost") || !strcmp(name, s->host))
        return 1;
    unsigned char addr[16];
    if (!strcmp(name, "127.0.0.1") && !strcmp(s->host, "127.0.0.1"))
        return 1;
    return s->public_ && (inet_pton(AF_INET, name, addr) == 1 || inet_pton(AF_INET6, name, addr) == 1);
}

int sv_token_ok(const sv_server *s, struct MHD_Connection *c)
{
    const char *t = MHD_lookup_connection_value(c, MHD_HEADER_KIND, "X-Hystviz-Token");
    if (!t || strlen(t) != strlen(s->token))
        return 0;
    unsigned char d = 0; /* constant time */
    for (size_t i = 0; t[i]; i++)
        d |= (unsigned char)(t[i] ^ s->token[i]);
    return d == 0;
}

/* Reads the catalogue scene name through one descriptor opened beneath the
 * directory (sv_read_beneath: no check-then-open race with a link swapped
 * in) and writes the path shown in messages and command lines
 * (dir_arg/name) to path.  Returns the malloc'd text, or NULL if name is not
 * one: a bad name, missing, not a regular file, a link out of the directory. */
char *sv_scene_read(const sv_server *s, const char *name, char *path, size_t size, size_t *len)
{
    char *text = name ? sv_read_beneath(s->dirfd, name, HY_SCENE_MAX_FILE_BYTES, len) : NULL;
    if (text)
        snprintf(path, size, "%s/%s", s->dir_arg, name);
    return text;
}

/* Whether the peer of socket fd has gone (closed or reset its end). */
int sv_peer_gone(int fd)
{
    struct pollfd p = {.fd = fd, .events = POLLRDHUP};
    return fd >= 0 && poll(&p, 1, 0) > 0 && (p.revents & (POLLRDHUP | POLLHUP | POLLERR));
}

int sv_client_gone(struct MHD_Connection *c)
{
    const union MHD_ConnectionInfo *ci = MHD_get_connection_info(c, MHD_CONNECTION_INFO_CONNECTION_FD);
    return ci && sv_peer_gone(ci->connect_fd);
}
