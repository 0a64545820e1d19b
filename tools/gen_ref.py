#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""gen_ref.py: libhystviz's reference pages from its installed headers' contract
comments (the headers are the one source: each function's comment says what
it does, what it returns on error and who owns the memory).

  gen_ref.py list HEADER...            the documented functions, one a line
  gen_ref.py check [--configured=N,...] HEADER...
                                       exit 1 naming header:line of every public
                                       function without a contract comment (and
                                       when the functions are not the N configured)
  gen_ref.py man OUTDIR HEADER...      OUTDIR/NAME.3 for every function
  gen_ref.py html OUT HEADER...        one HTML page: every header, every function

A function's contract is the comment right above its declaration (no blank
line between) or after it on the same line.  Declarations written one under
the other share the comment above the first when it names each of them (as
"hy_x_init ... hy_x_free").
"""
import html
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gen_docs import roff_escape  # noqa: E402  (the man pages' one escaping)

GUARD = re.compile(r"^#ifdef __cplusplus\n.*?^#endif\n", re.S | re.M)


def scan(text):
    """The header's file-scope items in order: (kind, text, line) with kind
    comment, pp, blank (an empty line) or decl (up to its ';' or closing brace)."""
    text = GUARD.sub(lambda m: "\n" * m.group(0).count("\n"), text)
    items, i, line, n = [], 0, 1, len(text)
    while i < n:
        c = text[i]
        if text.startswith("/*", i):
            j = text.index("*/", i) + 2
            items.append(("comment", text[i:j], line))
        elif text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            items.append(("comment", text[i:j], line))
        elif c == "#" and (i == 0 or text[i - 1] == "\n"):
            j = i
            while True:
                j = text.find("\n", j)
                if j < 0 or text[j - 1] != "\\":
                    break
                j += 1
            j = n if j < 0 else j
            items.append(("pp", text[i:j], line))
        elif c.isspace():
            j = i
            while j < n and text[j].isspace():
                j += 1
            if text.count("\n", i, j) >= 2:
                items.append(("blank", "", line))
        else:
            j, depth = i, 0
            while j < n:
                if text.startswith("/*", j):
                    j = text.index("*/", j) + 2
                    continue
                ch = text[j]
                if ch in "({":
                    depth += 1
                elif ch in ")}":
                    depth -= 1
                elif ch == ";" and depth == 0:
                    j += 1
                    break
                j += 1
            items.append(("decl", text[i:j], line))
        line += text.count("\n", i, j)
        i = j
    return items


def function_name(decl):
    code = re.sub(r"/\*.*?\*/", " ", decl, flags=re.S)
    m = re.match(r"[^(){};]*?\b(hy_\w+)\s*\(", code)
    if not m or "typedef" in code[: m.start(1)] or "{" in code[: m.start(1)]:
        return None
    return m.group(1)


def comment_text(c):
    """A comment's prose, without its markers and leading stars, lines kept."""
    if c.startswith("//"):
        return c[2:].strip()
    body = c[2:-2]
    lines = [re.sub(r"^\s*\* ?", "", l) if i else l.strip() for i, l in enumerate(body.split("\n"))]
    return "\n".join(lines).strip()


def parse(path):
    """(intro, functions): the header's opening comment and, in order, each
    function as a dict name, decl, doc (None when it has no contract), line."""
    with open(path, encoding="utf-8") as f:
        items = scan(f.read())
    comments = [t for k, t, _ in items if k == "comment" and "SPDX-License-Identifier" not in t]
    intro = comment_text(comments[0]) if comments else ""
    funcs, prev_doc, group = [], None, []
    for idx, (kind, text, line) in enumerate(items):
        if kind != "decl":
            if kind != "comment" or idx + 1 < len(items) and items[idx + 1][0] != "decl":
                group = []
            continue
        before = items[idx - 1] if idx else ("blank", "", 0)
        after = items[idx + 1] if idx + 1 < len(items) else ("blank", "", 0)
        own = None
        if before[0] == "comment":
            own = comment_text(before[1])
            group = []
        elif after[0] == "comment" and after[2] == line + text.count("\n"):
            own = comment_text(after[1])
        name = function_name(text)
        if own is not None:
            prev_doc = own
        elif group and prev_doc is not None and name and name in prev_doc:
            own = prev_doc
        group.append(name)
        if name:
            decl = re.sub(r"\s+", " ", re.sub(r"/\*.*?\*/", " ", text, flags=re.S)).strip()
            funcs.append({"name": name, "decl": decl, "doc": own, "line": line, "header": path})
    return intro, funcs


def all_functions(headers):
    out = []
    for h in headers:
        out += parse(h)[1]
    return out


def roff(text):
    """text's lines for a man page: gen_docs.py's escapes (backslashes,
    non-ASCII as \\[uXXXX], a leading dot), and minus signs as \\-."""
    return [roff_escape(l).replace("-", "\\-") for l in text.split("\n")]


