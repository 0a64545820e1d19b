/* SPDX-License-Identifier: MIT */
/* serve_slots.c: render slots, page slots, cancellation and the idle trim
 * (serve_slots.h). */
#include "serve_slots.h"

#include <malloc.h>
#include <netinet/in.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>

#include "serve_request.h"

#define QUEUE_MAX 64        /* renders waiting for a slot; more: 503 + Retry-After */
#define TRIM_IDLE_S 2.0     /* idle seconds before freed memory goes back to the kernel */
#define LOOK_EVERY_S 1e-3   /* a running render looks at its connection at most this often */
#define PREEMPT_AGE_S 0.25  /* a client's only render runs this long before another client's may stop it */

/* Counts a stopped render and says so on stderr, at most once a second (a
 * flood of abandoned requests must not flood the terminal). */
void sv_cancelled_count(sv_server *s)
{
    pthread_mutex_lock(&s->mu);
    unsigned long n = ++s->ncancelled;
    double t = sv_now();
    int note = t - s->last_cancel_note >= 1.0;
    if (note)
        s->last_cancel_note = t;
    pthread_mutex_unlock(&s->mu);
    if (note)
        fprintf(stderr, "hystviz serve: stopped a render whose client had gone (%lu so far)\n", n);
}

int sv_render_unwanted(void *ctx)
{
    sv_render_watch *w = ctx;
    double t = sv_now();
    if (t < w->next_look) /* the core asks every few hundred microseconds */
        return 0;
    w->next_look = t + LOOK_EVERY_S;
    pthread_mutex_lock(&w->s->mu);
    int stop = w->s->stopping || w->preempted || (w->slot && w->slot->latest != w->seq);
    pthread_mutex_unlock(&w->s->mu);
    if (!stop && sv_client_gone(w->c))
        stop = w->gone = 1;
    return stop;
}

/* Says on stderr that a render was stopped for another client's turn, at
 * most once a second (s->mu held: the note is printed under it, rarely). */
static void note_preempted(sv_server *s, const char *then)
{
    double t = sv_now();
    if (t - s->last_preempt_note < 1.0)
        return;
    s->last_preempt_note = t;
    fprintf(stderr, "hystviz serve: stopped a render for another client's turn, %s (%lu so far)\n", then,
            s->npreempted);
}

int sv_render_requeue(sv_render_watch *w)
{
    sv_server *s = w->s;
    pthread_mutex_lock(&s->mu);
    int again = w->preempted && !w->gone && !s->stopping && !(w->slot && w->slot->latest != w->seq);
    if (again) {
        w->preempted = 0, w->next_look = 0, w->requeued++;
        s->npreempted++;
        note_preempted(s, "queued again");
    }
    pthread_mutex_unlock(&s->mu);
    return again;
}

unsigned sv_render_stopped(sv_render_watch *w, const char **msg)
{
    sv_server *s = w->s;
    unsigned st = 0;
    unsigned long n = 0;
    int note = 0;
    pthread_mutex_lock(&s->mu);
    double t = sv_now();
    if (w->gone || s->stopping)
        st = 0;
    else if (w->slot && w->slot->latest != w->seq) {
        st = 409, n = ++s->nsuperseded, *msg = "superseded by a newer request of the same page (stopped)";
        if ((note = t - s->last_supersede_note >= 1.0))
            s->last_supersede_note = t;
    } else if (w->preempted) {
        st = 503, *msg = "stopped for another client's turn: try again in a second";
        s->npreempted++;
        note_preempted(s, "answered 503");
    }
    pthread_mutex_unlock(&s->mu);
    if (note) /* at most once a second, as for clients gone */
        fprintf(stderr, "hystviz serve: stopped a render superseded by a newer request of its page (%lu so far)\n", n);
    return st;
}

/* The client address of c as a key: its family and the IPv4 address, or
 * the /64 prefix of an IPv6 address (one host has a whole /64 to pick from). */
