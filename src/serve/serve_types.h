/* SPDX-License-Identifier: MIT */
/* serve_types.h: the bottom of src/serve: the server's state and a request's
 * arguments, shared by the endpoints, the route table and the HTTP layer.
 * It includes no other serve header but the frame pool's and the text
 * buffer's; every other serve file includes it, none the other way round.
 * What changes while serving (generation, slots, streams, caches, saves) is
 * guarded by mu; the rest is set before the daemon starts. */
#ifndef SERVE_TYPES_H
#define SERVE_TYPES_H

#include <limits.h>
#include <microhttpd.h>
#include <pthread.h>
#include <stddef.h>
#include <stdint.h>

#include "hy_scene_policy.h"
#include "hy_serve.h"
#include "serve_frames.h"
#include "serve_util.h"

#define MAX_ARGS 64         /* query arguments per request */
#define MAX_PAGES 128       /* pages tracked for render coalescing */
#define SSE_MAX 32          /* event streams in all ... */
#define SSE_PER_ADDR 16     /* ... from one client address (issue 36 item 2: one took all 32) */
#define ADDR_MAX 64         /* client addresses with renders running or waiting */
#define CLIENT_MAX 128      /* clients (page id, else address) with renders running or waiting */
#define ANIM_CACHE 64       /* `hystviz-animate --info` answers kept, by scene hash */

typedef struct sv_page_slot {
    char id[40];
    unsigned long latest;   /* newest sequence number seen */
    int busy;               /* a render for this page is running */
    double used;
} sv_page_slot;

typedef struct sv_sse_page {
    char id[40];
    unsigned char addr[17]; /* the client address (sv_addr_key): streams are counted per page and address */
    int n;
} sv_sse_page;

typedef struct sv_anim_entry {
    uint64_t hash;          /* hy_scene_hash of the scene (its files and includes) */
    long frames;
    double fps;
    int ok;
    char msg[512];
} sv_anim_entry;

typedef struct sv_server {
    char dir[PATH_MAX];     /* the scenes directory, resolved */
    int dirfd;              /* ... opened once: every scene is read beneath it */
    const char *dir_arg;    /* as given (for command lines and messages) */
    char dir_given[PATH_MAX]; /* ... where it is the directory of SCENE.scene */
    char first[256];        /* SCENE.scene given: open it first */
    char token[33];
    char animate[PATH_MAX]; /* hystviz-animate next to this program */
    char host[64];          /* bound address as text */
    int port, ipv6, public_, allow_save;
    double max_work;        /* work budget of one render (HY_SERVE_WORK_DEFAULT, --max-work) */
    hy_scene_policy pol;    /* --include-dir (and max_work): every scene is parsed and loaded under it */
    const char *incdirs[HY_SERVE_INCLUDE_DIRS];
    char *page;             /* index.html with the token */
    size_t page_len;
    pthread_mutex_t mu;
    pthread_cond_t cond;    /* generation changes, stop, page slots freed */
    unsigned long gen;
    char changed[2048];
    int stopping;
    sv_page_slot pages[MAX_PAGES];
    int nslots;             /* renders (and hystviz-animate children) at once */
    int running, running_anon, waiting;
    int waiting_fresh;      /* ... of them not preempted before (they go first) */
    double idle_since;      /* when the last render ended (sv_now) */
    int trim_due;           /* its memory not yet given back (sv_idle_trim) */
    struct {
        unsigned char key[17]; /* family, then the IPv4 address or IPv6 /64 */
        int running, waiting;
    } addr[ADDR_MAX];         /* per client address (sv_slot_take's fairness)  */
    struct {
        char key[48];          /* "p:" and the page id, else "a:" and the address */
        int running, waiting;
    } client[CLIENT_MAX];     /* per client: one render each while another waits */
    struct sv_render_watch *renders; /* the renders running, newest first (preemption) */
    unsigned long npreempted; /* renders stopped for another client's turn ... */
    unsigned long nsuperseded; /* ... or for a newer request of their page */
    double last_preempt_note, last_supersede_note; /* their notes on stderr: once a second */
    size_t mem_held;          /* bytes of rasters reserved by running renders */
    unsigned long ncancelled; /* renders stopped because their client went */
    double last_cancel_note;
    sv_sse_page sse[SSE_MAX];  /* event streams by page */
    int nsse;
    sv_anim_entry anim[ANIM_CACHE];
    size_t anim_next;
    int nsaved;
    double last_save;
    sv_frames *frames;      /* warm hystviz-animate --worker processes (serve_frames.h) */
    char builtin[32][32];   /* hystviz animate --list: the built-in animations */
    char builtin_doc[32][200];
    int nbuiltin;
    int stop_pipe[2];
} sv_server;

/* A request's query arguments (sv_arg_it); the strings are libmicrohttpd's. */
typedef struct sv_args {
    int n, too_many;
    const char *scene, *fmt, *page, *seq, *frame, *name, *hover, *from, *to, *free;
    const char *sets[MAX_ARGS];
    size_t nsets;
    int bad_nul;
} sv_args;

/* A running render as serve_slots.c sees it: its client, its page, whether
 * it is to stop (hy_scene_run.cancelled polls it: sv_render_unwanted). */
typedef struct sv_render_watch {
    struct sv_server *s;
    struct MHD_Connection *c;
    const char *page;       /* its page id, or NULL */
    sv_page_slot *slot;     /* that page's slot (NULL: none or not tracked) */
    unsigned long seq;      /* its sequence number in the page */
    int client;             /* index in s->client while it holds a slot */
    int preempted;          /* under s->mu: stop, another client's turn */
    double started;         /* when it got its slot (sv_now) */
    double held;            /* seconds it held slots before, when queued again */
    int requeued;           /* times it was preempted and queued again */
    double next_look;       /* when sv_render_unwanted looks at the connection again */
    int gone;               /* it saw the client gone */
    size_t mem;             /* bytes of s->mem_held it reserved (sv_mem_take) */
    struct sv_render_watch *next;
} sv_render_watch;

/* Why a request got no render slot (serve_slots.h), or SV_SLOT_OK. */
enum { SV_SLOT_OK, SV_SLOT_GONE, SV_SLOT_FULL, SV_SLOT_STOP };

/* What a route answers with: the request's connection and arguments, and
 * the rest of the path after a prefix route's path ("" for an exact one). */
typedef enum MHD_Result sv_handler(sv_server *s, struct MHD_Connection *c, const sv_args *a, const char *rest);

#endif