def man(outdir, headers):
    intros = {h: parse(h)[0] for h in headers}
    funcs = all_functions(headers)
    for f in funcs:
        base = os.path.basename(f["header"])
        group = [g for g in funcs if g["header"] == f["header"] and g["doc"] == f["doc"]]
        page = [f'.TH {f["name"].upper()} 3 "" "hystviz" "libhystviz manual"', ".SH NAME",
                f'{f["name"]} \\- ' + roff(first_sentence(f["doc"] or "")).pop(0), ".SH SYNOPSIS", ".nf",
                f"#include <{base}>", "cc prog.c $(pkg\\-config \\-\\-cflags \\-\\-libs hystviz)", ""]
        for g in group:
            page += roff(g["decl"])
        page += [".fi", ".SH DESCRIPTION", ".nf"] + roff(f["doc"] or "") + [".fi"]
        page += [".SH HEADER", f"From {base}:", ".PP", ".nf"] + roff(intros[f["header"]]) + [".fi"]
        see = sorted({g["name"] for g in group} - {f["name"]})
        page += [".SH SEE ALSO"] + [f".BR {s} (3)," for s in see] + [".BR libhystviz (3)"]
        with open(os.path.join(outdir, f["name"] + ".3"), "w", encoding="utf-8") as out:
            out.write("\n".join(page) + "\n")


def first_sentence(doc):
    """The summary for the NAME line: the comment's first sentence (to a full
    stop followed by a space), at most 70 characters."""
    s = re.split(r"(?<=\.)\s", " ".join(doc.split()), maxsplit=1)[0]
    if len(s) > 70:
        s = s[:67].rsplit(" ", 1)[0] + " ..."
    return s[:1].lower() + s[1:] if s[1:2] == s[1:2].lower() else s


def page_html(out, headers):
    parts = ["<!DOCTYPE html>", '<html lang="en"><head><meta charset="utf-8">',
             "<title>libhystviz reference</title>",
             "<style>body{font-family:sans-serif;max-width:60em;margin:auto}pre{background:#f4f4f4;padding:.5em;"
             "white-space:pre-wrap}h3{font-family:monospace}</style></head><body>",
             "<h1>libhystviz reference</h1>",
             "<p>Generated by tools/gen_ref.py from the installed headers' comments (the same text as the "
             "section-3 man pages).</p>", "<h2>Headers</h2>", "<ul>"]
    parsed = [(h, *parse(h)) for h in headers]
    for h, _, funcs in parsed:
        b = os.path.basename(h)
        parts.append(f'<li><a href="#{b}">{b}</a>: ' +
                     ", ".join(f'<a href="#{f["name"]}">{f["name"]}</a>' for f in funcs) + "</li>")
    parts.append("</ul>")
    for h, intro, funcs in parsed:
        b = os.path.basename(h)
        parts += [f'<h2 id="{b}">{b}</h2>', f"<pre>{html.escape(intro)}</pre>"]
        for f in funcs:
            parts += [f'<h3 id="{f["name"]}">{f["name"]}</h3>', f'<pre><code>{html.escape(f["decl"])}</code></pre>',
                      f'<p>{html.escape(f["doc"] or "").replace(chr(10), " ")}</p>']
    parts.append("</body></html>")
    with open(out, "w", encoding="utf-8") as f:
        f.write("\n".join(parts) + "\n")


def main():
    a = sys.argv[1:]
    if len(a) < 2 or a[0] not in ("list", "check", "man", "html"):
        sys.exit(__doc__)
    if a[0] == "list":
        print("\n".join(sorted(f["name"] for f in all_functions(a[1:]))))
    elif a[0] == "check":
        configured = None
        if a[1].startswith("--configured="):
            configured = set(a[1].split("=", 1)[1].split(","))
            a = a[:1] + a[2:]
        funcs = all_functions(a[1:])
        if configured is not None and configured != {f["name"] for f in funcs}:
            print("the reference pages were configured for other functions than the headers declare now "
                  "(added: %s; removed: %s): run meson setup --reconfigure" %
                  (" ".join(sorted({f["name"] for f in funcs} - configured)) or "none",
                   " ".join(sorted(configured - {f["name"] for f in funcs})) or "none"))
            sys.exit(1)
        bad = [f for f in funcs if not f["doc"]]
        for f in bad:
            print(f'{f["header"]}:{f["line"]}: {f["name"]} has no contract comment (the comment right above '
                  "its declaration, or one above a group of declarations that names it)")
        if bad:
            sys.exit(1)
        print(f"ok: {len(funcs)} functions, each with its contract comment")
    elif a[0] == "man":
        man(a[1], a[2:])
    else:
        page_html(a[1], a[2:])


if __name__ == "__main__":
    main()