void sv_addr_key(struct MHD_Connection *c, unsigned char key[17])
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
static int addr_find(sv_server *s, const unsigned char key[17])
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

/* The client of a request (s->mu held): its page id, else its address;
 * made if new; -1 if the table is full of clients with work. */
static int client_find(sv_server *s, const char *page, const unsigned char addr[17])
{
    char key[sizeof s->client[0].key];
    if (page)
        snprintf(key, sizeof key, "p:%s", page);
    else {
        memcpy(key, "a:", 2);
        for (int i = 0; i < 17; i++)
            snprintf(key + 2 + 2 * i, 3, "%02x", addr[i]);
    }
    int fresh = -1;
    for (int i = 0; i < CLIENT_MAX; i++) {
        int busy = s->client[i].running || s->client[i].waiting;
        if (busy && !strcmp(s->client[i].key, key))
            return i;
        if (fresh < 0 && !busy)
            fresh = i;
    }
    if (fresh >= 0)
        snprintf(s->client[fresh].key, sizeof s->client[fresh].key, "%s", key);
    return fresh;
}

/* Whether a client other than k waits with no render running (s->mu held). */
static int other_starved(const sv_server *s, int k)
{
    for (int i = 0; i < CLIENT_MAX; i++)
        if (i != k && s->client[i].waiting && !s->client[i].running)
            return 1;
    return 0;
}

/* Client k waits with nothing running and every slot is busy (s->mu held):
 * stops one render so that k gets the next slot.  The victim is a render of
 * the client with the most running, the newest of them when that client
 * runs several (at once), else, among the renders that have run
 * PREEMPT_AGE_S since they got their slot, the one that has held slots
 * longest in all (a render queued again keeps its count: the shortest work
 * goes first, a heavy scene is the victim): one heavy scene cannot hold a
 * slot for seconds while a client with nothing running waits.  The render
 * stops within a millisecond (sv_render_unwanted) and queues again
 * (sv_render_requeue), at most REQUEUE_MAX times (serve_render.c) before it
 * answers 503 with Retry-After; queued again, it waits for a free slot
 * while no request that was never stopped waits (the slot it gave up goes
 * to the client that stopped it) and stops no other render (heavy renders
 * would take turns stopping each other). */
static void preempt_one(sv_server *s, int k)
{
    sv_render_watch *victim = NULL;
    int most = 0;
    double now = sv_now();
    for (sv_render_watch *w = s->renders; w; w = w->next)
        if (w->preempted) /* one is stopping: its slot comes next */
            return;
    for (sv_render_watch *w = s->renders; w; w = w->next) {
        int n = w->client >= 0 ? s->client[w->client].running : 0;
        if (w->client == k)
            continue;
        if (n > most && n > 1) /* newest first in the list: the newest of the busiest client */
            victim = w, most = n;
        else if (most <= 1 && now - w->started >= PREEMPT_AGE_S &&
                 (!victim || w->held - w->started > victim->held - victim->started))
            victim = w, most = 1;
    }
    if (victim)
        victim->preempted = 1;
}

/* Waits for one of the nslots render slots.  Fairness:
 *  - per client (a page id, else the client address; issue 36 item 2): a
 *    client holds a second slot only while no other client waits with none,
 *    and a client with none that finds every slot busy stops a render of
 *    another (preempt_one), so one heavy scene holds no one for seconds;
 *  - requests without a page id (an <img>, a script) hold at most half of
 *    the slots, so a page being dragged always finds one;
 *  - per client address (issue 20 item 6): at most QUEUE_MAX / 2 of its
 *    requests wait, and while another address waits, one address holds at
 *    most nslots - 1 slots.  Local users all come from 127.0.0.1 and share
 *    one address: their page ids tell them apart;
 *  - at most QUEUE_MAX wait in all (SV_SLOT_FULL: answer 503).
 * A request whose client has gone (SV_SLOT_GONE) or a stopping server
 * (SV_SLOT_STOP) gives up its turn: nothing is computed for nobody.  w (may
 * be NULL: not preemptable) joins s->renders. */
