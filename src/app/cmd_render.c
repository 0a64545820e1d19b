/* cmd_render.c: `hystviz render SCENE...` (figures) and `hystviz data SCENE`
 * (every series as CSV), with --set overrides. */
#include "cmd_render.h"

#include <gsl/gsl_errno.h>
#include <stdlib.h>
#include <string.h>

#include "cli_util.h"
#include "scene_run.h"

static const char render_help[] =
    "usage: hystviz render SCENE... [-o DIR] [--set SECTION.KEY=VALUE]... [--format svg,pdf,png] [-v]\n"
    "       hystviz data SCENE [--set SECTION.KEY=VALUE]... [-o FILE]\n"
    "\n"
    "render draws each scene file (docs/SCENES.md) into DIR (default: the scene's\n"
    "[output] dir) as NAME.svg/.pdf/.png; files are written whole or not at all.\n"
    "data prints every series the scene draws as CSV 'series,x,y' (%.17g).\n"
    "\n"
    "  -o DIR / FILE      output directory (render) or CSV file (data)\n"
    "  --set S.K=V        override a scene key, e.g. --set model.sigma0=1\n"
    "                     or --set series.ystar.style=dashed\n"
    "  --format LIST      formats to write instead of the scene's\n"
    "  -v, --verbose      print the plan, each step's time and each series' error\n"
    "                     against the exact answer where one exists\n";

int hy_cmd_render(int argc, char **argv)
{
    int is_data = !strcmp(argv[0], "data");
    const char *out = NULL, *formats = NULL;
    int verbose = 0;
    char **sets = calloc((size_t)argc, sizeof *sets), **scenes = calloc((size_t)argc, sizeof *scenes);
    size_t nsets = 0, nscenes = 0;
    if (!sets || !scenes) {
        fprintf(stderr, "hystviz %s: out of memory\n", argv[0]);
        return 1;
    }
    int rc = 0;
    for (int i = 1; i < argc && !rc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            fputs(render_help, stdout);
            free(sets);
            free(scenes);
            return 0;
        } else if ((!strcmp(a, "-o") || !strcmp(a, "--output")) && v)
            out = argv[++i];
        else if (!strcmp(a, "--set") && v)
            sets[nsets++] = argv[++i];
        else if (!strncmp(a, "--set=", 6))
            sets[nsets++] = argv[i] + 6;
        else if (!strcmp(a, "--format") && v && !is_data)
            formats = argv[++i];
        else if (!strcmp(a, "-v") || !strcmp(a, "--verbose"))
            verbose = 1;
        else if (a[0] == '-') {
            fprintf(stderr, "hystviz %s: unknown or incomplete option '%s' (see hystviz %s --help)\n", argv[0], a, argv[0]);
            rc = 2;
        } else
            scenes[nscenes++] = argv[i];
    }
    if (!rc && (nscenes == 0 || (is_data && nscenes != 1))) {
        fprintf(stderr, "hystviz %s: give %s scene file (see hystviz %s --help)\n", argv[0], is_data ? "one" : "at least one",
                argv[0]);
        rc = 2;
    }
    gsl_set_error_handler_off();
    int failed = 0;
    for (size_t k = 0; k < nscenes && !rc; k++) {
        hy_scene_run run;
        hy_error err;
        if (hy_scene_run_load(&run, scenes[k], sets, nsets, &err) ||
            (hy_scene_run_compute(&run, verbose ? stderr : NULL, &err) && (hy_scene_run_free(&run), 1))) {
            fprintf(stderr, "hystviz: %s\n", err.msg);
            failed = 1;
            continue;
        }
        if (is_data) {
            char tmp[4200];
            FILE *f = cli_out_open(out, tmp, sizeof tmp);
            if (!f || hy_scene_run_data(&run, f, &err) || cli_out_close(f, out, tmp)) {
                if (f && tmp[0]) {
                    fclose(f);
                    remove(tmp);
                }
                failed = 1;
            }
        } else {
            char written[8192] = "";
            if (hy_scene_run_write(&run, out, formats, written, sizeof written, &err)) {
                fprintf(stderr, "hystviz: %s: %s\n", scenes[k], err.msg);
                failed = 1;
            } else if (verbose)
                fprintf(stderr, "%s", written);
        }
        hy_scene_run_free(&run);
    }
    free(sets);
    free(scenes);
    return rc ? rc : failed;
}
