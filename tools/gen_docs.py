#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""gen_docs.py: man pages and bash completion generated at build time from
the one place each fact lives (issue 24: they cannot drift):
  - each command's options: its option table (src/app/cli_opt.h), which
    `hystviz CMD --options-json` prints and from which the program's parser
    and its --help options section are made;
  - the commands: `hystviz --help`'s command list;
  - the scene keys for --set and --grid: the schema table (hy_schema_json,
    printed by the build's hy_schema_json program).

  gen_docs.py man HYSTVIZ CMD OUT.1          hystviz(1) (CMD "-") or hystviz-CMD(1)
  gen_docs.py scene5 SCENES_MD OUT.5         hystviz-scene(5) from docs/SCENES.md
  gen_docs.py lib3 HEADER OUT.3              libhystviz(3) from src/lib/hystviz.h
  gen_docs.py completion HYSTVIZ SCHEMA_JSON OUT   bash completion
  gen_docs.py options HYSTVIZ CMD            print the options of CMD's table, sorted
  gen_docs.py commands MAIN_C                the commands of the usage text in
                                             src/app/main.c (what --help prints;
                                             read at configure time, before any
                                             program is built)
"""
import json
import os
import re
import subprocess
import sys

def help_text(hv, cmd):
    args = [hv, "--help"] if cmd == "-" else [hv, cmd, "--help"]
    r = subprocess.run(args, capture_output=True, text=True, timeout=60,
                       env=dict(os.environ, LC_ALL="C.UTF-8"))
    return r.stdout


def commands(hv):
    """(name, one-line description) from `hystviz --help`'s command list."""
    out, on = [], False
    for line in help_text(hv, "-").splitlines():
        if line.strip() == "commands:":
            on = True
            continue
        if on:
            m = re.match(r"^  ([a-z]+)\s+(.*)$", line)
            if not m:
                break
            out.append((m.group(1), m.group(2)))
    return out


def table(hv, cmd):
    """The option table of CMD ("-": the program's own) as --options-json prints it."""
    args = [hv, "--options-json"] if cmd == "-" else [hv, cmd, "--options-json"]
    r = subprocess.run(args, capture_output=True, text=True, timeout=60, env=dict(os.environ, LC_ALL="C.UTF-8"))
    if r.returncode:
        sys.exit(f"gen_docs: {' '.join(args)} failed: {r.stderr.strip()}")
    return json.loads(r.stdout)


def names(opt):
    return [n for n in (opt["short"], opt["long"]) if n]


def options(hv, cmd):
    return sorted(n for o in table(hv, cmd)["options"] for n in names(o))


def roff_escape(line):
    line = line.replace("\\", "\\e")
    # non-ASCII as groff's \[uXXXX] (man pages are read as Latin-1 otherwise)
    line = "".join(c if ord(c) < 128 else (f"\\[u{ord(c):04X}]" if ord(c) < 0x10000 else f"\\[u{ord(c):X}]")
                   for c in line)
    if line.startswith((".", "'")):
        line = "\\&" + line
    return line


def write(path, text):
    tmp = path + ".tmp"
    with open(tmp, "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(tmp, path)


def man(hv, cmd, out):
    t = table(hv, cmd)
    desc = dict(commands(hv))
    name = "hystviz" if cmd == "-" else f"hystviz-{cmd}"
    what = "hysteresis models and their figures from scene files" if cmd == "-" else desc.get(cmd, cmd)
    lines = t["usage"].rstrip("\n").split("\n")
    n = 1  # the usage lines: "usage: ..." and the indented lines under it
    while n < len(lines) and lines[n].startswith(" "):
        n += 1
    body = [f'.TH {name.upper()} 1 "" "hystviz" "hystviz manual"', ".SH NAME", f"{name} \\- {roff_escape(what)}",
            ".SH SYNOPSIS", ".nf"]
    body += [roff_escape(u.replace("usage: ", "", 1).strip()) for u in lines[:n]]
    body += [".fi", ".SH DESCRIPTION", ".nf"] + [roff_escape(l) for l in lines[n:]] + [".fi", ".SH OPTIONS"]
    for o in t["options"]:
        tag = ", ".join("\\fB" + roff_escape(x) + "\\fR" for x in names(o))
        if o["arg"]:
            tag += " \\fI" + roff_escape(o["arg"]) + "\\fR"
        body += [".TP", tag, ".nf"] + [roff_escape(l) for l in o["help"].split("\n")] + [".fi"]
    if t["tail"]:
        body += [".SH NOTES", ".nf"] + [roff_escape(l) for l in t["tail"].rstrip("\n").split("\n")] + [".fi"]
    if cmd == "-":
        body += [".SH COMMANDS", "Each has its own page:"]
        body += [f".BR hystviz-{c} (1)" for c, _ in commands(hv)]
    body += [".SH SEE ALSO", ".BR hystviz (1),", ".BR hystviz-scene (5),", ".BR libhystviz (3)"]
    write(out, "\n".join(body) + "\n")


def scene5(md, out):
    with open(md, encoding="utf-8") as f:
        text = f.read()
    body = ['.TH HYSTVIZ-SCENE 5 "" "hystviz" "hystviz manual"', ".SH NAME",
            "hystviz-scene \\- the scene file format of hystviz", ".SH DESCRIPTION"]
    in_code = False
    for line in text.splitlines():
        if line.startswith("```"):
            body.append(".fi" if in_code else ".nf")
            in_code = not in_code
            continue
        if not in_code and line.startswith("#"):
            body.append(".SH " + roff_escape(line.lstrip("#").strip().upper()))
            continue
        if not in_code and not line.strip():
            body.append(".PP")
            continue
        body.append(roff_escape(line))
    body += [".SH SEE ALSO", ".BR hystviz (1)"]
    write(out, "\n".join(body) + "\n")


def lib3(header, out):
    with open(header, encoding="utf-8") as f:
        text = f.read()
    body = ['.TH LIBHYSTVIZ 3 "" "hystviz" "hystviz manual"', ".SH NAME",
            "libhystviz \\- hysteresis models and their figures as a C library", ".SH SYNOPSIS", ".nf",
            "#include <hystviz.h>", "cc prog.c $(pkg-config \\-\\-cflags \\-\\-libs hystviz)", ".fi",
            ".SH DESCRIPTION", ".nf"]
    body += [roff_escape(l) for l in text.splitlines() if not l.startswith("#")]
    body += [".fi", ".SH SEE ALSO", ".BR hystviz (1),", ".BR hystviz-scene (5)"]
    write(out, "\n".join(body) + "\n")


def completion(hv, schema_prog, out):
    schema = json.loads(subprocess.run([schema_prog], capture_output=True, check=True, timeout=60).stdout)
    keys = []
    for s in schema["sections"]:
        pre = s["name"] + (".NAME." if s["takes_name"] else ".")
        keys += [pre + k["name"] for k in s["keys"]]
    cmds = [c for c, _ in commands(hv)]
    tables = {c: table(hv, c) for c in cmds}
    keyed = sorted({n for t in tables.values() for o in t["options"] if o["scene_key"] for n in names(o)})
    # a value written as its choices ("dahl|lugre|dahl-filter"): completed from them
    choices = {}
    for t in tables.values():
        for o in t["options"]:
            if o["arg"] and re.fullmatch(r"[a-z0-9-]+(\|[a-z0-9-]+)+", o["arg"]):
                for n in names(o):
                    choices.setdefault(n, set()).add(o["arg"])
    lines = ["# bash completion for hystviz (generated by tools/gen_docs.py from each",
             "# command's option table and the scene schema; do not edit)",
             "_hystviz() {",
             "    local cur=${COMP_WORDS[COMP_CWORD]} prev=${COMP_WORDS[COMP_CWORD-1]} cmd=${COMP_WORDS[1]}",
             "    if [ \"$COMP_CWORD\" -eq 1 ]; then",
             f"        COMPREPLY=($(compgen -W '{' '.join(cmds + options(hv, '-'))}' -- \"$cur\")); return",
             "    fi",
             "    case $prev in",
             f"    {'|'.join(keyed)})",
             f"        COMPREPLY=($(compgen -S = -W '{' '.join(keys)}' -- \"$cur\")); compopt -o nospace; return ;;",
             *[f"    {n}) COMPREPLY=($(compgen -W '{' '.join(next(iter(a)).split('|'))}' -- \"$cur\")); return ;;"
               for n, a in sorted(choices.items()) if len(a) == 1],  # one meaning of the name in every command
             "    esac",
             "    local opts",
             "    case $cmd in"]
    for c in cmds:
        lines.append(f"    {c}) opts='{' '.join(sorted(n for o in tables[c]['options'] for n in names(o)))}' ;;")
    lines += ["    *) opts='' ;;", "    esac",
              "    case $cur in",
              "    -*) COMPREPLY=($(compgen -W \"$opts\" -- \"$cur\")) ;;",
              "    *) COMPREPLY=($(compgen -f -X '!*.scene' -- \"$cur\") $(compgen -d -- \"$cur\")) ;;",
              "    esac",
              "}",
              "complete -F _hystviz hystviz"]
    write(out, "\n".join(lines) + "\n")


def main():
    a = sys.argv[1:]
    if not a:
        sys.exit(__doc__)
    if a[0] == "man" and len(a) == 4:
        man(a[1], a[2], a[3])
    elif a[0] == "scene5" and len(a) == 3:
        scene5(a[1], a[2])
    elif a[0] == "lib3" and len(a) == 3:
        lib3(a[1], a[2])
    elif a[0] == "completion" and len(a) == 4:
        completion(a[1], a[2], a[3])
    elif a[0] == "commands" and len(a) == 2:
        with open(a[1], encoding="utf-8") as f:
            src = f.read()
        block = src[src.index('"commands:\\n"'):]
        names = []
        for m in re.finditer(r'^\s*"  ([a-z]+) {2,}[^"]*\\n"\s*$', block, re.M):
            names.append(m.group(1))
            if block[m.end():].lstrip().startswith('"\\n"'):
                break
        print("\n".join(names))
    elif a[0] == "options" and len(a) == 3:
        print("\n".join(options(a[1], a[2])))
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main()