static int slot_take(sv_server *s, struct MHD_Connection *c, int anon, const char *page, sv_render_watch *w)
{
    int cap_anon = s->nslots > 1 ? s->nslots / 2 : 1;
    int cap_addr = s->nslots > 1 ? s->nslots - 1 : 1;
    unsigned char key[17];
    sv_addr_key(c, key);
    pthread_mutex_lock(&s->mu);
    int a = addr_find(s, key), k = client_find(s, page, key);
    if (s->waiting >= QUEUE_MAX || a < 0 || k < 0 || s->addr[a].waiting >= QUEUE_MAX / 2) {
        pthread_mutex_unlock(&s->mu);
        return SV_SLOT_FULL;
    }
    int fresh = !(w && w->requeued); /* a render queued again lets the others go first */
    s->waiting++;
    s->waiting_fresh += fresh;
    s->addr[a].waiting++;
    s->client[k].waiting++;
    int rc = SV_SLOT_OK;
    while (!s->stopping && (s->running >= s->nslots || (anon && s->running_anon >= cap_anon) ||
                            (s->addr[a].running >= cap_addr && s->waiting > s->addr[a].waiting) ||
                            (s->client[k].running && other_starved(s, k)) || (!fresh && s->waiting_fresh))) {
        if (s->running >= s->nslots && !s->client[k].running && !(w && w->requeued))
            preempt_one(s, k); /* a render queued again waits for a free slot: no churn */
        sv_cond_wait_slice(&s->cond, &s->mu);
        if (c && sv_client_gone(c)) {
            rc = SV_SLOT_GONE;
            break;
        }
    }
    s->waiting--;
    s->waiting_fresh -= fresh;
    s->addr[a].waiting--;
    s->client[k].waiting--;
    if (s->stopping)
        rc = SV_SLOT_STOP;
    if (rc == SV_SLOT_OK && c && sv_client_gone(c))
        rc = SV_SLOT_GONE;
    if (rc == SV_SLOT_OK) {
        s->running++;
        s->running_anon += anon;
        s->addr[a].running++;
        s->client[k].running++;
        if (w) {
            w->client = k;
            w->started = sv_now();
            w->next = s->renders;
            s->renders = w;
        }
    }
    pthread_cond_broadcast(&s->cond); /* the waiting counts changed */
    pthread_mutex_unlock(&s->mu);
    return rc;
}

/* Frees the slot slot_take gave c's request; the last one out gives the
 * freed memory back to the system (glibc keeps the arenas of every
 * connection thread otherwise). */
static void slot_give(sv_server *s, struct MHD_Connection *c, int anon, const char *page, sv_render_watch *w)
{
    unsigned char key[17];
    sv_addr_key(c, key);
    pthread_mutex_lock(&s->mu);
    s->running--;
    s->running_anon -= anon;
    for (int i = 0; i < ADDR_MAX; i++)
        if (s->addr[i].running && !memcmp(s->addr[i].key, key, 17)) {
            s->addr[i].running--;
            break;
        }
    int k = w ? w->client : client_find(s, page, key);
    if (k >= 0 && s->client[k].running)
        s->client[k].running--;
    if (w) {
        for (sv_render_watch **pp = &s->renders; *pp; pp = &(*pp)->next)
            if (*pp == w) {
                *pp = w->next;
                break;
            }
        s->mem_held -= w->mem;
        w->mem = 0;
        w->client = -1;
        w->held += sv_now() - w->started;
    }
    if (s->running == 0) { /* given back to the kernel after TRIM_IDLE_S idle (sv_idle_trim) */
        s->idle_since = sv_now();
        s->trim_due = 1;
    }
    pthread_cond_broadcast(&s->cond);
    pthread_mutex_unlock(&s->mu);
}

