/* SPDX-License-Identifier: MIT */
/* hy_scene_write.c: writes the effective scene (merged files, overrides, optional defaults) back as scene text. */
#include "hy_scene_internal.h"
#include "hy_scene.h"

static void write_section(const hy_scene *s, const hy__section *x, int sec, int defaults, FILE *f)
{
    const hy_scene_section_spec *spec = hy_scene_schema(NULL) + sec;
    if (x && x->name)
        fprintf(f, "[%s %s]\n", spec->name, x->name);
    else
        fprintf(f, "[%s]\n", spec->name);
    for (size_t j = 0; j < spec->nkeys; j++) {
        const hy_scene_key_spec *k = &spec->keys[j];
        const hy__slot *slot = x ? &x->slots[j] : NULL;
        if (slot && slot->set) {
            fprintf(f, "%s = ", k->name);
            if (slot->ref)
                fprintf(f, "$%s", s->refs[slot->ref - 1]);
            else
                hy__value_write(k, &slot->v, f);
            if (slot->loc.line)
                fprintf(f, "    # %s:%d\n", slot->loc.file, slot->loc.line);
            else
                fprintf(f, "    # %s\n", slot->loc.file);
        } else if (defaults && k->def) {
            fprintf(f, "%s = ", k->name);
            hy__value_write(k, &s->defaults[s->defoff[sec] + j], f);
            fputs("    # default\n", f);
        }
    }
    fputc('\n', f);
}

int hy_scene_write(const hy_scene *s, FILE *f, int defaults)
{
    size_t nsec;
    const hy_scene_section_spec *spec = hy_scene_schema(&nsec);
    fprintf(f, "# effective scene of %s\n", hy_scene_source(s));
    for (size_t i = 0; i < nsec; i++) {
        int any = 0;
        for (size_t j = 0; j < s->nsecs; j++)
            if (s->secs[j].spec == (int)i) {
                write_section(s, &s->secs[j], (int)i, defaults, f);
                any = 1;
            }
        if (!any && defaults && !spec[i].takes_name)
            write_section(s, NULL, (int)i, defaults, f);
    }
    return ferror(f) ? HY_EIO : HY_OK;
}
