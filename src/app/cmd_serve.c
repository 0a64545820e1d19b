/* SPDX-License-Identifier: MIT */
/* cmd_serve.c: `hystviz serve [SCENE.scene|DIR]`: a live preview in the
 * browser on libmicrohttpd (one thread per connection), with a control per
 * numeric key, reload on save (inotify, Server-Sent Events), animation
 * frames from warm hystviz-animate workers (serve_frames.c: no OSMesa in hystviz) and
 * "save as new scene".  Every figure is rendered in memory by the same
 * pipeline as `hystviz render`, so the bytes are those render writes. */
#define _GNU_SOURCE /* POLLRDHUP: a peer that closed its end */
#include "cmd_serve.h"

#include "cli_util.h"
#include "hy_config.h"
#include "hy_file.h"

#include <stdio.h>
#include <string.h>

static const char serve_help[] =
    "usage: hystviz serve [SCENE.scene | DIR] [--port N] [--host ADDR [--public]] [--open]\n"
    "                     [--max-work W] [--include-dir DIR]... [--allow-save]\n"
    "\n"
    "Serves a live preview of the scenes in DIR (default: scenes) at http://127.0.0.1:PORT/\n"
    "until Ctrl-C: the catalogue, each figure as SVG with a slider and a number box per\n"
    "numeric key, the `hystviz render --set` line that writes the same figure, downloads\n"
    "(SVG, PDF, PNG, CSV), animations played at their frame rate (frames from warm\n"
    "hystviz-animate workers, the sliders applied), a reload of every open page when a\n"
    "scene file or one it includes is saved, and (with --allow-save) \"save as new scene\".\n"
    "With SCENE.scene, the page opens that scene (the others in its directory stay reachable).\n"
    "\n";

static const char serve_tail[] =
    "A page may set (as `render --set`) numbers, switches, choices, lengths and colours of\n"
    "[model], [input], [compute], [series], [figure], [annotation] and [param]; never a file path,\n"
    "text, [output] or an animation.  Budgets: one answer is at most 32 MB; renders run a\n"
    "few at a time (requests without a page id get half of them; 64 wait, more get 503 with\n"
    "Retry-After); a request whose client has gone is dropped before computing; idle\n"
    "connections close after 10 s; 32 event streams in all, 2 per page.\n"
    "\n"
    "Only the directory's *.scene files and their renders are served; requests whose\n"
    "Host header is not the bound address or localhost are refused (DNS rebinding), as\n"
    "are requests another site's page makes (Sec-Fetch-Site).  Exit status: 0 after\n"
    "Ctrl-C, 1 if the port cannot be bound, 2 for a bad option, 3 if built without\n"
    "libmicrohttpd.\n";

enum { OPT_PORT = CLI_FIRST, OPT_HOST, OPT_PUBLIC, OPT_OPEN, OPT_MAX_WORK, OPT_ALLOW_SAVE };
static const cli_opt serve_opts[] = {
    {"port", 0, "N", "port (default 8017; 0 picks a free one, printed)", OPT_PORT, 0, NULL, NULL, NULL},
    {"host", 0, "ADDR", "address to bind (default 127.0.0.1); any other needs --public", OPT_HOST, 0, NULL, NULL,
     NULL},
    {"public", 0, NULL, "allow --host to be reachable from other machines: anyone who can\n"
     "reach the port reads every scene file of DIR (and what they include)\n"
     "and makes this machine render figures (CPU and memory within the\n"
     "budgets below); with --allow-save also writes new scenes into DIR", OPT_PUBLIC, 0, NULL, NULL, NULL},
    {"open", 0, NULL, "open the page in the desktop's browser (xdg-open)", OPT_OPEN, 0, NULL, NULL, NULL},
    {"max-work", 0, "W", "work budget of one render (default 2e6, 50 times the largest\n"
     "gallery figure; `hystviz render` allows 1e8):\n"
     "a page's request for more is refused before computing (422)", OPT_MAX_WORK, 0, NULL, NULL, NULL},
    {"include-dir", 0, "DIR", "a directory scenes may include from and read input files\n"
     "from, besides their own (as for hystviz render); repeatable", CLI_INCLUDE_DIR, 0, NULL, NULL, NULL},
    {"allow-save", 0, NULL, "enable \"save as new scene\": the page carries a token that lets it\n"
     "write NEW.scene files into DIR (never replacing one), at most 100\n"
     "per run and one a second; anyone who can load the page can save", OPT_ALLOW_SAVE, 0, NULL, NULL, NULL},
    {0},
};
static const cli_cmd serve_cli = {"serve", serve_help, serve_tail, "SCENE.scene|DIR", serve_opts};

#if !HY_HAVE_MICROHTTPD

int hy_cmd_serve(int argc, char **argv)
{
    cli_parser p;
    cli_parser_init(&p, &serve_cli, argc, argv, 1);
    for (int id; (id = cli_next(&p)) != CLI_END;)
        if (id == CLI_STOP || id == CLI_ERROR)
            return id == CLI_STOP ? 0 : 2;
    fprintf(stderr, "hystviz serve: this hystviz was built without libmicrohttpd (Debian: apt-get install "
                    "libmicrohttpd-dev, then meson setup --reconfigure build -Dmicrohttpd=enabled)\n");
    return 3;
}

#else

#include <arpa/inet.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <malloc.h>
#include <math.h>
#include <microhttpd.h>
#include <netinet/in.h>
#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <spawn.h>
#include <stdint.h>
#include <stdlib.h>
#include <strings.h>
#include <poll.h>
#include <sys/random.h>
#include <sys/signalfd.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <dirent.h>
#include <unistd.h>

#include "dirwatch.h"
#include "hy_jobs.h"
#include "hy_scene_policy.h"
#include "scene_boucwen.h"
#include "scene_run.h"
#include "serve_frames.h"
#include "serve_util.h"

extern char **environ;

/* the page (src/app/serve/, embedded at build time) */
extern const char hy_page_html[], hy_page_js[], hy_page_css[];
extern const size_t hy_page_html_len, hy_page_js_len, hy_page_css_len;

#define MAX_ARGS 64         /* query arguments per request */
#define MAX_QUERY 256       /* ... counted before libmicrohttpd stores them */
#define MAX_BODY 4096       /* request body bytes (no request needs one) */
#define MAX_PAGES 128       /* pages tracked for render coalescing */
#define SSE_PING_S 5        /* below CONN_TIMEOUT_S: a live stream is never idle that long */
#define SSE_MAX 32          /* event streams in all ... */
#define SSE_PER_PAGE 2      /* ... and per page (?page=ID; streams without one share "") */
#define CONN_TIMEOUT_S 10   /* an idle connection (no bytes either way) is closed */
#define CONN_MAX 1000       /* connections in all, and from one address */
#define CONN_PER_IP 900
#define QUEUE_MAX 64        /* renders waiting for a slot; more: 503 + Retry-After */
#define ADDR_MAX 64         /* client addresses with renders running or waiting */
#define SERVE_INCLUDE_DIRS 16        /* --include-dir, at most */
#define SERVE_WORK_DEFAULT 2e6       /* serve's work budget per render (--max-work raises it) */
#define SERVE_OUTPUT_MAX (32u << 20) /* bytes of one answer (SVG, PDF, PNG, CSV, JSON) */
#define CHILD_TIMEOUT_S 60  /* hystviz-animate --info / --list: killed after this */
#define TRIM_IDLE_S 2.0     /* idle seconds before freed memory goes back to the kernel */
#define ANIM_CACHE 64       /* `hystviz-animate --info` answers kept, by scene hash */
#define SAVE_MAX 100        /* saves per run (--allow-save) ... */
#define SAVE_EVERY_S 1.0    /* ... at most one a second */

typedef struct page_slot {
    char id[40];
    unsigned long latest;   /* newest sequence number seen */
    int busy;               /* a render for this page is running */
    double used;
} page_slot;

typedef struct sse_page {
    char id[40];
    int n;
} sse_page;

typedef struct anim_entry {
    uint64_t hash;          /* hy_scene_hash of the scene (its files and includes) */
    long frames;
    double fps;
    int ok;
    char msg[512];
} anim_entry;

typedef struct server {
    char dir[PATH_MAX];     /* the scenes directory, resolved */
    int dirfd;              /* ... opened once: every scene is read beneath it */
    const char *dir_arg;    /* as given (for command lines and messages) */
    char first[256];        /* SCENE.scene given: open it first */
    char token[33];
    char animate[PATH_MAX]; /* hystviz-animate next to this program */
    char host[64];          /* bound address as text */
    int port, ipv6, public_, allow_save;
    double max_work;        /* work budget of one render (SERVE_WORK_DEFAULT, --max-work) */
    hy_scene_policy pol;    /* --include-dir (and max_work): every scene is parsed and loaded under it */
    const char *incdirs[SERVE_INCLUDE_DIRS];
    char *page;             /* index.html with the token */
    size_t page_len;
    pthread_mutex_t mu;
    pthread_cond_t cond;    /* generation changes, stop, page slots freed */
    unsigned long gen;
    char changed[2048];
    int stopping;
    page_slot pages[MAX_PAGES];
    int nslots;             /* renders (and hystviz-animate children) at once */
    int running, running_anon, waiting;
    double idle_since;      /* when the last render ended (now_s) */
    int trim_due;           /* its memory not yet given back (idle_trim) */
    struct {
        unsigned char key[17]; /* family, then the IPv4 address or IPv6 /64 */
        int running, waiting;
    } addr[ADDR_MAX];         /* per client address (slot_take's fairness)  */
    unsigned long ncancelled; /* renders stopped because their client went */
    double last_cancel_note;
    sse_page sse[SSE_MAX];  /* event streams by page */
    int nsse;
    anim_entry anim[ANIM_CACHE];
    size_t anim_next;
    int nsaved;
    double last_save;
    sv_frames *frames;      /* warm hystviz-animate --worker processes (serve_frames.h) */
    char builtin[32][32];   /* hystviz animate --list: the built-in animations */
    char builtin_doc[32][200];
    int nbuiltin;
    int stop_pipe[2];
} server;

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* CPU seconds of the calling thread (a render runs on its connection's
 * thread): on a loaded machine its wall time is mostly waiting for a core */
static double thread_cpu_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Waits on cond (mu held) for at most 0.2 s, so the caller can look at its
 * client or the stop flag between slices. */
static void cond_wait_slice(pthread_cond_t *cond, pthread_mutex_t *mu)
{
    struct timespec until;
    clock_gettime(CLOCK_REALTIME, &until);
    until.tv_nsec += 200000000L;
    if (until.tv_nsec >= 1000000000L)
        until.tv_sec++, until.tv_nsec -= 1000000000L;
    pthread_cond_timedwait(cond, mu, &until);
}

/* ---- responses ------------------------------------------------------ */

/* The headers of every answer but the page's and 503's. */
static void add_headers(struct MHD_Response *r, const char *type)
{
    MHD_add_response_header(r, "Content-Type", type);
    MHD_add_response_header(r, "Cache-Control", "no-store");
    MHD_add_response_header(r, "X-Content-Type-Options", "nosniff");
    MHD_add_response_header(r, "Referrer-Policy", "no-referrer");
    MHD_add_response_header(r, "X-Frame-Options", "DENY");
}

static enum MHD_Result send_buf(struct MHD_Connection *c, unsigned status, const char *type, void *data, size_t len,
                                int must_free, const char *disposition)
{
    struct MHD_Response *r =
        MHD_create_response_from_buffer(len, data, must_free ? MHD_RESPMEM_MUST_FREE : MHD_RESPMEM_PERSISTENT);
    if (!r) {
        if (must_free)
            free(data);
        return MHD_NO;
    }
    add_headers(r, type);
    if (disposition)
        MHD_add_response_header(r, "Content-Disposition", disposition);
    enum MHD_Result ret = MHD_queue_response(c, status, r);
    MHD_destroy_response(r);
    return ret;
}