int sv_slot_take(sv_server *s, struct MHD_Connection *c, int anon)
{
    return slot_take(s, c, anon, NULL, NULL);
}

void sv_slot_give(sv_server *s, struct MHD_Connection *c, int anon)
{
    slot_give(s, c, anon, NULL, NULL);
}

int sv_render_enter(sv_render_watch *w, int anon)
{
    w->client = -1;
    return slot_take(w->s, w->c, anon, w->page, w);
}

void sv_render_leave(sv_render_watch *w, int anon)
{
    slot_give(w->s, w->c, anon, w->page, w);
}

int sv_mem_take(sv_render_watch *w, size_t bytes)
{
    sv_server *s = w->s;
    int rc = SV_SLOT_OK;
    pthread_mutex_lock(&s->mu);
    while (!s->stopping && s->mem_held && s->mem_held + bytes > SV_MEM_TOTAL) {
        sv_cond_wait_slice(&s->cond, &s->mu);
        if (sv_client_gone(w->c)) {
            rc = SV_SLOT_GONE;
            break;
        }
    }
    if (s->stopping)
        rc = SV_SLOT_STOP;
    if (rc == SV_SLOT_OK)
        s->mem_held += bytes, w->mem += bytes;
    pthread_mutex_unlock(&s->mu);
    return rc;
}

/* The memory of the last renders goes back to the kernel (malloc_trim) once
 * serve has rendered nothing for TRIM_IDLE_S, not when each render ends: the
 * next render of a drag reuses those pages instead of faulting fresh ones
 * in (bw_fig1a: 2900 page faults a render; hystviz-serve's mallopt keeps
 * big arrays on the heap).  Called by the main thread every second. */
void sv_idle_trim(sv_server *s)
{
    pthread_mutex_lock(&s->mu);
    int due = s->trim_due && s->running == 0 && sv_now() - s->idle_since >= TRIM_IDLE_S;
    if (due)
        s->trim_due = 0;
    pthread_mutex_unlock(&s->mu);
    if (due)
        malloc_trim(0);
}

/* Latest wins: a request for page P with sequence number q waits while a
 * render for P runs; if a newer request for P arrived meanwhile it gives up
 * (409) and the newer one goes next.  Returns the slot, or NULL if superseded. */
sv_page_slot *sv_page_enter(sv_server *s, const char *id, unsigned long seq)
{
    pthread_mutex_lock(&s->mu);
    sv_page_slot *p = NULL, *old = NULL;
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
        return (sv_page_slot *)s;
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
    p->used = sv_now();
    pthread_mutex_unlock(&s->mu);
    return p;
}

void sv_page_leave(sv_server *s, sv_page_slot *p)
{
    if ((void *)p == (void *)s)
        return;
    pthread_mutex_lock(&s->mu);
    p->busy = 0;
    pthread_cond_broadcast(&s->cond);
    pthread_mutex_unlock(&s->mu);
}

unsigned sv_page_join(sv_server *s, const sv_args *a, sv_page_slot **slot, const char **msg)
{
    *slot = NULL;
    if (!a->page)
        return 0;
    char *end;
    unsigned long seq = a->seq ? strtoul(a->seq, &end, 10) : 0;
    if (strlen(a->page) >= sizeof s->pages[0].id || !*a->page)
        return *msg = "page: at most 39 characters", 400;
    *slot = sv_page_enter(s, a->page, seq);
    if (!*slot)
        return *msg = "superseded by a newer request of the same page", 409;
    return 0;
}

unsigned sv_page_watch(sv_server *s, const sv_args *a, sv_render_watch *w, sv_page_slot **slot, const char **msg)
{
    unsigned bad = sv_page_join(s, a, slot, msg);
    if (!bad && *slot && (void *)*slot != (void *)s) { /* a newer request of the page stops this one */
        w->slot = *slot;
        w->seq = a->seq ? strtoul(a->seq, NULL, 10) : 0;
    }
    return bad;
}
