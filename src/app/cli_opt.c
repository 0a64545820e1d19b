/* SPDX-License-Identifier: MIT */
/* cli_opt.c: the table-driven option parser and --help printer of the
 * hystviz commands (cli_opt.h). */
#include "cli_opt.h"

#include <string.h>

#include "hy_config.h"

/* " NAME", or nothing for the program itself (name ""): two %s. */
#define SP(name) (name)[0] ? " " : "", (name)

/* Every command's: ids handled here, never returned. */
enum { ID_HELP = -10, ID_VERSION = -11, ID_JSON = -12 };
static const cli_opt builtin[] = {
    {"help", 'h', NULL, "this text", ID_HELP, 0, NULL, NULL, NULL},
    {"version", 'V', NULL, "the program version", ID_VERSION, 0, NULL, NULL, NULL},
    {0},
};
static const cli_opt json_opt = {"options-json", 0, NULL, NULL, ID_JSON, 0, NULL, NULL, NULL};

/* Calls fn on each option of table t that command name accepts (groups
 * expanded, in order); stops at and returns the first nonzero result. */
static const cli_opt *each(const cli_opt *t, const char *name, int (*fn)(const cli_opt *, void *), void *ctx)
{
    for (; t->id || t->group; t++) {
        if (t->group) {
            const cli_opt *o = each(t->group, name, fn, ctx);
            if (o)
                return o;
        } else if ((!t->only || !strcmp(t->only, name)) && fn(t, ctx))
            return t;
    }
    return NULL;
}

/* Calls fn on the command's options, then on -h/--help and --version. */
static const cli_opt *each_all(const cli_cmd *c, const char *name, int (*fn)(const cli_opt *, void *), void *ctx)
{
    const cli_opt *o = each(c->opts, name, fn, ctx);
    return o ? o : each(builtin, name, fn, ctx);
}

typedef struct key {
    const char *s;
    size_t n; /* long name: its length; short: 0 */
} key;

static int match(const cli_opt *o, void *ctx)
{
    const key *k = ctx;
    return k->n ? o->lng && strlen(o->lng) == k->n && !strncmp(o->lng, k->s, k->n) : o->shrt == k->s[0];
}

/* The option argv[*i] names, its value in *val (argv[*i] advanced past what
 * it takes); NULL for a positional argument; &json_opt for --options-json;
 * *bad set (message printed) for an unknown option or a missing or unwanted
 * value. */
static const cli_opt *classify(cli_parser *p, int *i, const char **val, int *bad)
{
    const char *a = p->argv[*i];
    *val = a;
    *bad = 0;
    (*i)++;
    if (p->dashdash || a[0] != '-' || !a[1])
        return NULL;
    key k = {a + 1, 0};
    const char *eq = NULL;
    if (a[1] == '-') {
        k.s = a + 2;
        eq = strchr(k.s, '=');
        k.n = eq ? (size_t)(eq - k.s) : strlen(k.s);
        if (!eq && !strcmp(k.s, "options-json"))
            return &json_opt;
    }
    const cli_opt *o = (k.n || !a[2]) ? each_all(p->cmd, p->name, match, &k) : NULL;
    if (!o || (a[1] == '-' && !k.n)) {
        fprintf(stderr, "hystviz%s%s: unknown option '%s' (see hystviz%s%s --help)\n", SP(p->name), a, SP(p->name));
        *bad = 1;
        return NULL;
    }
    if (k.n)
        snprintf(p->optname, sizeof p->optname, "--%s", o->lng);
    else
        snprintf(p->optname, sizeof p->optname, "-%c", o->shrt);
    *val = NULL;
    if (eq && !o->arg) {
        fprintf(stderr, "hystviz%s%s: option %s takes no value (see hystviz%s%s --help)\n", SP(p->name), p->optname,
                SP(p->name));
        *bad = 1;
    } else if (eq)
        *val = eq + 1;
    else if (o->arg && *i < p->argc)
        *val = p->argv[(*i)++];
    else if (o->arg) {
        fprintf(stderr, "hystviz%s%s: option %s needs a value (%s) (see hystviz%s%s --help)\n", SP(p->name), p->optname,
                o->arg, SP(p->name));
        *bad = 1;
    }
    return o;
}

void cli_parser_init(cli_parser *p, const cli_cmd *cmd, int argc, char **argv, int first)
{
    memset(p, 0, sizeof *p);
    p->cmd = cmd;
    p->name = cmd->name ? cmd->name : argv[0];
    p->argc = argc;
    p->argv = argv;
    p->i = first;
}

static void print_json(FILE *f, const cli_cmd *c, const char *name);

/* Checks the whole command line from p->i; CLI_END when it is good, else
 * CLI_STOP (help, version or the table printed) or CLI_ERROR (message printed). */
static int check_all(cli_parser *p)
{
    for (int i = p->i; i < p->argc;) {
        const char *val;
        int bad;
        if (!p->dashdash && !strcmp(p->argv[i], "--")) {
            p->dashdash = 1;
            i++;
            continue;
        }
        const cli_opt *o = classify(p, &i, &val, &bad);
        if (bad)
            return CLI_ERROR;
        if (!o && !p->cmd->args) {
            p->val = val;
            return cli_unexpected(p);
        }
        if (o && o->id == ID_HELP)
            cli_help(stdout, p->cmd, p->name);
        else if (o && o->id == ID_VERSION)
            printf("hystviz %s\n", HY_VERSION);
        else if (o == &json_opt)
            print_json(stdout, p->cmd, p->name);
        else
            continue;
        return CLI_STOP;
    }
    return CLI_END;
}

