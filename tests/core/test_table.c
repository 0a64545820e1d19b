/* SPDX-License-Identifier: MIT */
/* test_table.c: the measured-data reader (hy_table.h) on crafted good and bad
 * texts, each refusal with its exact file:line:col, and the shoelace area of
 * measured loops against areas computed by hand. */
#include <stdlib.h>

#include "hy_table.h"
#include "tutil.h"

static const hy_table_spec UY = {{"u", "y", NULL, NULL}, {1, 1, 1}};

/* Parses text with spec; expects a refusal whose message starts with want. */
static void refused(const char *text, const hy_table_spec *sp, const char *want)
{
    hy_table t;
    hy_error err = {0};
    int rc = hy_table_parse(text, strlen(text), "d.csv", sp, 0, &t, &err);
    CHECK(rc == HY_EINVAL && !strncmp(err.msg, want, strlen(want)), "'%s': want '%s...', got %d '%s'", text, want, rc,
          err.msg);
    CHECK(t.n == 0 && t.u == NULL && t.rec == NULL, "a refusal leaves nothing: n %zu", t.n);
}

static void bad_inputs(void)
{
    refused("u,y\n1,2\n3,x\n", &UY, "d.csv:3:3: column 2 is not a number");
    refused("u,y\n1,2\n3,nan\n", &UY, "d.csv:3:3: column 2 is not a finite number");
    refused("u,y\n1,2\n-inf,1\n", &UY, "d.csv:3:1: column 1 is not a finite number");
    refused("u,y\n1,2\n1e999,1\n", &UY, "d.csv:3:1: column 1 is not a finite number");
    refused("u,y\n1,2\n0x10,1\n", &UY, "d.csv:3:1: column 1 is not a number"); /* hex is not decimal */
    refused("u,y\n1,2\n3\n", &UY, "d.csv:3:2: the row has 1 column, the rows before it 2");
    refused("u y\n1 2\n3 4 5\n", &UY, "d.csv:3:5: the row has 3 columns, the rows before it 2");
    refused("u,y\n1,2\n3,\n", &UY, "d.csv:3:3: column 2 is not a number"); /* an empty field */
    hy_table_spec h = {{"H", "B", NULL, NULL}, {1, 1, 1}};
    refused("u,y\n1,2\n", &h, "d.csv:1:1: no column named 'H' (u) in the header of 2 columns");
    refused("1,2\n3,4\n", &h, "d.csv:1:1: no header line names the columns");
    hy_table_spec i5 = {{"5", "2", NULL, NULL}, {1, 1, 1}};
    refused("# c\n1,2\n3,4\n", &i5, "d.csv:2:1: column 5 (u) does not exist: the rows have 2 columns");
    refused("", &UY, "d.csv:1:1: no data rows");
    refused("# only a comment\nu,y\n\n", &UY, "d.csv:3:1: no data rows");
    /* a NUL inside the text (not cut) */
    {
        static const char nul[] = "u,y\n1,2\n3,4\0\n";
        hy_table t;
        hy_error err = {0};
        int rc = hy_table_parse(nul, sizeof nul - 1, "d.csv", &UY, 0, &t, &err);
        CHECK(rc == HY_EINVAL && !strncmp(err.msg, "d.csv:3:4: NUL byte", 19), "NUL: %s", err.msg);
    }
    /* a line past the cap */
    {
        size_t n = HY_TABLE_MAX_LINE + 20;
        char *s = malloc(n + 16);
        memcpy(s, "u,y\n1,", 6);
        memset(s + 6, '1', n);
        strcpy(s + 6 + n, "\n");
        refused(s, &UY, "d.csv:2:4096: the line is longer than 4095 bytes");
        free(s);
    }
    /* more rows than the cap (one past it) */
    {
        size_t rows = HY_TABLE_MAX_ROWS + 1, n = 4 + 4 * rows;
        char *s = malloc(n + 1), *p = s;
        memcpy(p, "u,y\n", 4);
        p += 4;
        for (size_t i = 0; i < rows; i++, p += 4)
            memcpy(p, "1,2\n", 4);
        *p = '\0';
        char want[80];
        snprintf(want, sizeof want, "d.csv:%zu:1: more than %zu data rows", rows + 1, (size_t)HY_TABLE_MAX_ROWS);
        refused(s, &UY, want);
        free(s);
    }
    /* more bytes than the cap: refused before any line is read */
    {
        hy_table t;
        hy_error err = {0};
        int rc = hy_table_parse("u,y\n", HY_TABLE_MAX_BYTES + 1, "d.csv", &UY, 0, &t, &err);
        CHECK(rc == HY_EINVAL && strstr(err.msg, "d.csv:1:1: the file is"), "bytes cap: %s", err.msg);
    }
    /* a scene's file is never quoted; the user's may list its header */
    {
        hy_table t;
        hy_error err = {0};
        const char *s = "secret,y\n1,2\n";
        hy_table_parse(s, strlen(s), "d.csv", &h, 0, &t, &err);
        CHECK(!strstr(err.msg, "secret"), "quoted a scene's file: %s", err.msg);
        hy_table_parse(s, strlen(s), "d.csv", &h, 1, &t, &err);
        CHECK(strstr(err.msg, "it names 'secret', 'y'") != NULL, "the user's header not listed: %s", err.msg);
    }
}