static enum MHD_Result send_text(struct MHD_Connection *c, unsigned status, const char *msg)
{
    size_t n = strlen(msg);
    char *m = malloc(n + 2);
    if (!m)
        return MHD_NO;
    memcpy(m, msg, n);
    memcpy(m + n, "\n", 2);
    return send_buf(c, status, "text/plain; charset=utf-8", m, n + 1, 1, NULL);
}

static enum MHD_Result send_json(struct MHD_Connection *c, unsigned status, sv_buf *b)
{
    if (b->oom) {
        free(b->s);
        return send_text(c, 500, "out of memory");
    }
    return send_buf(c, status, "application/json", b->s, b->len, 1, NULL);
}

static enum MHD_Result send_error_json(struct MHD_Connection *c, unsigned status, const char *msg)
{
    sv_buf b = {0};
    sv_puts(&b, "{\"error\":");
    sv_json(&b, msg);
    sv_puts(&b, "}");
    return send_json(c, status, &b);
}

/* ---- requests: arguments, host, token ------------------------------- */

typedef struct args {
    int n, too_many;
    const char *scene, *fmt, *page, *seq, *frame, *name, *hover, *from, *to;
    const char *sets[MAX_ARGS];
    size_t nsets;
    int bad_nul;
} args;

static enum MHD_Result arg_it(void *cls, enum MHD_ValueKind kind, const char *key, size_t key_size, const char *value,
                              size_t value_size)
{
    (void)kind;
    args *a = cls;
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
    if (!strcmp(key, "scene"))
        a->scene = value;
    else if (!strcmp(key, "fmt"))
        a->fmt = value;
    else if (!strcmp(key, "page"))
        a->page = value;
    else if (!strcmp(key, "seq"))
        a->seq = value;
    else if (!strcmp(key, "frame"))
        a->frame = value;
    else if (!strcmp(key, "name"))
        a->name = value;
    else if (!strcmp(key, "hover"))
        a->hover = value;
    else if (!strcmp(key, "from"))
        a->from = value;
    else if (!strcmp(key, "to"))
        a->to = value;
    else if (!strcmp(key, "set"))
        a->sets[a->nsets++] = value;
    return MHD_YES;
}

/* The Host header names this server: localhost or the bound address (with
 * our port, if a port is given); with --public any IP literal (a DNS
 * rebinding attack needs a name, never an address). */
static int host_ok(const server *s, const char *h)
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

static int token_ok(const server *s, struct MHD_Connection *c)
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
static char *scene_read(const server *s, const char *name, char *path, size_t size, size_t *len)
{
    char *text = name ? sv_read_beneath(s->dirfd, name, HY_SCENE_MAX_FILE_BYTES, len) : NULL;
    if (text)
        snprintf(path, size, "%s/%s", s->dir_arg, name);
    return text;
}

/* Whether the peer of socket fd has gone (closed or reset its end). */
static int peer_gone(int fd)
{
    struct pollfd p = {.fd = fd, .events = POLLRDHUP};
    return fd >= 0 && poll(&p, 1, 0) > 0 && (p.revents & (POLLRDHUP | POLLHUP | POLLERR));
}

static int client_gone(struct MHD_Connection *c)
{
    const union MHD_ConnectionInfo *ci = MHD_get_connection_info(c, MHD_CONNECTION_INFO_CONNECTION_FD);
    return ci && peer_gone(ci->connect_fd);
}

/* ---- render slots ----------------------------------------------------- */

/* What a render polls between its steps (hy_scene_run.cancelled): the work
 * stops when its client has gone or the server is stopping (issue 20 item 6:
 * requests sent and closed at once kept computing for nobody). */
typedef struct {
    server *s;
    struct MHD_Connection *c;
} render_watch;

/* Counts a stopped render and says so on stderr, at most once a second (a
 * flood of abandoned requests must not flood the terminal). */
static void cancelled_count(server *s)
{
    pthread_mutex_lock(&s->mu);
    unsigned long n = ++s->ncancelled;
    double t = now_s();
    int note = t - s->last_cancel_note >= 1.0;
    if (note)
        s->last_cancel_note = t;
    pthread_mutex_unlock(&s->mu);
    if (note)
        fprintf(stderr, "hystviz serve: stopped a render whose client had gone (%lu so far)\n", n);
}

static int render_unwanted(void *ctx)
{
    const render_watch *w = ctx;
    int stopping;
    pthread_mutex_lock(&w->s->mu);
    stopping = w->s->stopping;
    pthread_mutex_unlock(&w->s->mu);
    return stopping || client_gone(w->c);
}

enum { SLOT_OK, SLOT_GONE, SLOT_FULL, SLOT_STOP };

/* The client address of c as a key: its family and the IPv4 address, or
 * the /64 prefix of an IPv6 address (one host has a whole /64 to pick from). */
static void addr_key(struct MHD_Connection *c, unsigned char key[17])
{
    memset(key, 0, 17);
    const union MHD_ConnectionInfo *ci = c ? MHD_get_connection_info(c, MHD_CONNECTION_INFO_CLIENT_ADDRESS) : NULL;
    const struct sockaddr *sa = ci ? ci->client_addr : NULL;
    if (sa && sa->sa_family == AF_INET) {
        key[0] = 4;
        memcpy(key + 1, &((const struct sockaddr_in *)(const void *)sa)->sin_addr, 4);
    } else if (sa && sa->sa_family == AF_INET6) {
        key[0] = 6;
        memcpy(key + 1, &((const struct sockaddr_in6 *)(const void *)sa)->sin6_addr, 8);
    }
}

/* The entry of key (s->mu held), made if there is none; NULL if the table
 * is full of addresses with work. */
static int addr_find(server *s, const unsigned char key[17])
{
    int fresh = -1;
    for (int i = 0; i < ADDR_MAX; i++) {
        if ((s->addr[i].running || s->addr[i].waiting) && !memcmp(s->addr[i].key, key, 17))
            return i;
        if (fresh < 0 && !s->addr[i].running && !s->addr[i].waiting)
            fresh = i;
    }
    if (fresh >= 0)
        memcpy(s->addr[fresh].key, key, 17);
    return fresh;
}

/* Waits for one of the nslots render slots.  Fairness:
 *  - requests without a page id (an <img>, a script) hold at most half of
 *    the slots, so a page being dragged always finds one;
 *  - per client address (issue 20 item 6: a flood from one client cannot
 *    starve another): at most QUEUE_MAX / 2 of its requests wait, and while
 *    another address waits, one address holds at most nslots - 1 slots, so
 *    the next free slot goes to the other.  Local users all come from
 *    127.0.0.1 and share one entry; serve cannot tell them apart;
 *  - at most QUEUE_MAX wait in all (SLOT_FULL: answer 503).
 * A request whose client has gone (SLOT_GONE) or a stopping server
 * (SLOT_STOP) gives up its turn: nothing is computed for nobody. */
static int slot_take(server *s, struct MHD_Connection *c, int anon)
{
    int cap_anon = s->nslots > 1 ? s->nslots / 2 : 1;
    int cap_addr = s->nslots > 1 ? s->nslots - 1 : 1;
    unsigned char key[17];
    addr_key(c, key);
    pthread_mutex_lock(&s->mu);
    int a = addr_find(s, key);
    if (s->waiting >= QUEUE_MAX || a < 0 || s->addr[a].waiting >= QUEUE_MAX / 2) {
        pthread_mutex_unlock(&s->mu);
        return SLOT_FULL;
    }
    s->waiting++;
    s->addr[a].waiting++;
    int rc = SLOT_OK;
    while (!s->stopping && (s->running >= s->nslots || (anon && s->running_anon >= cap_anon) ||
                            (s->addr[a].running >= cap_addr && s->waiting > s->addr[a].waiting))) {
        cond_wait_slice(&s->cond, &s->mu);
        if (c && client_gone(c)) {
            rc = SLOT_GONE;
            break;
        }
    }
    s->waiting--;
    s->addr[a].waiting--;
    if (s->stopping)
        rc = SLOT_STOP;
    if (rc == SLOT_OK && c && client_gone(c))
        rc = SLOT_GONE;
    if (rc == SLOT_OK) {
        s->running++;
        s->running_anon += anon;
        s->addr[a].running++;
    }
    pthread_cond_broadcast(&s->cond); /* the waiting counts changed */
    pthread_mutex_unlock(&s->mu);
    return rc;
}

/* Frees the slot slot_take gave c's request; the last one out gives the
 * freed memory back to the system (glibc keeps the arenas of every
 * connection thread otherwise). */
static void slot_give(server *s, struct MHD_Connection *c, int anon)
{
    unsigned char key[17];
    addr_key(c, key);
    pthread_mutex_lock(&s->mu);
    s->running--;
    s->running_anon -= anon;
    for (int i = 0; i < ADDR_MAX; i++)
        if (s->addr[i].running && !memcmp(s->addr[i].key, key, 17)) {
            s->addr[i].running--;
            break;
        }
    if (s->running == 0) { /* given back to the kernel after TRIM_IDLE_S idle (idle_trim) */
        s->idle_since = now_s();
        s->trim_due = 1;
    }
    pthread_cond_broadcast(&s->cond);
    pthread_mutex_unlock(&s->mu);
}

/* The memory of the last renders goes back to the kernel (malloc_trim) once
 * serve has rendered nothing for TRIM_IDLE_S, not when each render ends: the
 * next render of a drag reuses those pages instead of faulting fresh ones
 * in (bw_fig1a: 2900 page faults a render; hystviz-serve's mallopt keeps
 * big arrays on the heap).  Called by the main thread every second. */
static void idle_trim(server *s)
{
    pthread_mutex_lock(&s->mu);
    int due = s->trim_due && s->running == 0 && now_s() - s->idle_since >= TRIM_IDLE_S;
    if (due)
        s->trim_due = 0;
    pthread_mutex_unlock(&s->mu);
    if (due)
        malloc_trim(0);
}

static enum MHD_Result send_busy(struct MHD_Connection *c, int why)
{
    if (why == SLOT_GONE || why == SLOT_STOP)
        return MHD_NO; /* nobody to answer */
    sv_buf b = {0};
    sv_puts(&b, "{\"error\":\"the server is busy: try again in a second\"}");
    if (b.oom)
        return MHD_NO;
    struct MHD_Response *r = MHD_create_response_from_buffer(b.len, b.s, MHD_RESPMEM_MUST_FREE);
    if (!r) {
        free(b.s);
        return MHD_NO;
    }
    MHD_add_response_header(r, "Content-Type", "application/json");
    MHD_add_response_header(r, "Cache-Control", "no-store");
    MHD_add_response_header(r, "Retry-After", "1");
    enum MHD_Result ret = MHD_queue_response(c, 503, r);
    MHD_destroy_response(r);
    return ret;
}

/* ---- hystviz-animate, out of process ---------------------------------- */

/* Runs argv with stdout and stderr into out (NUL-terminated, truncated to
 * size); returns the exit status, -1 if it could not run or was killed
 * after CHILD_TIMEOUT_S, -2 if stop_fd (a signalfd, or -1 for none) became
 * readable first (the child is killed).  The child is reaped before this
 * returns. */
