/* SPDX-License-Identifier: MIT */
/* fuzz_dict.c: the fuzzer's dictionary (libFuzzer/AFL++ -dict format), generated from the
 * scene schema so that it names every section, key and enum value there is.
 *
 *     fuzz_dict                 print it
 *     fuzz_dict --check FILE    exit 1 (with a diff hint) unless FILE holds exactly that
 *     fuzz_dict --write FILE    write it (tools/setup.sh fuzz does, into build-fuzz/)
 *
 * tests/fuzz/scene.dict is the committed copy; the `fuzz-dict` test runs --check so it
 * stays equal to the schema. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hy_scene_schema.h"

typedef struct sbuf {
    char *s;
    size_t n, cap;
} sbuf;

static void put(sbuf *b, const char *fmt, const char *a, const char *c)
{
    char line[512];
    int n = snprintf(line, sizeof line, fmt, a, c);
    if (n < 0 || (size_t)n >= sizeof line)
        abort();
    /* one entry once: an entry is a whole line */
    for (const char *p = b->s; p && (p = strstr(p, line)) != NULL; p++)
        if (p == b->s || p[-1] == '\n')
            return;
    if (b->n + (size_t)n + 1 > b->cap) {
        b->cap = 2 * (b->n + (size_t)n + 1);
        b->s = realloc(b->s, b->cap);
        if (!b->s)
            abort();
    }
    memcpy(b->s + b->n, line, (size_t)n + 1);
    b->n += (size_t)n;
}

/* A dictionary value: '"' and '\' escaped, other bytes outside printable
 * ASCII as \xNN (the only escapes libFuzzer and AFL++ read). */
static const char *q(const char *text, char *buf, size_t size)
{
    size_t o = 0;
    for (const unsigned char *p = (const unsigned char *)text; *p && o + 5 < size; p++) {
        if (*p == '"' || *p == '\\') {
            buf[o++] = '\\';
            buf[o++] = (char)*p;
        } else if (*p < 0x20 || *p >= 0x7f)
            o += (size_t)snprintf(buf + o, size - o, "\\x%02x", *p);
        else
            buf[o++] = (char)*p;
    }
    buf[o] = '\0';
    return buf;
}

static char *dictionary(void)
{
    sbuf b = {NULL, 0, 0};
    char e1[256], e2[256];
    put(&b, "# scene dictionary, generated from the schema by tests/fuzz/fuzz_dict.c%s%s\n", "", "");
    put(&b, "# (regenerate: build/tests/fuzz/fuzz_dict --write tests/fuzz/scene.dict)%s%s\n", "", "");
    size_t nsec;
    const hy_scene_section_spec *sec = hy_scene_schema(&nsec);
    for (size_t i = 0; i < nsec; i++) {
        put(&b, sec[i].takes_name ? "sec_%s=\"[%s \"\n" : "sec_%s=\"[%s]\"\n", sec[i].name, sec[i].name);
        for (size_t j = 0; j < sec[i].nkeys; j++) {
            const hy_scene_key_spec *k = &sec[i].keys[j];
            put(&b, "key_%s=\"%s = \"\n", k->name, k->name);
            for (size_t e = 0; k->enums && k->enums[e]; e++) {
                snprintf(e1, sizeof e1, "%s", k->enums[e]);
                for (char *c = e1; *c; c++)
                    if (*c == '-')
                        *c = '_';
                put(&b, "val_%s=\"%s\"\n", e1, q(k->enums[e], e2, sizeof e2));
            }
        }
    }
    /* the syntax around values, the units and colour names the value parser knows,
     * and the files the harness's directory holds (fuzz_harness.c) */
    static const char *const extra[] = {
        "include \"", "\"", "]", "=", ",", "#", "\\\"", "\n", "true", "false", "auto",
        "pt", "cm", "mm", "in", "px", "e-", "e+", "1e308", "4.9e-324", "-0", "nan", "inf",
        "0x", "#0072b2", "black", "vermillion", "vermilion", "orange", "skyblue", "bluishgreen",
        "yellow", "blue", "reddishpurple", "{", "}", "{energy}", "{nminor}", ".area}", "^", "_",
        "\\circ", "style.scene", "part.scene", "self.scene", "sub/inner.scene", "v.txt", "u.txt", "u1.txt",
        "bad.txt", "empty.txt", "../", "/", "\r\n", "\t", "\xef\xbb\xbf", NULL};
    for (size_t i = 0; extra[i]; i++)
        put(&b, "\"%s\"\n", q(extra[i], e2, sizeof e2), "");
    return b.s;
}

int main(int argc, char **argv)
{
    char *d = dictionary();
    if (argc == 1) {
        fputs(d, stdout);
        free(d);
        return 0;
    }
    if (argc != 3 || (strcmp(argv[1], "--check") && strcmp(argv[1], "--write"))) {
        fprintf(stderr, "usage: fuzz_dict [--check FILE | --write FILE]\n");
        return 2;
    }
    int rc = 0;
    if (!strcmp(argv[1], "--write")) {
        FILE *f = fopen(argv[2], "w");
        if (!f || fputs(d, f) == EOF || fclose(f)) {
            fprintf(stderr, "fuzz_dict: cannot write %s\n", argv[2]);
            rc = 1;
        }
    } else {
        FILE *f = fopen(argv[2], "r");
        size_t len = strlen(d);
        char *have = malloc(len + 2);
        size_t got = f && have ? fread(have, 1, len + 1, f) : 0;
        if (f)
            fclose(f);
        if (!f || !have || got != len || memcmp(have, d, len)) {
            fprintf(stderr, "fuzz_dict: %s differs from the schema's dictionary; regenerate it with\n"
                            "  build/tests/fuzz/fuzz_dict --write %s\n", argv[2], argv[2]);
            rc = 1;
        }
        free(have);
    }
    free(d);
    return rc;
}