int cli_next(cli_parser *p)
{
    if (!p->checked) {
        p->checked = 1;
        int rc = check_all(p);
        p->dashdash = 0; /* the options are now returned from p->i again */
        if (rc != CLI_END)
            return rc;
    }
    while (p->i < p->argc) {
        if (!p->dashdash && !strcmp(p->argv[p->i], "--")) {
            p->dashdash = 1;
            p->i++;
            continue;
        }
        int bad;
        p->opt = classify(p, &p->i, &p->val, &bad);
        return p->opt ? p->opt->id : CLI_ARG; /* checked: no error, no built-in option */
    }
    return CLI_END;
}

int cli_unexpected(const cli_parser *p)
{
    fprintf(stderr, "hystviz%s%s: unexpected argument '%s' (see hystviz%s%s --help)\n", SP(p->name), p->val,
            SP(p->name));
    return CLI_ERROR;
}

/* ---- help ---- */

enum { COL = 22 }; /* where descriptions start */

/* "-o, --output DIR" into buf. */
static void synopsis(const cli_opt *o, char *buf, size_t size)
{
    int n = 0;
    if (o->shrt && o->lng)
        n = snprintf(buf, size, "-%c, --%s", o->shrt, o->lng);
    else if (o->shrt)
        n = snprintf(buf, size, "-%c", o->shrt);
    else
        n = snprintf(buf, size, "--%s", o->lng);
    if (o->arg && n > 0 && (size_t)n < size)
        snprintf(buf + n, size - (size_t)n, " %s", o->arg);
}

/* The whole description (help and help_more) into buf. */
static const char *describe(const cli_opt *o, char *buf, size_t size, int doc)
{
    char more[2048] = "";
    const char *m = o->help_more ? o->help_more(more, sizeof more, doc) : "";
    snprintf(buf, size, "%s%s", o->help ? o->help : "", m);
    return buf;
}

typedef struct help_ctx {
    FILE *f;
    int doc;
} help_ctx;

static int print_opt(const cli_opt *o, void *ctx)
{
    FILE *f = ((help_ctx *)ctx)->f;
    char syn[128], desc[4096];
    synopsis(o, syn, sizeof syn);
    describe(o, desc, sizeof desc, 0);
    int n = fprintf(f, "  %s", syn);
    const char *s = desc;
    for (int first = 1;; first = 0) {
        size_t len = strcspn(s, "\n");
        if (first && n >= COL - 1)
            fprintf(f, "\n%*s", COL, "");
        else if (first)
            fprintf(f, "%*s", COL - n, "");
        else
            fprintf(f, "%*s", COL, "");
        fprintf(f, "%.*s\n", (int)len, s);
        if (!s[len])
            return 0;
        s += len + 1;
    }
}

void cli_help(FILE *f, const cli_cmd *cmd, const char *name)
{
    help_ctx h = {f, 0};
    fputs(cmd->usage, f);
    fputs("options:\n", f);
    each_all(cmd, name, print_opt, &h);
    if (cmd->tail) {
        fputc('\n', f);
        fputs(cmd->tail, f);
    }
}

/* ---- the table as JSON (tools/gen_docs.py) ---- */

static void json_str(FILE *f, const char *s)
{
    fputc('"', f);
    for (; s && *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\')
            fprintf(f, "\\%c", c);
        else if (c == '\n')
            fputs("\\n", f);
        else if (c < 0x20)
            fprintf(f, "\\u%04x", c);
        else
            fputc(c, f);
    }
    fputc('"', f);
}

static int json_opt_line(const cli_opt *o, void *ctx)
{
    help_ctx *h = ctx;
    char buf[8], desc[4096];
    fputs(h->doc++ ? ",\n  {\"long\": " : "\n  {\"long\": ", h->f);
    if (o->lng) {
        fputs("\"--", h->f);
        fputs(o->lng, h->f);
        fputc('"', h->f);
    } else
        fputs("null", h->f);
    snprintf(buf, sizeof buf, "-%c", o->shrt);
    fputs(", \"short\": ", h->f);
    if (o->shrt)
        json_str(h->f, buf);
    else
        fputs("null", h->f);
    fputs(", \"arg\": ", h->f);
    if (o->arg)
        json_str(h->f, o->arg);
    else
        fputs("null", h->f);
    fputs(", \"help\": ", h->f);
    json_str(h->f, describe(o, desc, sizeof desc, 1));
    fprintf(h->f, ", \"scene_key\": %s}", o->flags & CLI_SCENE_KEY ? "true" : "false");
    return 0;
}

static void print_json(FILE *f, const cli_cmd *c, const char *name)
{
    help_ctx h = {f, 0}; /* doc counts the options written */
    fputs("{\"command\": ", f);
    json_str(f, name);
    fputs(", \"usage\": ", f);
    json_str(f, c->usage);
    fputs(", \"tail\": ", f);
    json_str(f, c->tail);
    fputs(", \"args\": ", f);
    if (c->args)
        json_str(f, c->args);
    else
        fputs("null", f);
    fputs(", \"options\": [", f);
    each_all(c, name, json_opt_line, &h);
    fputs("]}\n", f);
}