static int run_capture(char *const *argv, char *out, size_t size, int stop_fd)
{
    int fd[2];
    out[0] = '\0';
    if (pipe(fd))
        return -1;
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_adddup2(&fa, fd[1], 1);
    posix_spawn_file_actions_adddup2(&fa, fd[1], 2);
    posix_spawn_file_actions_addclose(&fa, fd[0]);
    pid_t pid;
    int sp = posix_spawn(&pid, argv[0], &fa, NULL, argv, environ);
    posix_spawn_file_actions_destroy(&fa);
    close(fd[1]);
    size_t n = 0;
    double deadline = now_s() + CHILD_TIMEOUT_S;
    int killed = 0, stopped = 0;
    for (;;) {
        char tmp[4096];
        struct pollfd pf[2] = {{fd[0], POLLIN, 0}, {stop_fd, POLLIN, 0}};
        double left = deadline - now_s();
        int pr = sp ? 1 : left <= 0 ? 0 : poll(pf, stop_fd >= 0 ? 2 : 1, (int)(left * 1000) + 1);
        if (!sp && stop_fd >= 0 && pr > 0 && (pf[1].revents & POLLIN)) {
            kill(pid, SIGKILL); /* a signal for serve during start-up */
            stopped = 1;
            break;
        }
        if (!sp && pr == 0) {
            kill(pid, SIGKILL); /* hung: its slot and its pipe are freed */
            killed = 1;
            break;
        }
        ssize_t r = read(fd[0], tmp, sizeof tmp);
        if (r < 0 && errno == EINTR)
            continue;
        if (r <= 0)
            break;
        size_t k = (size_t)r < size - 1 - n ? (size_t)r : size - 1 - n;
        memcpy(out + n, tmp, k);
        n += k;
    }
    out[n] = '\0';
    close(fd[0]);
    if (sp)
        return -1;
    int status;
    while (waitpid(pid, &status, 0) < 0)
        if (errno != EINTR)
            return -1;
    return stopped ? -2 : !killed && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/* The built-in animations (hystviz-animate animate --list); -1 when a
 * signal came meanwhile (stop_fd readable), else 0. */
static int list_builtins(server *s, int stop_fd)
{
    char out[8192];
    char *argv[] = {s->animate, "animate", "--list", NULL};
    int rc = s->animate[0] ? run_capture(argv, out, sizeof out, stop_fd) : 1;
    if (rc == -2)
        return -1;
    if (rc != 0)
        return 0; /* no hystviz-animate, or built without OSMesa */
    for (char *line = out; *line && s->nbuiltin < 32;) {
        char *nl = strchr(line, '\n');
        if (nl)
            *nl = '\0';
        if (!*line)
            break; /* the animations end at the first empty line (the GL backend follows) */
        char *sp = strchr(line, ' ');
        if (sp && sp - line < 32 && strspn(line, "abcdefghijklmnopqrstuvwxyz0123456789-") == (size_t)(sp - line)) {
            snprintf(s->builtin[s->nbuiltin], sizeof s->builtin[0], "%.*s", (int)(sp - line), line);
            while (*sp == ' ')
                sp++;
            snprintf(s->builtin_doc[s->nbuiltin], sizeof s->builtin_doc[0], "%s", sp);
            s->nbuiltin++;
        }
        if (!nl)
            break;
        line = nl + 1;
    }
    return 0;
}

/* "@NAME" of a built-in animation: its index, or -1. */
static int builtin_index(const server *s, const char *name)
{
    for (int i = 0; name && name[0] == '@' && i < s->nbuiltin; i++)
        if (!strcmp(name + 1, s->builtin[i]))
            return i;
    return -1;
}

/* The frames and fps of an animation (`hystviz animate WHAT --info`, asked
 * of a frame worker with the scene's text, NULL for a built-in); 0 or -1
 * with msg set.  The answer is cached by hash (hy_scene_hash: the scene's
 * text and its includes), so reloading a page asks nothing; a request runs
 * in a render slot. */
static int anim_info(server *s, struct MHD_Connection *c, uint64_t hash, const char *what, const char *text,
                     size_t len, long *frames, double *fps, char *msg, size_t size)
{
    pthread_mutex_lock(&s->mu);
    for (size_t i = 0; i < ANIM_CACHE; i++)
        if (s->anim[i].hash == hash && (s->anim[i].ok || s->anim[i].msg[0])) {
            anim_entry e = s->anim[i];
            pthread_mutex_unlock(&s->mu);
            *frames = e.frames, *fps = e.fps;
            snprintf(msg, size, "%s", e.msg);
            return e.ok ? 0 : -1;
        }
    pthread_mutex_unlock(&s->mu);
    int slot = slot_take(s, c, 0);
    if (slot != SLOT_OK) {
        snprintf(msg, size, "the server is busy: reload the page");
        return -1;
    }
    aw_request rq = {.op = "info", .name = (char *)what, .text = (char *)text, .len = len};
    char *out = NULL, why[2048];
    int rc = s->frames ? sv_frames_run(s->frames, &rq, NULL, NULL, NULL, NULL, &out, why, sizeof why)
                       : (snprintf(why, sizeof why, "no frame worker"), SV_FRAMES_FAILED);
    slot_give(s, c, 0);
    anim_entry e = {.hash = hash};
    if (rc == 0 && out && sscanf(out, "frames %ld fps %lf", &e.frames, &e.fps) == 2)
        e.ok = 1;
    else
        snprintf(e.msg, sizeof e.msg, "%.*s", (int)sizeof e.msg - 1,
                 rc < 0 ? "cannot run hystviz-animate (it is built next to hystviz)" : why);
    free(out);
    if (rc >= 0) { /* a failure to start is not cached: it may be a passing shortage */
        pthread_mutex_lock(&s->mu);
        s->anim[s->anim_next++ % ANIM_CACHE] = e;
        pthread_mutex_unlock(&s->mu);
    }
    *frames = e.frames, *fps = e.fps;
    snprintf(msg, size, "%s", e.msg);
    return e.ok ? 0 : -1;
}

static void json_anim(sv_buf *b, server *s, struct MHD_Connection *c, uint64_t hash, const char *what,
                      const char *text, size_t len)
{
    long frames = 0;
    double fps = 0;
    char msg[2048];
    if (anim_info(s, c, hash, what, text, len, &frames, &fps, msg, sizeof msg)) {
        sv_puts(b, ",\"anim\":{\"frames\":0,\"error\":");
        sv_json(b, msg);
        sv_puts(b, "}");
        return;
    }
    sv_printf(b, ",\"anim\":{\"frames\":%ld,\"fps\":", frames);
    sv_num(b, fps);
    sv_puts(b, "}");
}

/* FNV-1a of a built-in animation's name (its cache key). */
static uint64_t name_hash(const char *name)
{
    uint64_t h = 0xcbf29ce484222325ull ^ 0x40; /* apart from scene hashes' start */
    for (; *name; name++)
        h = (h ^ (unsigned char)*name) * 0x100000001b3ull;
    return h;
}

/* ---- the catalogue and a scene's description ----------------------- */

/* The header comment of a scene file, without the '#'s. */
static void caption(sv_buf *b, const char *text)
{
    sv_buf c = {0};
    for (const char *p = text; *p == '#';) {
        const char *nl = strchr(p, '\n');
        size_t n = nl ? (size_t)(nl - p) : strlen(p);
        const char *q = p + 1;
        while (q < p + n && *q == ' ')
            q++;
        if (c.len)
            sv_puts(&c, " ");
        sv_add(&c, q, (size_t)(p + n - q));
        if (!nl)
            break;
        p = nl + 1;
    }
    sv_json(b, c.s ? c.s : "");
    free(c.s);
}

/* The gallery's order: by catalogue part, then by file name. */
static int by_name(const void *a, const void *b)
{
    const char *x = *(char *const *)a, *y = *(char *const *)b;
    int d = hy_scene_catalogue_part(x) - hy_scene_catalogue_part(y);
    return d ? d : strcmp(x, y);
}

/* The [figure] caption of d (sc decoded) with its placeholders
 * ({model.sigma0}) replaced by the scene's values (overrides included), as
 * JSON; 0 when it has none.  hy_scene_expand fills them from sc: a
 * placeholder shows a value as the scene text writes it, any key of any
 * section (not only the decoded numbers). */
static int figure_caption(sv_buf *b, const hy_scene *sc, const hy_scene_doc *d)
{
    const char *cap = d->figure.caption;
    char *out = NULL;
    hy_error err = {0};
    if (!sc || hy_decl_got(&d->figure.h, offsetof(hy_decl_figure, caption)) != HY_SCENE_SET || !cap || !*cap)
        return 0;
    sv_json(b, hy_scene_expand(sc, cap, &out, &err) ? cap : out);
    free(out);
    return 1;
}

/* The caption: the scene's [figure] caption (as the gallery), else its header comment. */
static void scene_caption(sv_buf *b, const hy_scene *sc, const hy_scene_doc *d, const char *text)
{
    if (!figure_caption(b, sc, d))
        caption(b, text);
}

static int is_animation(const hy_scene_doc *d)
{
    return d->nkeyframe > 0;
}

static enum MHD_Result api_scenes(server *s, struct MHD_Connection *c)
{
    DIR *d = opendir(s->dir);
    if (!d)
        return send_error_json(c, 500, "cannot read the scenes directory");
    char **v = NULL;
    size_t n = 0, cap = 0;
    for (struct dirent *de; (de = readdir(d));) {
        if (!sv_scene_name_ok(de->d_name))
            continue;
        if (n == cap) {
            char **nv = realloc(v, (cap = cap ? 2 * cap : 64) * sizeof *v);
            if (!nv)
                break;
            v = nv;
        }
        if (!(v[n] = strdup(de->d_name)))
            break;
        n++;
    }
    closedir(d);
    if (n)
        qsort(v, n, sizeof *v, by_name);
    sv_buf b = {0};
    sv_puts(&b, "{\"dir\":");
    sv_json(&b, s->dir_arg);
    sv_puts(&b, ",\"first\":");
    sv_json(&b, s->first);
    sv_puts(&b, ",\"scenes\":[");
    int first = 1;
    for (size_t i = 0; i < n; i++) {
        char path[PATH_MAX + 300];
        hy_scene *sc = NULL;
        hy_error err = {0};
        size_t tl;
        char *text = scene_read(s, v[i], path, sizeof path, &tl);
        if (!text) {
            free(v[i]);
            continue;
        }
        int bad = hy_scene_parse_buffer_policy(path, text, tl, &s->pol, &sc, &err);
        if (!bad && !hy_scene_is_figure(sc)) { /* style.scene and other includes */
            hy_scene_free(sc);
            free(text);
            free(v[i]);
            continue;
        }
        hy_scene_run chk; /* what render refuses before computing: the catalogue says why */
        if (!bad && (bad = hy_scene_run_load_scene(&chk, sc, path, hy_scene_policy_budget(&s->pol), &err)) == 0)
            hy_scene_run_free(&chk);
        char name[256];
        hy_scene_doc d = {0};
        hy_error derr = {0};
        if (sc && hy_scene_decode_fill(sc, &d, &derr)) {
            hy_scene_doc_free(&d); /* out of memory: shown without caption and as a still */
            memset(&d, 0, sizeof d);
        }
        if (sc)
            hy_scene_probe_name(sc, path, name, sizeof name);
        else
            snprintf(name, sizeof name, "%.*s", (int)(strlen(v[i]) - 6), v[i]);
        sv_puts(&b, first ? "{\"file\":" : ",{\"file\":");
        first = 0;
        sv_json(&b, v[i]);
        sv_puts(&b, ",\"name\":");
        sv_json(&b, name);
        sv_puts(&b, ",\"caption\":");
        scene_caption(&b, sc, &d, text);
        char label[32];
        hy_scene_figure_label(v[i], label, sizeof label);
        sv_printf(&b, ",\"label\":\"%s\",\"part\":%d", label, hy_scene_catalogue_part(v[i]));
        sv_printf(&b, ",\"anim\":%s", is_animation(&d) ? "true" : "false");
        if (bad) {
            if (strstr(err.msg, "cannot read included file") && !s->pol.ninclude_dirs)
                hy_error_set(&err, err.code, "%.400s (a file of another directory: start serve with --include-dir DIR)",
                             err.msg);
            sv_puts(&b, ",\"error\":");
            sv_json(&b, err.msg);
        }
        sv_puts(&b, "}");
        free(text);
        hy_scene_doc_free(&d);
        hy_scene_free(sc);
        free(v[i]);
    }
    free(v);
    for (int i = 0; i < s->nbuiltin; i++) {
        char at[40];
        snprintf(at, sizeof at, "@%s", s->builtin[i]);
        sv_puts(&b, first ? "{\"file\":" : ",{\"file\":");
        first = 0;
        sv_json(&b, at);
        sv_puts(&b, ",\"builtin\":true,\"anim\":true,\"part\":4,\"label\":\"\",\"name\":");
        sv_json(&b, s->builtin[i]);
        sv_puts(&b, ",\"caption\":");
        sv_json(&b, s->builtin_doc[i]);
        sv_puts(&b, "}");
    }
    sv_puts(&b, "]}");
    return send_json(c, 200, &b);
}

static enum MHD_Result api_scene(server *s, struct MHD_Connection *c, const args *a)
{
    int bi = builtin_index(s, a->scene);
    if (bi >= 0) {
        sv_buf b = {0};
        sv_puts(&b, "{\"file\":");
        sv_json(&b, a->scene);
        sv_puts(&b, ",\"builtin\":true,\"path\":");
        sv_json(&b, s->builtin[bi]);
        sv_puts(&b, ",\"name\":");
        sv_json(&b, s->builtin[bi]);
        sv_puts(&b, ",\"caption\":");
        sv_json(&b, s->builtin_doc[bi]);
        sv_puts(&b, ",\"text\":\"\",\"controls\":[]");
        json_anim(&b, s, c, name_hash(s->builtin[bi]), s->builtin[bi], NULL, 0);
        sv_puts(&b, "}");
        return send_json(c, 200, &b);
    }
    char path[PATH_MAX + 300];
    size_t tl;
    char *text = scene_read(s, a->scene, path, sizeof path, &tl);
    if (!text)
        return send_error_json(c, 404, "no such scene");
    hy_scene *sc = NULL;
    hy_error err = {0};
    sv_buf b = {0};
    sv_puts(&b, "{\"file\":");
    sv_json(&b, a->scene);
    sv_puts(&b, ",\"path\":");
    sv_json(&b, path);
    sv_puts(&b, ",\"text\":");
    sv_json(&b, text);
    int bad = hy_scene_parse_buffer_policy(path, text, tl, &s->pol, &sc, &err);
    hy_scene_doc d = {0};
    if (!bad && hy_scene_decode_fill(sc, &d, &err)) {
        hy_scene_doc_free(&d);
        hy_scene_free(sc);
        free(text);
        free(b.s);
        return send_error_json(c, 500, err.msg);
    }
    sv_puts(&b, ",\"caption\":");
    scene_caption(&b, bad ? NULL : sc, &d, text);
    if (bad) {
        sv_puts(&b, ",\"controls\":[],\"anim\":null,\"error\":");
        sv_json(&b, err.msg);
    } else {
        char name[256];
        hy_scene_probe_name(sc, path, name, sizeof name);
        sv_puts(&b, ",\"name\":");
        sv_json(&b, name);
        sv_puts(&b, ",\"controls\":");
        sv_controls_json(&b, sc, &d, hy_scene_doc_reads(&d));
        sv_puts(&b, ",\"presets\":");
        sv_presets_json(&b, sc, &d);
        if (is_animation(&d))
            json_anim(&b, s, c, hy_scene_hash(sc), path, text, tl);
        else
            sv_puts(&b, ",\"anim\":null");
        hy_scene_doc_free(&d);
        hy_scene_free(sc);
    }
    free(text);
    sv_puts(&b, "}");
    return send_json(c, 200, &b);
}

static enum MHD_Result api_text(server *s, struct MHD_Connection *c, const char *name)
{
    char path[PATH_MAX + 300];
    size_t n;
    char *text = scene_read(s, name, path, sizeof path, &n);
    if (!text)
        return send_text(c, 404, "not found");
    return send_buf(c, 200, "text/plain; charset=utf-8", text, n, 1, NULL);
}

/* ---- rendering ------------------------------------------------------ */

/* Latest wins: a request for page P with sequence number q waits while a
 * render for P runs; if a newer request for P arrived meanwhile it gives up
 * (409) and the newer one goes next.  Returns the slot, or NULL if superseded. */
static page_slot *page_enter(server *s, const char *id, unsigned long seq)
{
    pthread_mutex_lock(&s->mu);
    page_slot *p = NULL, *old = NULL;
    for (int i = 0; i < MAX_PAGES; i++) {
        if (!strcmp(s->pages[i].id, id))
            p = &s->pages[i];
        if (!s->pages[i].busy && (!old || s->pages[i].used < old->used))
            old = &s->pages[i];
    }
    if (!p && old) { /* the least recently used idle slot */
        p = old;
        snprintf(p->id, sizeof p->id, "%s", id);
        p->latest = 0;
    }
    if (!p) { /* every slot busy: no coalescing for this one */
        pthread_mutex_unlock(&s->mu);
        return (page_slot *)s;
    }
    if (seq > p->latest)
        p->latest = seq;
    while (p->busy && seq == p->latest && !s->stopping)
        pthread_cond_wait(&s->cond, &s->mu);
    if (seq != p->latest || s->stopping || strcmp(p->id, id)) {
        pthread_mutex_unlock(&s->mu);
        return NULL;
    }
    p->busy = 1;
    p->used = now_s();
    pthread_mutex_unlock(&s->mu);
    return p;
}

static void page_leave(server *s, page_slot *p)
{
    if ((void *)p == (void *)s)
        return;
    pthread_mutex_lock(&s->mu);
    p->busy = 0;
    pthread_cond_broadcast(&s->cond);
    pthread_mutex_unlock(&s->mu);
}

static void command_line(sv_buf *b, const char *path, const args *a, const char *fmt)
{
    sv_puts(b, !strcmp(fmt, "csv") ? "hystviz data " : "hystviz render ");
    sv_shell(b, path);
    for (size_t i = 0; i < a->nsets; i++) {
        sv_puts(b, " --set ");
        sv_shell(b, a->sets[i]);
    }
    if (strcmp(fmt, "csv"))
        sv_printf(b, " --format %s", fmt);
}


/* One coordinate array of a series as JSON: null where the point is not
 * finite in x or y (a break between pieces). */
static void json_coords(sv_buf *b, const hy_run_series *se, const double *v)
{
    sv_puts(b, "[");
    for (size_t j = 0; j < se->n; j++) {
        if (j)
            sv_puts(b, ",");
        if (isfinite(se->x[j]) && isfinite(se->y[j]))
            sv_printf(b, "%.9g", v[j]);
        else
            sv_puts(b, "null");
    }
    sv_puts(b, "]");
}

static void json_series(sv_buf *b, const hy_scene_run *r)
{
    sv_puts(b, "[");
    for (size_t i = 0; i < r->nseries; i++) {
        const hy_run_series *se = &r->series[i];
        sv_puts(b, i ? ",{\"name\":" : "{\"name\":");
        sv_json(b, se->name);
        sv_puts(b, ",\"x\":");
        json_coords(b, se, se->x);
        sv_puts(b, ",\"y\":");
        json_coords(b, se, se->y);
        if (se->has_mark)
            sv_printf(b, ",\"mark\":[%.9g,%.9g]", se->mark_x, se->mark_y);
        sv_puts(b, "}");
    }
    sv_puts(b, "]");
}

static enum MHD_Result api_render(server *s, struct MHD_Connection *c, const args *a)
{
    static const char *const ext[] = {HY_FIGURE_FORMATS(HY_FORMAT_EXT) NULL};
    const char *fmt = a->fmt ? a->fmt : "svg";
    int format = !strcmp(fmt, "json") ? HY_FORMAT_SVG : !strcmp(fmt, "csv") ? -2 : -1; /* json: an SVG with its numbers */
    for (int k = 0; format == -1 && ext[k]; k++)
        if (!strcmp(fmt, ext[k]))
            format = k;
    if (format == -1) {
        char msg[96];
        snprintf(msg, sizeof msg, "fmt: %s, csv or json", HY_FORMAT_NAMES);
        return send_error_json(c, 400, msg);
    }
    hy_error err = {0};
    for (size_t i = 0; i < a->nsets; i++)
        if (sv_set_ok(a->sets[i], &err))
            return send_error_json(c, 400, err.msg);
    char path[PATH_MAX + 300];
    size_t tl;
    char *text = scene_read(s, a->scene, path, sizeof path, &tl);
    if (!text)
        return send_error_json(c, 404, "no such scene");
    page_slot *slot = NULL;
    if (a->page) {
        char *end;
        unsigned long seq = a->seq ? strtoul(a->seq, &end, 10) : 0;
        if (strlen(a->page) >= sizeof slot->id || !*a->page) {
            free(text);
            return send_error_json(c, 400, "page: at most 39 characters");
        }
        slot = page_enter(s, a->page, seq);
        if (!slot) {
            free(text);
            return send_error_json(c, 409, "superseded by a newer request of the same page");
        }
    }
    int anon = !a->page, got = slot_take(s, c, anon);
    if (got != SLOT_OK) {
        free(text);
        if (slot)
            page_leave(s, slot);
        return send_busy(c, got);
    }
    double t0 = now_s(), c0 = thread_cpu_s();
    hy_scene_run run;
    int rc = hy_scene_run_load_text(&run, path, text, tl, (char *const *)a->sets, a->nsets, &s->pol, &err);
    free(text);
    int loaded = !rc;
    render_watch watch = {s, c};
    if (!rc) {
        run.cancelled = render_unwanted;
        run.cancel_ctx = &watch;
        /* a figure, not its points (csv, json with hover) */
        run.figure_only = format != -2 && !(a->hover && !strcmp(a->hover, "1"));
    }
    if (!rc && (rc = hy_scene_run_compute(&run, NULL, &err))) {
        hy_scene_run_free(&run);
        loaded = 0;
    }
    unsigned char *bytes = NULL;
    size_t len = 0;
    hy_panel_map map = {0};
    char *csv = NULL;
    if (!rc) {
        if (format == -2)
            rc = hy_scene_run_csv(&run, &csv, &len, &err);
        else
            rc = hy_scene_run_render(&run, format, &bytes, &len, &map, &err);
    }
    double seconds = now_s() - t0, cpu = thread_cpu_s() - c0;
    if (!rc && len > SERVE_OUTPUT_MAX) {
        rc = hy_error_set(&err, HY_EINVAL, "%s: the %s is %.0f MB, over serve's output budget of %u MB per answer "
                          "(hystviz render writes it)", path, fmt, (double)len / (1 << 20), SERVE_OUTPUT_MAX >> 20);
        free(bytes);
        free(csv);
        bytes = NULL, csv = NULL;
    }
    if (slot)
        page_leave(s, slot);
    enum MHD_Result ret;
    if (rc) {
        if (loaded)
            hy_scene_run_free(&run);
        slot_give(s, c, anon);
        if (rc == HY_ECANCEL) { /* nobody to answer: close the connection */
            cancelled_count(s);
            return MHD_NO;
        }
        return send_error_json(c, 422, err.msg);
    }
    char name[256];
    hy_scene_run_name(&run, name, sizeof name);
    if (!strcmp(fmt, "json")) {
        sv_buf b = {0};
        sv_printf(&b, "{\"seq\":%s,\"seconds\":", a->seq && strspn(a->seq, "0123456789") == strlen(a->seq) && *a->seq
                                                      ? a->seq
                                                      : "0");
        sv_num(&b, seconds);
        sv_puts(&b, ",\"cpu\":");
        sv_num(&b, cpu);
        /* the work estimate and budget: the page bounds the sliders whose work grows with them */
        sv_puts(&b, ",\"work\":");
        sv_num(&b, run.work);
        sv_puts(&b, ",\"budget\":");
        sv_num(&b, run.budget);
        sv_puts(&b, ",\"caption\":"); /* with the values drawn ("σ0 = {model.sigma0}") */
        if (!figure_caption(&b, run.scene, &run.doc))
            sv_puts(&b, "null");
        sv_puts(&b, ",\"cmd\":");
        sv_buf cmd = {0};
        command_line(&cmd, path, a, "svg");
        sv_json(&b, cmd.s ? cmd.s : "");
        free(cmd.s);
        sv_puts(&b, ",\"errors\":[");
        int first = 1;
        for (size_t i = 0; i < run.nseries; i++)
            if (!isnan(run.series[i].err)) {
                sv_puts(&b, first ? "{\"series\":" : ",{\"series\":");
                first = 0;
                sv_json(&b, run.series[i].name);
                sv_puts(&b, ",\"err\":");
                sv_num(&b, run.series[i].err);
                sv_puts(&b, ",\"ref\":");
                sv_json(&b, run.series[i].err_ref ? run.series[i].err_ref : "");
                sv_puts(&b, "}");
            }
        /* where the panel was drawn, for hover: pixel box and data ranges */
        const struct {
            const char *key;
            double v;
        } mf[] = {{"x0", map.x0},   {"y0", map.y0},   {"w", map.w},     {"h", map.h},
                  {"xlo", map.xlo}, {"xhi", map.xhi}, {"ylo", map.ylo}, {"yhi", map.yhi}};
        sv_puts(&b, "],\"map\":{");
        for (size_t k = 0; k < sizeof mf / sizeof mf[0]; k++) {
            sv_printf(&b, "%s\"%s\":", k ? "," : "", mf[k].key);
            sv_num(&b, mf[k].v);
        }
        sv_printf(&b, ",\"xlog\":%d,\"ylog\":%d}", map.xlog, map.ylog);
        /* the x quantity by figure kind (timeseries, loop, input, g, psi) */
        static const char *const xname[] = {"t", "u", "t", "v", "\u03f1"};
        sv_printf(&b, ",\"xname\":\"%s\"", run.figure_kind >= 0 && run.figure_kind < 5 ? xname[run.figure_kind] : "x");
        if (a->hover && !strcmp(a->hover, "1")) {
            sv_puts(&b, ",\"series\":");
            json_series(&b, &run);
        }
        sv_puts(&b, ",\"svg\":");
        bytes = realloc(bytes, len + 1);
        if (bytes) {
            bytes[len] = '\0';
            sv_json(&b, (const char *)bytes);
        } else
            b.oom = 1;
        sv_puts(&b, "}");
        free(bytes);
        hy_scene_run_free(&run);
        if (b.len > SERVE_OUTPUT_MAX) {
            free(b.s);
            slot_give(s, c, anon);
            return send_error_json(c, 422, "the figure with its points is over serve's output budget per answer; "
                                           "turn hover off or ask for fewer points");
        }
        slot_give(s, c, anon);
        return send_json(c, 200, &b);
    }
    slot_give(s, c, anon);
    char disp[400];
    snprintf(disp, sizeof disp, "%s; filename=\"%s.%s\"", a->name && !strcmp(a->name, "download") ? "attachment" : "inline",
             name, fmt);
    hy_scene_run_free(&run);
    static const char *const types[] = {"image/svg+xml", "application/pdf", "image/png"};
    if (format == -2)
        return send_buf(c, 200, "text/csv; charset=utf-8", csv, len, 1, disp);
    char hdr[64];
    snprintf(hdr, sizeof hdr, "%.6f", seconds);
    struct MHD_Response *r = MHD_create_response_from_buffer(len, bytes, MHD_RESPMEM_MUST_FREE);
    if (!r) {
        free(bytes);
        return MHD_NO;
    }
    MHD_add_response_header(r, "Content-Type", types[format]);
    MHD_add_response_header(r, "Cache-Control", "no-store");
    MHD_add_response_header(r, "X-Content-Type-Options", "nosniff");
    MHD_add_response_header(r, "Content-Security-Policy", "default-src 'none'; style-src 'unsafe-inline'");
    MHD_add_response_header(r, "Content-Disposition", disp);
    MHD_add_response_header(r, "X-Hystviz-Seconds", hdr);
    ret = MHD_queue_response(c, 200, r);
    MHD_destroy_response(r);
    return ret;
}

/* ---- animation frames: warm hystviz-animate workers (serve_frames.c) ---- */

/* A frame request's animation: a built-in (@NAME) or a catalogue scene,
 * whose text is read once here, checked, and sent to the worker with the
 * path it is shown under (never opened by the worker).  The page's
 * overrides pass the allow-list as a render's do.  0, else an HTTP status
 * with the message in msg. */
static unsigned frame_source(server *s, const args *a, aw_request *rq, char *path, size_t psize, char *msg,
                             size_t msize)
{
    memset(rq, 0, sizeof *rq);
    int bi = builtin_index(s, a->scene);
    if (bi >= 0) {
        if (a->nsets)
            return snprintf(msg, msize, "a built-in animation has no keys to set"), 400;
        snprintf(path, psize, "%s", s->builtin[bi]);
        rq->name = path;
        return 0;
    }
    hy_error err = {0};
    for (size_t i = 0; i < a->nsets; i++)
        if (sv_set_ok(a->sets[i], &err))
            return snprintf(msg, msize, "%s", err.msg), 400;
    size_t tl;
    char *text = scene_read(s, a->scene, path, psize, &tl);
    if (!text)
        return snprintf(msg, msize, "no such scene"), 404;
    hy_scene *chk = NULL;
    if (hy_scene_parse_buffer_policy(path, text, tl, &s->pol, &chk, &err)) {
        free(text);
        return snprintf(msg, msize, "%s", err.msg), 422;
    }
    hy_scene_free(chk);
    rq->name = path, rq->text = text, rq->len = tl;
    for (size_t i = 0; i < a->nsets; i++)
        rq->sets[rq->nsets++] = (char *)a->sets[i];
    return 0;
}

/* A frame index from 0 in text; -1 if it is not one. */
static long frame_index(const char *text)
{
    char *end;
    errno = 0;
    long i = text ? strtol(text, &end, 10) : -1;
    return !text || !*text || *end || errno || i < 0 || i > 9999999 ? -1 : i;
}

/* The HTTP status of a worker's answer: 501 without GL, 503 for no worker, 422. */
static unsigned frame_status(int rc)
{
    return rc == 3 ? 501 : rc == SV_FRAMES_FAILED ? 503 : 422;
}

typedef struct one_frame {
    char *png;
    size_t len;
} one_frame;

static int keep_frame(void *ctx, long index, char *png, size_t len)
{
    (void)index;
    one_frame *f = ctx;
    free(f->png);
    f->png = png, f->len = len;
    return 0;
}

static int conn_gone(void *ctx) { return client_gone(ctx); }

/* GET /api/frame?scene=S&frame=I[&set=K=V]...: the PNG of one frame, byte
 * for byte what `hystviz animate S --frames I:I+1 --set K=V` writes. */
static enum MHD_Result api_frame(server *s, struct MHD_Connection *c, const args *a)
{
    char path[PATH_MAX + 300], msg[4096];
    aw_request rq;
    unsigned bad = frame_source(s, a, &rq, path, sizeof path, msg, sizeof msg);
    if (bad)
        return send_error_json(c, bad, msg);
    long frame = frame_index(a->frame);
    if (!s->frames) {
        free(rq.text);
        return send_error_json(c, 501, "cannot run hystviz-animate (it is built next to hystviz)");
    }
    if (frame < 0) {
        free(rq.text);
        return send_error_json(c, 400, "frame: a frame index from 0");
    }
    page_slot *slot = NULL;
    if (a->page) {
        char *end;
        unsigned long seq = a->seq ? strtoul(a->seq, &end, 10) : 0;
        if (strlen(a->page) >= sizeof slot->id || !*a->page) {
            free(rq.text);
            return send_error_json(c, 400, "page: at most 39 characters");
        }
        slot = page_enter(s, a->page, seq);
        if (!slot) {
            free(rq.text);
            return send_error_json(c, 409, "superseded by a newer request of the same page");
        }
    }
    snprintf(rq.op, sizeof rq.op, "frames");
    rq.first = frame, rq.last = frame + 1;
    one_frame got = {0};
    int taken = slot_take(s, c, !a->page), rc = SV_FRAMES_GONE;
    if (taken == SLOT_OK) {
        rc = sv_frames_run(s->frames, &rq, keep_frame, &got, conn_gone, c, NULL, msg, sizeof msg);
        slot_give(s, c, !a->page);
    }
    free(rq.text);
    if (slot)
        page_leave(s, slot);
    if (taken != SLOT_OK)
        return send_busy(c, taken);
    if (rc == 0 && got.png)
        return send_buf(c, 200, "image/png", got.png, got.len, 1, NULL);
    free(got.png);
    if (rc == SV_FRAMES_GONE)
        return MHD_NO;
    return send_error_json(c, frame_status(rc), msg[0] ? msg : "hystviz animate failed");
}

/* ---- a stream of frames (playback) ---- */

/* GET /api/frames?scene=S&from=A&to=B[&set=K=V]...&page=P&seq=N streams
 * frames A .. B-1 as records "frame I LEN\n<PNG>" (anim_worker.h), then
 * "end N 0\n", or "error STATUS LEN\n<message>" at the first failure.  Each
 * frame is rendered when the connection can take it, in a render slot, by
 * a warm worker; the stream ends when its client goes, the server stops or
 * a newer stream of the same page (seq) starts. */
typedef struct frame_stream {
    server *s;
    struct MHD_Connection *c;
    aw_request rq;
    char path[PATH_MAX + 300];
    char page[48];
    unsigned long seq;
    long next, to, sent;
    char *buf;                /* the record being sent */
    size_t len, off;
    int ended;
} frame_stream;

static void stream_free(void *cls)
{
    frame_stream *st = cls;
    free(st->rq.text);
    free(st->buf);
    free(st);
}

/* The record "TAG NUM LEN\n" + data as st's buffer (data is the callee's). */
static int stream_record(frame_stream *st, const char *tag, long num, char *data, size_t len)
{
    char head[64];
    int h = snprintf(head, sizeof head, "%s %ld %zu\n", tag, num, len);
    char *b = malloc((size_t)h + len);
    if (b) {
        memcpy(b, head, (size_t)h);
        if (len)
            memcpy(b + h, data, len);
    }
    free(data);
    free(st->buf);
    st->buf = b, st->len = b ? (size_t)h + len : 0, st->off = 0;
    return b ? 0 : -1;
}

static int stream_frame(void *ctx, long index, char *png, size_t len)
{
    frame_stream *st = ctx;
    st->sent++;
    return stream_record(st, "frame", index, png, len);
}

/* Renders the next frame into st's buffer; -1 ends the stream at once. */
static int stream_next(frame_stream *st)
{
    server *s = st->s;
    if (st->next >= st->to) {
        st->ended = 1;
        return stream_record(st, "end", st->sent, NULL, 0);
    }
    page_slot *slot = page_enter(s, st->page, st->seq);
    if (!slot)
        return -1; /* a newer stream of the page: this one's frames are stale */
    int taken = slot_take(s, st->c, 0), rc = SV_FRAMES_GONE;
    char msg[4096] = "";
    if (taken == SLOT_OK) {
        st->rq.first = st->next, st->rq.last = st->next + 1;
        rc = sv_frames_run(s->frames, &st->rq, stream_frame, st, conn_gone, st->c, NULL, msg, sizeof msg);
        slot_give(s, st->c, 0);
    }
    page_leave(s, slot);
    if (taken != SLOT_OK || rc == SV_FRAMES_GONE)
        return -1;
    if (rc) {
        st->ended = 1;
        char *m = strdup(msg[0] ? msg : "hystviz animate failed");
        return stream_record(st, "error", (long)frame_status(rc), m, m ? strlen(m) : 0);
    }
    st->next++;
    return 0;
}

static ssize_t stream_read(void *cls, uint64_t pos, char *out, size_t max)
{
    (void)pos;
    frame_stream *st = cls;
    if (st->off == st->len) {
        if (st->ended)
            return MHD_CONTENT_READER_END_OF_STREAM;
        if (st->s->stopping || client_gone(st->c) || stream_next(st))
            return MHD_CONTENT_READER_END_WITH_ERROR;
    }
    size_t n = st->len - st->off < max ? st->len - st->off : max;
    memcpy(out, st->buf + st->off, n);
    st->off += n;
    return (ssize_t)n;
}

static enum MHD_Result api_frames(server *s, struct MHD_Connection *c, const args *a)
{
    frame_stream *st = calloc(1, sizeof *st);
    if (!st)
        return send_text(c, 500, "out of memory");
    char msg[4096];
    unsigned bad = frame_source(s, a, &st->rq, st->path, sizeof st->path, msg, sizeof msg);
    if (!bad && ((st->next = frame_index(a->from)) < 0 || (st->to = frame_index(a->to)) <= st->next))
        bad = 400, snprintf(msg, sizeof msg, "from, to: frames from .. to-1, 0 <= from < to");
    if (!bad && !s->frames)
        bad = 501, snprintf(msg, sizeof msg, "cannot run hystviz-animate (it is built next to hystviz)");
    if (!bad && (!a->page || !*a->page || strlen(a->page) >= sizeof s->pages[0].id))
        bad = 400, snprintf(msg, sizeof msg, "page: a stream needs the page's id (at most 39 characters)");
    if (bad) {
        stream_free(st);
        return send_error_json(c, bad, msg);
    }
    char *end;
    st->s = s, st->c = c;
    st->seq = a->seq ? strtoul(a->seq, &end, 10) : 0;
    snprintf(st->page, sizeof st->page, "%s", a->page);
    snprintf(st->rq.op, sizeof st->rq.op, "frames");
    struct MHD_Response *r = MHD_create_response_from_callback(MHD_SIZE_UNKNOWN, 1 << 16, stream_read, st, stream_free);
    if (!r) {
        stream_free(st);
        return MHD_NO;
    }
    add_headers(r, "application/octet-stream");
    enum MHD_Result ret = MHD_queue_response(c, 200, r);
    MHD_destroy_response(r);
    return ret;
}

/* ---- save as new scene ---------------------------------------------- */

/* Removes every '#' that starts a line or follows a space, to the end of its line. */
static void strip_comments(char *w)
{
    if (!w)
        return;
    char *o = w;
    for (char *p = w; *p;) {
        if (*p == '#' && (p == w || p[-1] == ' ' || p[-1] == '\n')) {
            while (o > w && o[-1] == ' ')
                o--;
            while (*p && *p != '\n')
                p++;
            continue;
        }
        *o++ = *p++;
    }
    *o = '\0';
}

/* Saving is opt-in (--allow-save) and limited: SAVE_MAX files a run, one
 * every SAVE_EVERY_S.  Returns 1 after answering 429 (with Retry-After) when
 * over a limit, 0 when the save may go on: it is counted now (so two at once
 * cannot both pass) and *prev receives the time to restore if writing fails. */
static int save_refused(server *s, struct MHD_Connection *c, double *prev)
{
    pthread_mutex_lock(&s->mu);
    double t = now_s();
    int full = s->nsaved >= SAVE_MAX, soon = !full && s->nsaved && t - s->last_save < SAVE_EVERY_S;
    if (!full && !soon) {
        *prev = s->last_save;
        s->nsaved++;
        s->last_save = t;
    }
    pthread_mutex_unlock(&s->mu);
    if (!full && !soon)
        return 0;
    sv_buf b = {0};
    sv_puts(&b, full ? "{\"error\":\"this server has saved its limit of scenes; restart it to save more\"}"
                     : "{\"error\":\"one save a second: try again\"}");
    struct MHD_Response *r = b.oom ? NULL : MHD_create_response_from_buffer(b.len, b.s, MHD_RESPMEM_MUST_FREE);
    if (!r) {
        free(b.s);
        return 1;
    }
    MHD_add_response_header(r, "Content-Type", "application/json");
    if (soon)
        MHD_add_response_header(r, "Retry-After", "1");
    MHD_queue_response(c, 429, r);
    MHD_destroy_response(r);
    return 1;
}

/* Save as new scene: NAME.scene with the page's overrides written in, after
 * checking that it renders what the page shows; the rate limit is applied
 * just before writing, so a refused request (400, 409, 422) does not count. */
static enum MHD_Result api_save(server *s, struct MHD_Connection *c, const args *a)
{
    char path[PATH_MAX + 300];
    size_t tl;
    char *text = scene_read(s, a->scene, path, sizeof path, &tl);
    if (!text)
        return send_error_json(c, 404, "no such scene");
    const char *nm = a->name;
    size_t nl = nm ? strlen(nm) : 0;
    if (!nm || !nl || nl > 100 || nm[0] == '.' || nm[0] == '-' || strspn(nm, "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-") != nl) {
        free(text);
        return send_error_json(c, 400, "name: 1 to 100 letters, digits, '_' or '-' (the new scene is NAME.scene)");
    }
    hy_error err = {0};
    for (size_t i = 0; i < a->nsets; i++)
        if (sv_set_ok(a->sets[i], &err)) {
            free(text);
            return send_error_json(c, 400, err.msg);
        }
    char dest[PATH_MAX + 300];
    snprintf(dest, sizeof dest, "%s/%s.scene", s->dir_arg, nm);
    hy_scene *orig = NULL, *want = NULL;
    if (hy_scene_parse_buffer_policy(path, text, tl, &s->pol, &orig, &err) ||
        hy_scene_parse_buffer_policy(path, text, tl, &s->pol, &want, &err)) {
        hy_scene_free(orig);
        free(text);
        return send_error_json(c, 422, err.msg);
    }
    /* the new scene must render what the page shows: the original with the
       overrides (and the new output name) */
    char *newtext = sv_scene_with_sets(orig, path, text, (char *const *)a->sets, a->nsets, nm, &err);
    hy_scene_free(orig);
    free(text);
    if (!newtext) {
        hy_scene_free(want);
        return send_error_json(c, 422, err.msg);
    }
    const char *sets[MAX_ARGS + 1];
    char outset[200];
    snprintf(outset, sizeof outset, "output.name=%s", nm);
    for (size_t i = 0; i < a->nsets; i++)
        sets[i] = a->sets[i];
    sets[a->nsets] = outset;
    hy_scene *got = NULL;
    int rc = HY_OK;
    for (size_t i = 0; !rc && i <= a->nsets; i++)
        rc = hy_scene_set(want, sets[i], &err);
    if (!rc)
        rc = hy_scene_parse_buffer_policy(dest, newtext, strlen(newtext), &s->pol, &got, &err);
    if (!rc) { /* same effective values: the scenes written back without origins agree */
        char *w1 = NULL, *w2 = NULL;
        size_t l1 = 0, l2 = 0;
        FILE *f1 = open_memstream(&w1, &l1), *f2 = open_memstream(&w2, &l2);
        if (f1 && f2) {
            hy_scene_write(want, f1, 1);
            hy_scene_write(got, f2, 1);
        }
        if (f1)
            fclose(f1);
        if (f2)
            fclose(f2);
        /* drop the comments (origins, the header) before comparing */
        strip_comments(w1);
        strip_comments(w2);
        if (!w1 || !w2 || strcmp(w1, w2))
            rc = hy_error_set(&err, HY_EINVAL, "the new scene would not reproduce the figure; nothing was written");
        free(w1);
        free(w2);
    }
    hy_scene_free(want);
    hy_scene_free(got);
    char file[200];
    snprintf(file, sizeof file, "%s.scene", nm);
    struct stat st;
    if (!rc && !fstatat(s->dirfd, file, &st, AT_SYMLINK_NOFOLLOW)) /* link(2) below decides; this names it early */
        rc = hy_error_set(&err, HY_EINVAL, "%s exists already: choose another name", dest);
    double prev = 0;
    if (!rc && save_refused(s, c, &prev)) { /* answered 429 */
        free(newtext);
        return MHD_YES;
    }
    if (!rc && (rc = sv_write_new(dest, newtext, strlen(newtext), &err))) { /* nothing written: not counted */
        pthread_mutex_lock(&s->mu);
        s->nsaved--;
        s->last_save = prev;
        pthread_mutex_unlock(&s->mu);
    }
    free(newtext);
    if (rc)
        return send_error_json(c, rc == HY_EINVAL ? 409 : 500, err.msg);
    sv_buf b = {0};
    sv_puts(&b, "{\"file\":");
    sv_json(&b, file);
    sv_puts(&b, ",\"path\":");
    sv_json(&b, dest);
    sv_puts(&b, "}");
    return send_json(c, 201, &b);
}

/* ---- Server-Sent Events --------------------------------------------- */

typedef struct sse_client {
    server *s;
    unsigned long seen;
    int hello;
    int fd;                 /* the connection's socket: a closed peer frees the slot at once */
    sse_page *page;         /* the slot counted in s->sse */
    double last;            /* when something was last sent */
} sse_client;


static ssize_t sse_read(void *cls, uint64_t pos, char *buf, size_t max)
{
    (void)pos;
    sse_client *cl = cls;
    server *s = cl->s;
    if (max < 64)
        return 0;
    pthread_mutex_lock(&s->mu);
    if (s->stopping) {
        pthread_mutex_unlock(&s->mu);
        return MHD_CONTENT_READER_END_OF_STREAM;
    }
    if (!cl->hello) {
        cl->hello = 1;
        cl->seen = s->gen;
        int n = snprintf(buf, max, "retry: 1000\nevent: hello\ndata: {\"gen\":%lu}\n\n", s->gen);
        pthread_mutex_unlock(&s->mu);
        return n;
    }
    /* wait for a change in slices of 0.2 s, looking at the peer between them */
    int gone = 0;
    while (cl->seen == s->gen && !s->stopping && now_s() - cl->last < SSE_PING_S && !gone) {
        cond_wait_slice(&s->cond, &s->mu);
        gone = peer_gone(cl->fd);
    }
    if (gone) {
        pthread_mutex_unlock(&s->mu);
        return MHD_CONTENT_READER_END_WITH_ERROR;
    }
    if (s->stopping) {
        pthread_mutex_unlock(&s->mu);
        return MHD_CONTENT_READER_END_OF_STREAM;
    }
    cl->last = now_s();
    if (cl->seen == s->gen) {
        pthread_mutex_unlock(&s->mu);
        return snprintf(buf, max, ": ping\n\n");
    }
    cl->seen = s->gen;
    sv_buf b = {0};
    sv_printf(&b, "event: change\ndata: {\"gen\":%lu,\"files\":", s->gen);
    sv_json(&b, s->changed);
    sv_puts(&b, "}\n\n");
    pthread_mutex_unlock(&s->mu);
    ssize_t n = 0;
    if (!b.oom && b.len <= max) {
        memcpy(buf, b.s, b.len);
        n = (ssize_t)b.len;
    } else
        n = snprintf(buf, max, "event: change\ndata: {\"gen\":%lu,\"files\":\"\"}\n\n", cl->seen);
    free(b.s);
    return n;
}

static void sse_free(void *cls)
{
    sse_client *cl = cls;
    server *s = cl->s;
    pthread_mutex_lock(&s->mu);
    if (cl->page && --cl->page->n == 0)
        cl->page->id[0] = '\0';
    s->nsse--;
    pthread_mutex_unlock(&s->mu);
    free(cl);
}

/* Counts a new stream of page id; NULL when over SSE_MAX in all or
 * SSE_PER_PAGE for the page. */
static sse_page *sse_enter(server *s, const char *id)
{
    pthread_mutex_lock(&s->mu);
    sse_page *p = NULL, *free_slot = NULL;
    for (int i = 0; i < SSE_MAX; i++) {
        if (s->sse[i].n && !strcmp(s->sse[i].id, id))
            p = &s->sse[i];
        else if (!s->sse[i].n && !free_slot)
            free_slot = &s->sse[i];
    }
    if (s->nsse >= SSE_MAX || (p && p->n >= SSE_PER_PAGE) || (!p && !free_slot)) {
        pthread_mutex_unlock(&s->mu);
        return NULL;
    }
    if (!p) {
        p = free_slot;
        snprintf(p->id, sizeof p->id, "%s", id);
    }
    p->n++;
    s->nsse++;
    pthread_mutex_unlock(&s->mu);
    return p;
}

static enum MHD_Result events(server *s, struct MHD_Connection *c, const args *a)
{
    const char *id = a->page ? a->page : "";
    if (strlen(id) >= sizeof s->sse[0].id)
        return send_text(c, 400, "page: at most 39 characters");
    sse_page *pg = sse_enter(s, id);
    if (!pg)
        return send_busy(c, SLOT_FULL);
    sse_client *cl = calloc(1, sizeof *cl);
    if (!cl) {
        pthread_mutex_lock(&s->mu);
        if (--pg->n == 0)
            pg->id[0] = '\0';
        s->nsse--;
        pthread_mutex_unlock(&s->mu);
        return MHD_NO;
    }
    cl->s = s;
    cl->page = pg;
    cl->last = now_s();
    const union MHD_ConnectionInfo *ci = MHD_get_connection_info(c, MHD_CONNECTION_INFO_CONNECTION_FD);
    cl->fd = ci ? ci->connect_fd : -1;
    struct MHD_Response *r = MHD_create_response_from_callback(MHD_SIZE_UNKNOWN, 4096, sse_read, cl, sse_free);
    if (!r) {
        sse_free(cl);
        return MHD_NO;
    }
    MHD_add_response_header(r, "Content-Type", "text/event-stream");
    MHD_add_response_header(r, "Cache-Control", "no-store");
    enum MHD_Result ret = MHD_queue_response(c, 200, r);
    MHD_destroy_response(r);
    return ret;
}

/* ---- dispatch ------------------------------------------------------- */

typedef struct conn_state {
    size_t body;
    int started;            /* handle() has seen the headers */
    int too_many;           /* more than MAX_QUERY query arguments: answered 400 */
} conn_state;

/* Called with the request line's URI before libmicrohttpd stores the query
 * arguments (each costs memory from the connection's pool; about 1,000 ran it
 * out and the connection was closed with no answer).  Past MAX_QUERY the
 * query is cut in place, in the buffer libmicrohttpd itself rewrites while
 * parsing, so none is stored, and handle() answers 400. */
static void *uri_seen(void *cls, const char *uri, struct MHD_Connection *c)
{
    (void)cls;
    (void)c;
    conn_state *cs = calloc(1, sizeof *cs);
    char *q = uri ? strchr(uri, '?') : NULL;
    size_t n = 0;
    for (const char *p = q; p && *p; p++)
        n += *p == '&';
    if (q && n + 1 > MAX_QUERY) {
        q[1] = '\0';
        if (cs)
            cs->too_many = 1;
    }
    return cs;
}

static enum MHD_Result handle_request(void *cls, struct MHD_Connection *c, const char *url, const char *method,
                                      const char *version, const char *upload, size_t *upload_size, void **con_cls)
{
    (void)version;
    (void)upload;
    server *s = cls;
    conn_state *cs = *con_cls;
    if (!cs)
        return MHD_NO; /* out of memory in uri_seen */
    if (!cs->started) {
        cs->started = 1;
        return MHD_YES;
    }
    if (*upload_size) { /* no request needs a body: count it, keep none */
        cs->body += *upload_size;
        *upload_size = 0;
        return MHD_YES;
    }
    if (cs->body > MAX_BODY)
        return send_text(c, 413, "request body too large");
    if (!host_ok(s, MHD_lookup_connection_value(c, MHD_HEADER_KIND, "Host")))
        return send_text(c, 403, "Host header not allowed (use http://localhost:PORT/ or the bound address)");
    /* another site's page (an <img> flood, a form): chromium and firefox say
       so; nothing here is meant to be embedded, so it is refused before any work */
    const char *site = MHD_lookup_connection_value(c, MHD_HEADER_KIND, "Sec-Fetch-Site");
    if (site && strcmp(site, "same-origin") && strcmp(site, "none"))
        return send_text(c, 403, "requests from other sites are refused");
    int get = !strcmp(method, "GET") || !strcmp(method, "HEAD"), post = !strcmp(method, "POST");
    if (!get && !post)
        return send_text(c, 405, "method not allowed");
    args a;
    memset(&a, 0, sizeof a);
    MHD_get_connection_values_n(c, MHD_GET_ARGUMENT_KIND, arg_it, &a);
    if (a.too_many || cs->too_many)
        return send_text(c, 400, "too many query arguments");
    if (a.bad_nul)
        return send_text(c, 404, "not found");
    if (post) {
        if (strcmp(url, "/api/save"))
            return send_text(c, 405, "method not allowed");
        if (!s->allow_save)
            return send_text(c, 403, "saving is off: start hystviz serve with --allow-save");
        if (!token_ok(s, c))
            return send_text(c, 403, "missing or wrong X-Hystviz-Token (reload the page)");
        return api_save(s, c, &a);
    }
    if (!strcmp(url, "/") || !strcmp(url, "/index.html")) {
        struct MHD_Response *r = MHD_create_response_from_buffer(s->page_len, s->page, MHD_RESPMEM_PERSISTENT);
        if (!r)
            return MHD_NO;
        MHD_add_response_header(r, "Content-Type", "text/html; charset=utf-8");
        MHD_add_response_header(r, "Cache-Control", "no-store");
        MHD_add_response_header(r, "X-Content-Type-Options", "nosniff");
        MHD_add_response_header(r, "X-Frame-Options", "DENY");
        MHD_add_response_header(r, "Referrer-Policy", "no-referrer");
        MHD_add_response_header(r, "Content-Security-Policy",
                                "default-src 'self'; img-src 'self' data: blob:; style-src 'self' 'unsafe-inline'; "
                                "script-src 'self'; frame-ancestors 'none'");
        enum MHD_Result ret = MHD_queue_response(c, 200, r);
        MHD_destroy_response(r);
        return ret;
    }
    if (!strcmp(url, "/app.js"))
        return send_buf(c, 200, "text/javascript; charset=utf-8", (void *)hy_page_js, hy_page_js_len, 0, NULL);
    if (!strcmp(url, "/app.css"))
        return send_buf(c, 200, "text/css; charset=utf-8", (void *)hy_page_css, hy_page_css_len, 0, NULL);
    if (!strcmp(url, "/events"))
        return events(s, c, &a);
    if (!strcmp(url, "/api/scenes"))
        return api_scenes(s, c);
    if (!strcmp(url, "/api/scene"))
        return api_scene(s, c, &a);
    if (!strcmp(url, "/api/render"))
        return api_render(s, c, &a);
    if (!strcmp(url, "/api/frame"))
        return api_frame(s, c, &a);
    if (!strcmp(url, "/api/frames"))
        return api_frames(s, c, &a);
    if (!strncmp(url, "/scenes/", 8))
        return api_text(s, c, url + 8);
    return send_text(c, 404, "not found");
}

/* The idle timeout is for the network: it is off while the request is being
 * answered (waiting for a render slot, rendering) and on again, counted from
 * now, for sending the answer (libmicrohttpd checks it after the handler
 * returns, and dropped answers that took longer than the timeout to make). */
static enum MHD_Result handle(void *cls, struct MHD_Connection *c, const char *url, const char *method,
                              const char *version, const char *upload, size_t *upload_size, void **con_cls)
{
    MHD_set_connection_option(c, MHD_CONNECTION_OPTION_TIMEOUT, 0u);
    enum MHD_Result ret = handle_request(cls, c, url, method, version, upload, upload_size, con_cls);
    MHD_set_connection_option(c, MHD_CONNECTION_OPTION_TIMEOUT, (unsigned)CONN_TIMEOUT_S);
    return ret;
}

static void done(void *cls, struct MHD_Connection *c, void **con_cls, enum MHD_RequestTerminationCode toe)
{
    (void)cls;
    (void)c;
    (void)toe;
    free(*con_cls);
    *con_cls = NULL;
}

/* ---- the watcher thread --------------------------------------------- */

static void *watcher(void *arg)
{
    server *s = arg;
    const char *dirs[1] = {s->dir};
    hy_error err;
    hy_dirwatch *w = hy_dirwatch_open(dirs, 1, &err);
    if (!w) {
        fprintf(stderr, "hystviz serve: %s; pages will not reload on save\n", err.msg);
        return NULL;
    }
    char names[2048];
    for (;;) {
        int r = hy_dirwatch_wait(w, s->stop_pipe[0], -1, names, sizeof names, &err);
        if (r <= 0) {
            if (r < 0)
                fprintf(stderr, "hystviz serve: %s; pages will not reload on save\n", err.msg);
            break;
        }
        pthread_mutex_lock(&s->mu);
        s->gen++;
        /* the names relative to the directory */
        sv_buf b = {0};
        size_t dl = strlen(s->dir);
        for (char *p = names; *p;) {
            char *nl = strchr(p, '\n');
            size_t n = nl ? (size_t)(nl - p) : strlen(p);
            if (n > dl && !strncmp(p, s->dir, dl) && p[dl] == '/') {
                if (b.len)
                    sv_puts(&b, "\n");
                sv_add(&b, p + dl + 1, n - dl - 1);
            }
            p += n + (nl ? 1 : 0);
        }
        snprintf(s->changed, sizeof s->changed, "%s", b.s ? b.s : "");
        free(b.s);
        pthread_cond_broadcast(&s->cond);
        pthread_mutex_unlock(&s->mu);
    }
    hy_dirwatch_close(w);
    return NULL;
}

/* ---- the command ---------------------------------------------------- */

static int parse_port(const char *v, int *port)
{
    char *end;
    errno = 0;
    long p = v ? strtol(v, &end, 10) : -1;
    if (!v || errno || *end || end == v || p < 0 || p > 65535)
        return -1;
    *port = (int)p;
    return 0;
}

static int make_page(server *s)
{
    const char *mark = strstr(hy_page_html, "@TOKEN@");
    if (!mark)
        return -1;
    /* without --allow-save the page gets no token (and shows no save button) */
    const char *token = s->allow_save ? s->token : "";
    size_t pre = (size_t)(mark - hy_page_html), tl = strlen(token);
    s->page_len = hy_page_html_len - 7 + tl;
    s->page = malloc(s->page_len + 1);
    if (!s->page)
        return -1;
    memcpy(s->page, hy_page_html, pre);
    memcpy(s->page + pre, token, tl);
    memcpy(s->page + pre + tl, mark + 7, hy_page_html_len - pre - 7 + 1);
    return 0;
}

int hy_cmd_serve(int argc, char **argv)
{
    const char *target = NULL, *host = "127.0.0.1";
    int port = 8017, public_ = 0, open_browser = 0, host_given = 0, allow_save = 0;
    double max_work = SERVE_WORK_DEFAULT;
    hy_scene_policy pol = hy_scene_policy_default();
    const char *incdirs[SERVE_INCLUDE_DIRS];
    cli_parser p;
    cli_parser_init(&p, &serve_cli, argc, argv, 1);
    for (int id; (id = cli_next(&p)) != CLI_END;) {
        const char *v = p.val;
        switch (id) {
        case CLI_STOP: return 0;
        case CLI_ERROR: return 2;
        case CLI_INCLUDE_DIR: /* as render's */
            if (pol.ninclude_dirs == SERVE_INCLUDE_DIRS) {
                fprintf(stderr, "hystviz serve: at most %d --include-dir\n", SERVE_INCLUDE_DIRS);
                return 2;
            }
            if (cli_policy_take(&pol, incdirs, "serve", id, v) < 0)
                return 2;
            break;
        case OPT_PORT:
            if (parse_port(v, &port)) {
                fprintf(stderr, "hystviz serve: --port '%s': give a port from 0 to 65535\n", v);
                return 2;
            }
            break;
        case OPT_HOST: host = v, host_given = 1; break;
        case OPT_MAX_WORK: {
            char *end;
            errno = 0;
            max_work = strtod(v, &end);
            if (errno || *end || end == v || !(max_work >= 1) || !isfinite(max_work)) {
                fprintf(stderr, "hystviz serve: --max-work '%s': give a number of at least 1 (e.g. 1e8)\n", v);
                return 2;
            }
            break;
        }
        case OPT_ALLOW_SAVE: allow_save = 1; break;
        case OPT_PUBLIC: public_ = 1; break;
        case OPT_OPEN: open_browser = 1; break;
        default: /* CLI_ARG */
            if (target)
                return cli_unexpected(&p), 2;
            target = v;
        }
    }
    (void)host_given;
    server *s = calloc(1, sizeof *s);
    if (!s) {
        fprintf(stderr, "hystviz serve: out of memory\n");
        return 1;
    }
    int rc = 2;
    struct sockaddr_in6 sa6;
    struct sockaddr_in sa4;
    memset(&sa6, 0, sizeof sa6);
    memset(&sa4, 0, sizeof sa4);
    if (inet_pton(AF_INET, host, &sa4.sin_addr) == 1) {
        sa4.sin_family = AF_INET;
        sa4.sin_port = htons((uint16_t)port);
    } else if (inet_pton(AF_INET6, host, &sa6.sin6_addr) == 1) {
        sa6.sin6_family = AF_INET6;
        sa6.sin6_port = htons((uint16_t)port);
        s->ipv6 = 1;
    } else {
        fprintf(stderr, "hystviz serve: --host '%s': give an IPv4 or IPv6 address (e.g. 127.0.0.1, ::1)\n", host);
        free(s);
        return 2;
    }
    int loopback = s->ipv6 ? IN6_IS_ADDR_LOOPBACK(&sa6.sin6_addr) : (ntohl(sa4.sin_addr.s_addr) >> 24) == 127;
    if (!loopback && !public_) {
        fprintf(stderr, "hystviz serve: --host %s is reachable from other machines: add --public if that is meant\n",
                host);
        free(s);
        return 2;
    }
    snprintf(s->host, sizeof s->host, "%s", host);
    s->public_ = public_;
    s->allow_save = allow_save;
    s->max_work = max_work;
    for (size_t k = 0; k < pol.ninclude_dirs; k++)
        s->incdirs[k] = incdirs[k];
    s->pol = pol;
    s->pol.include_dirs = s->incdirs;
    s->pol.max_work = max_work;
    /* the directory, and the scene to open first */
    const char *dir = target ? target : "scenes";
    char dirbuf[PATH_MAX];
    struct stat st;
    if (stat(dir, &st)) {
        fprintf(stderr, "hystviz serve: %s: %s\n", dir, strerror(errno));
        free(s);
        return 2;
    }
    if (S_ISREG(st.st_mode)) {
        const char *slash = strrchr(dir, '/');
        snprintf(s->first, sizeof s->first, "%s", slash ? slash + 1 : dir);
        if (!sv_scene_name_ok(s->first)) {
            fprintf(stderr, "hystviz serve: %s: give a NAME.scene file (letters, digits, _ - .) or a directory\n", dir);
            free(s);
            return 2;
        }
        if (slash)
            snprintf(dirbuf, sizeof dirbuf, "%.*s", (int)(slash - dir), dir);
        else
            snprintf(dirbuf, sizeof dirbuf, ".");
        if (!dirbuf[0])
            snprintf(dirbuf, sizeof dirbuf, "/");
        dir = dirbuf;
    }
    if (!realpath(dir, s->dir)) {
        fprintf(stderr, "hystviz serve: %s: %s\n", dir, strerror(errno));
        free(s);
        return 2;
    }
    s->dir_arg = dir;
    if ((s->dirfd = open(s->dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC)) < 0) {
        fprintf(stderr, "hystviz serve: %s: %s\n", dir, strerror(errno));
        free(s);
        return 2;
    }
    /* hystviz-animate: next to this program in the build tree, in libexec installed */
    hy_file_installed(HY_INSTALLED_LIBEXEC, "hystviz-animate", s->animate, sizeof s->animate);
    /* start-up's long step (hystviz-animate loads GL): a signal ends it, and
       serve, at once (the signals are blocked since main: a signalfd sees them) */
    sigset_t stop;
    sigemptyset(&stop);
    sigaddset(&stop, SIGINT);
    sigaddset(&stop, SIGTERM);
    sigaddset(&stop, SIGHUP);
    int sfd = signalfd(-1, &stop, SFD_CLOEXEC);
    int stopped = list_builtins(s, sfd);
    if (sfd >= 0)
        close(sfd);
    if (stopped) {
        fprintf(stderr, "hystviz serve: stopping (signal during start-up)\n");
        close(s->dirfd);
        free(s);
        return 0;
    }
    /* the per-run token */
    unsigned char rnd[16];
    if (getrandom(rnd, sizeof rnd, 0) != (ssize_t)sizeof rnd) {
        fprintf(stderr, "hystviz serve: no random bytes for the page token: %s\n", strerror(errno));
        close(s->dirfd);
        free(s);
        return 1;
    }
    for (int i = 0; i < 16; i++)
        snprintf(s->token + 2 * i, 3, "%02x", rnd[i]);
    if (make_page(s)) {
        fprintf(stderr, "hystviz serve: out of memory\n");
        close(s->dirfd);
        free(s);
        return 1;
    }
    long ncpu = hy_jobs_default(); /* the CPUs this process may use, as -j of sweep */
    pthread_mutex_init(&s->mu, NULL);
    pthread_cond_init(&s->cond, NULL);
    s->nslots = (int)(ncpu > 0 && ncpu < 64 ? ncpu : ncpu > 0 ? 64 : 1) + 1;
    /* frame workers: one per CPU (at most 4), each a GL context kept warm;
       an animation's frames together within animate's budget, or serve's
       --max-work where that is larger */
    char work[64];
    snprintf(work, sizeof work, "%.17g", max_work > HY_SCENE_WORK_DEFAULT ? max_work : HY_SCENE_WORK_DEFAULT);
    char *extra[3 + 2 * SERVE_INCLUDE_DIRS] = {"--quiet", "--max-work", work};
    int nextra = 3;
    for (size_t k = 0; k < s->pol.ninclude_dirs; k++) { /* the workers load the scenes as serve does */
        extra[nextra++] = "--include-dir";
        extra[nextra++] = (char *)s->incdirs[k];
    }
    if (s->animate[0] && !(s->frames = sv_frames_new(s->animate, s->nslots - 1 < 4 ? s->nslots - 1 : 4, extra, nextra))) {
        fprintf(stderr, "hystviz serve: out of memory\n");
        close(s->dirfd);
        free(s->page);
        free(s);
        return 1;
    }
    /* few arenas: the memory of a heavy request is given back (malloc_trim)
       rather than kept by each connection thread's arena */
    mallopt(M_ARENA_MAX, 2);
    if (pipe(s->stop_pipe)) {
        fprintf(stderr, "hystviz serve: pipe: %s\n", strerror(errno));
        sv_frames_free(s->frames);
        close(s->dirfd);
        free(s->page);
        free(s);
        return 1;
    }
    /* every thread inherits the blocked signals (main blocked them before
       anything else: one sent during start-up is pending); this one waits */
    sigset_t sigs;
    sigemptyset(&sigs);
    sigaddset(&sigs, SIGINT);
    sigaddset(&sigs, SIGTERM);
    sigaddset(&sigs, SIGHUP);
    pthread_sigmask(SIG_BLOCK, &sigs, NULL);
    signal(SIGPIPE, SIG_IGN);
    /* idle sockets are closed after CONN_TIMEOUT_S (a request's headers must
       come, and an answer must be read, at that pace); poll, not select, so
       descriptors past 1024 work */
    unsigned flags = MHD_USE_POLL_INTERNAL_THREAD | MHD_USE_THREAD_PER_CONNECTION | (s->ipv6 ? MHD_USE_IPv6 : 0);
    struct MHD_Daemon *d = MHD_start_daemon(
        flags, (uint16_t)port, NULL, NULL, handle, s, MHD_OPTION_SOCK_ADDR,
        s->ipv6 ? (struct sockaddr *)&sa6 : (struct sockaddr *)&sa4, MHD_OPTION_CONNECTION_LIMIT, (unsigned)CONN_MAX,
        MHD_OPTION_PER_IP_CONNECTION_LIMIT, (unsigned)CONN_PER_IP, MHD_OPTION_CONNECTION_TIMEOUT,
        (unsigned)CONN_TIMEOUT_S, MHD_OPTION_CONNECTION_MEMORY_LIMIT, (size_t)65536, MHD_OPTION_NOTIFY_COMPLETED, done, s, MHD_OPTION_URI_LOG_CALLBACK, uri_seen, s, MHD_OPTION_END);
    pthread_t wt;
    int have_wt = 0;
    if (!d) {
        fprintf(stderr, "hystviz serve: cannot listen on %s port %d (in use? try --port 0)\n", host, port);
        rc = 1;
    } else {
        const union MHD_DaemonInfo *info = MHD_get_daemon_info(d, MHD_DAEMON_INFO_BIND_PORT);
        s->port = info ? (int)info->port : port;
        have_wt = !pthread_create(&wt, NULL, watcher, s);
        if (public_)
            fprintf(stderr, "hystviz serve: warning: listening on %s: anyone who can reach port %d can read the "
                            "scenes in %s and render figures\n",
                    host, s->port, s->dir);
        printf("hystviz serve: http://%s%s%s:%d/ (scenes: %s; Ctrl-C stops)\n", s->ipv6 ? "[" : "", host,
               s->ipv6 ? "]" : "", s->port, s->dir_arg);
        fflush(stdout);
        if (open_browser) {
            char url[128];
            snprintf(url, sizeof url, "http://%s%s%s:%d/", s->ipv6 ? "[" : "", host, s->ipv6 ? "]" : "", s->port);
            char *oargv[] = {"xdg-open", url, NULL};
            pid_t pid;
            /* the browser gets default signal handling, not this process's blocked set */
            posix_spawnattr_t at;
            sigset_t none;
            sigemptyset(&none);
            posix_spawnattr_init(&at);
            posix_spawnattr_setsigmask(&at, &none);
            posix_spawnattr_setflags(&at, POSIX_SPAWN_SETSIGMASK);
            int sp = posix_spawnp(&pid, "xdg-open", NULL, &at, oargv, environ);
            posix_spawnattr_destroy(&at);
            if (sp)
                fprintf(stderr, "hystviz serve: --open: cannot run xdg-open; open the URL above\n");
        }
        int sig;
        for (;;) {
            struct timespec tick = {1, 0};
            sig = sigtimedwait(&sigs, NULL, &tick);
            if (sig > 0)
                break;
            if (errno == EAGAIN)
                idle_trim(s);
        }
        fprintf(stderr, "hystviz serve: stopping (signal %d)\n", sig);
        rc = 0;
    }
    /* stop: wake every waiter, stop the watcher, then the daemon (it joins
       the connection threads, which finish what they are writing) */
    pthread_mutex_lock(&s->mu);
    s->stopping = 1;
    pthread_cond_broadcast(&s->cond);
    pthread_mutex_unlock(&s->mu);
    if (write(s->stop_pipe[1], "x", 1) < 0)
        rc = rc ? rc : 1;
    if (have_wt)
        pthread_join(wt, NULL);
    if (d)
        MHD_stop_daemon(d);
    sv_frames_free(s->frames); /* after the daemon: no request uses a worker now */
    for (int i = 0; i < 2; i++)
        close(s->stop_pipe[i]);
    close(s->dirfd);
    pthread_cond_destroy(&s->cond);
    pthread_mutex_destroy(&s->mu);
    free(s->page);
    free(s);
    return rc;
}

#endif