static void good_inputs(void)
{
    /* the ferrite file's layout: header as a comment, a split column, scales */
    const char *s = "# loop,H,B\n1,1,10\n1,2,20\n\n2,3,30\r\n2,4,40\n# a comment\n2,5,50\n3,6,60\n";
    hy_table_spec sp = {{"H", "3", NULL, "loop"}, {2, 1e-3, 1}};
    hy_table t;
    hy_error err = {0};
    int rc = hy_table_parse(s, strlen(s), "f.csv", &sp, 0, &t, &err);
    CHECK(rc == 0, "ferrite layout: %s", err.msg);
    if (rc)
        return;
    CHECK(t.n == 6 && t.nrec == 3, "rows %zu records %zu", t.n, t.nrec);
    CHECK(t.rec[0] == 0 && t.rec[1] == 2 && t.rec[2] == 5 && t.rec[3] == 6, "record offsets");
    CHECK(t.line[0] == 2 && t.line[1] == 5 && t.line[2] == 9, "record lines %zu %zu %zu", t.line[0], t.line[1], t.line[2]);
    CHECK(t.u[4] == 10 && t.y[4] == 0.05 && t.t == NULL, "values u %g y %g", t.u[4], t.y[4]);
    hy_table_free(&t);
    /* whitespace-separated, header row, t by index */
    s = "t u y\n0 1 2\n0.5\t3   4\n";
    hy_table_spec w = {{"u", "y", "1", NULL}, {1, 1, 1}};
    rc = hy_table_parse(s, strlen(s), "w.txt", &w, 0, &t, &err);
    CHECK(rc == 0 && t.n == 2 && t.nrec == 1 && t.t && t.t[1] == 0.5 && t.u[1] == 3 && t.y[1] == 4, "whitespace: %s",
          err.msg);
    hy_table_free(&t);
}

/* Areas computed by hand: a unit square and a triangle, both orientations. */
static void areas(void)
{
    /* the square (0,0) (1,0) (1,1) (0,1): counter-clockwise, area +1 */
    double su[] = {0, 1, 1, 0}, sy[] = {0, 0, 1, 1};
    CHECK(hy_table_area(su, sy, 4) == 1.0, "square: %g", hy_table_area(su, sy, 4));
    /* clockwise (reversed): -1 */
    double ru[] = {0, 0, 1, 1}, ry[] = {0, 1, 1, 0};
    CHECK(hy_table_area(ru, ry, 4) == -1.0, "square clockwise: %g", hy_table_area(ru, ry, 4));
    /* triangle (1,1) (4,1) (1,5): legs 3 and 4, area 3 x 4 / 2 = 6, counter-clockwise */
    double tu[] = {1, 4, 1}, ty[] = {1, 1, 5};
    CHECK(hy_table_area(tu, ty, 3) == 6.0, "triangle: %g", hy_table_area(tu, ty, 3));
    /* a B(H)-like loop as the ferrite file writes it: from the positive tip down
       the upper branch, back up the lower one.  Parallelogram tips (+-2, +-1),
       branches y = (u +- 1)/2... : vertices (2,1) (0,1) (-2,-1) (0,-1), base 2 x
       height 2 = 4, counter-clockwise */
    double pu[] = {2, 0, -2, 0}, py[] = {1, 1, -1, -1};
    CHECK(hy_table_area(pu, py, 4) == 4.0, "B(H) parallelogram: %g", hy_table_area(pu, py, 4));
    /* far from the origin: relative coordinates keep it exact */
    double fu[] = {1e8, 1e8 + 1, 1e8 + 1, 1e8}, fy[] = {1e8, 1e8, 1e8 + 1, 1e8 + 1};
    CHECK(hy_table_area(fu, fy, 4) == 1.0, "square at 1e8: %.17g", hy_table_area(fu, fy, 4));
    CHECK(hy_table_area(su, sy, 2) == 0.0, "two points: no area");
}

int main(void)
{
    bad_inputs();
    good_inputs();
    areas();
    return tu_finish("table");
}
