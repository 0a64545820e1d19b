/* SPDX-License-Identifier: MIT */
/* cli_opt.h: a command's options as one table, from which its parser, the
 * options section of its --help, its man page and the bash completion are
 * all made (issue 24: the four cannot drift apart).
 *
 *     enum { OPT_OUT = CLI_FIRST, OPT_VERBOSE };
 *     static const cli_opt opts[] = {
 *         {"output", 'o', "DIR", "output directory", OPT_OUT},
 *         {"verbose", 'v', NULL, "print the plan", OPT_VERBOSE},
 *         {.group = cli_policy_opts},      (another table's options, here)
 *         {0}};
 *     static const cli_cmd cmd = {"render", usage, NULL, "SCENE", opts};
 *     cli_parser p;
 *     cli_parser_init(&p, &cmd, argc, argv, 1);
 *     for (int id; (id = cli_next(&p)) != CLI_END;)
 *         switch (id) {
 *         case OPT_OUT: out = p.val; break;        (the option's value)
 *         case CLI_ARG: scene = p.val; break;      (a positional argument)
 *         case CLI_STOP: return 0;                 (--help or --version printed)
 *         case CLI_ERROR: return 2;                (the message printed)
 *         }
 *
 * Accepted forms: --name VALUE, --name=VALUE, -n VALUE, flags --name and -n,
 * "--" (every later argument is positional) and "-" (positional).  Every
 * option may be repeated; the command decides what a repeat means.  The
 * whole command line is checked before the first option is returned, so an
 * unknown option, a missing value or an unexpected argument stops the
 * command before it acts on anything ("hystviz CMD: unknown option '--x'
 * (see hystviz CMD --help)", exit status 2).  -h/--help and --version are
 * every command's (CLI_STOP); --options-json prints the table for
 * tools/gen_docs.py (not listed in --help: the generator's input). */
#ifndef HY_CLI_OPT_H
#define HY_CLI_OPT_H

#include <stddef.h>
#include <stdio.h>

/* What cli_next returns besides an option's id (ids start at CLI_FIRST). */
enum { CLI_ERROR = -2, CLI_STOP = -1, CLI_END = 0, CLI_ARG = 1, CLI_FIRST = 2 };

/* flags */
enum {
    CLI_SCENE_KEY = 1 /* the value is SECTION.KEY=VALUE (bash completion offers the scene keys) */
};

typedef struct cli_opt {
    const char *lng;  /* long name without "--", or NULL */
    char shrt;        /* short name, or 0 */
    const char *arg;  /* the value's name in help ("DIR"); NULL: a flag */
    const char *help; /* its description; '\n' starts a continuation line */
    int id;           /* what cli_next returns for it (>= CLI_FIRST) */
    unsigned flags;
    /* non-NULL: the rest of the description, known only when printed (a
     * default read from the machine, a list from a table) into buf; doc:
     * for a manual page rather than this machine's --help */
    const char *(*help_more)(char *buf, size_t size, int doc);
    const char *only;               /* non-NULL: only this command of those sharing the table */
    const struct cli_opt *group;    /* non-NULL: that table's options stand here */
} cli_opt;

typedef struct cli_cmd {
    const char *name;   /* in messages; NULL: argv[0] */
    const char *usage;  /* usage lines and prose printed before the options */
    const char *tail;   /* printed after the options, or NULL */
    const char *args;   /* the positional arguments' name ("SCENE"); NULL: none accepted */
    const cli_opt *opts; /* ends with an all-zero entry */
} cli_cmd;

typedef struct cli_parser {
    const cli_cmd *cmd;
    const char *name; /* the command's name in messages */
    int argc;
    char **argv;
    int i;           /* the next argument */
    int dashdash;    /* "--" seen: the rest is positional */
    int checked;     /* the whole line checked */
    const char *val; /* the value of the option, or the positional argument, just returned */
    const cli_opt *opt; /* the option just returned */
    char optname[64];   /* its name: "--output", or "-o" for one without a long name */
} cli_parser;

/* Parses argv[first..] of the command cmd (argv[0] names it when cmd->name
 * is NULL). */
void cli_parser_init(cli_parser *p, const cli_cmd *cmd, int argc, char **argv, int first);

/* The next option's id (value in p->val), CLI_ARG (p->val), CLI_END; or
 * CLI_STOP after printing --help, --version or --options-json to standard
 * output, or CLI_ERROR after printing the one-line message to standard error. */
int cli_next(cli_parser *p);

/* For a positional argument the command does not take (p->val): prints
 * "hystviz CMD: unexpected argument 'X' (see hystviz CMD --help)" and returns
 * CLI_ERROR. */
int cli_unexpected(const cli_parser *p);

/* The command's --help: usage, the options section from the table, tail. */
void cli_help(FILE *f, const cli_cmd *cmd, const char *name);

#endif
