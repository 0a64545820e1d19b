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
    const sv_render_watch *w = ctx;
    int stopping;
    pthread_mutex_lock(&w->s->mu);
    stopping = w->s->stopping;
    pthread_mutex_unlock(&w->s->mu);
    return stopping || sv_client_gone(w->c);
}

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

/* Waits for one of the nslots render slots.  Fairness:
 *  - requests without a page id (an <img>, a script) hold at most half of
 *    the slots, so a page being dragged always finds one;
 *  - per client address (issue 20 item 6: a flood from one client cannot
 *    starve another): at most QUEUE_MAX / 2 of its requests wait, and while
 *    another address waits, one address holds at most nslots - 1 slots, so
 *    the next free slot goes to the other.  Local users all come from
 *    127.0.0.1 and share one entry; serve cannot tell them apart;
 *  - at most QUEUE_MAX wait in all (SV_SLOT_FULL: answer 503).
 * A request whose client has gone (SV_SLOT_GONE) or a stopping server
 * (SV_SLOT_STOP) gives up its turn: nothing is computed for nobody. */
int sv_slot_take(sv_server *s, struct MHD_Connection *c, int anon)
{
    int cap_anon = s->nslots > 1 ? s->nslots / 2 : 1;
    int cap_addr = s->nslots > 1 ? s->nslots - 1 : 1;
    unsigned char key[17];
    addr_key(c, key);
    pthread_mutex_lock(&s->mu);
    int a = addr_find(s, key);
    if (s->waiting >= QUEUE_MAX || a < 0 || s->addr[a].waiting >= QUEUE_MAX / 2) {
        pthread_mutex_unlock(&s->mu);
        return SV_SLOT_FULL;
    }
    s->waiting++;
    s->addr[a].waiting++;
    int rc = SV_SLOT_OK;
    while (!s->stopping && (s->running >= s->nslots || (anon && s->running_anon >= cap_anon) ||
                            (s->addr[a].running >= cap_addr && s->waiting > s->addr[a].waiting))) {
        sv_cond_wait_slice(&s->cond, &s->mu);
        if (c && sv_client_gone(c)) {
            rc = SV_SLOT_GONE;
            break;
        }
    }
    s->waiting--;
    s->addr[a].waiting--;
    if (s->stopping)
        rc = SV_SLOT_STOP;
    if (rc == SV_SLOT_OK && c && sv_client_gone(c))
        rc = SV_SLOT_GONE;
    if (rc == SV_SLOT_OK) {
        s->running++;
        s->running_anon += anon;
        s->addr[a].running++;
    }
    pthread_cond_broadcast(&s->cond); /* the waiting counts changed */
    pthread_mutex_unlock(&s->mu);
    return rc;
}

/* Frees the slot sv_slot_take gave c's request; the last one out gives the
 * freed memory back to the system (glibc keeps the arenas of every
 * connection thread otherwise). */
void sv_slot_give(sv_server *s, struct MHD_Connection *c, int anon)
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
    if (s->running == 0) { /* given back to the kernel after TRIM_IDLE_S idle (sv_idle_trim) */
        s->idle_since = sv_now();
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
