#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""long_functions.py: no C function in src/ over 80 lines (issue 34, item 4).

A function's length is its lines from the first line of its definition to its
closing brace, as universal-ctags reports them (`--fields=+ne`, the line and
the end of each definition).  Two kinds of function may be longer:

  * a numerical kernel that reads best whole, named in its own file: a line
        Kernels read whole: name, name (why)
    in the comment at the top of the file (before the first #include);
  * a function listed in the allow-list file (default
    tests/design/long_functions.txt beside this tree): one `path name` a line,
    path relative to SRC_DIR; '#' starts a comment.  It holds only the
    offenders that another branch is rewriting; it should become empty.

Any other function over the limit is an offender: the checker prints each one
(path:line, name, length) and exits 1.  A stale name (a kernel or an allowed
function that no longer exists or is no longer over the limit) is an error too,
so the lists only shrink.  Exit 0 when all is well; 77 (skip) when ctags is
missing or is not universal-ctags with JSON output (1 under CI=true, where
tools/setup.sh test installs it); 2 for bad arguments or an
allow-list line that does not read as `path name`.

    python3 tools/long_functions.py [--max N] [--allow FILE] [SRC_DIR]
"""
import json
import os
import re
import shutil
import subprocess
import sys

# "Kernels read whole: name, name" and then anything (a reason) not a name list
KERNELS = re.compile(r'Kernels read whole:\s*([A-Za-z_]\w*(?:\s*,\s*[A-Za-z_]\w*)*)')


def functions(src):
    """(path relative to src, name, first line, length) of every C function."""
    ctags = shutil.which('ctags-universal') or shutil.which('ctags')  # (Debian's name, then any)
    if not ctags:
        return None
    cmd = [ctags, '--languages=C', '--langmap=C:.c.h', '--kinds-C=f', '--fields=+ne', '--output-format=json',
           '-R', '-o', '-', '.']
    try:
        out = subprocess.run(cmd, cwd=src, capture_output=True, text=True, timeout=120)
    except (OSError, subprocess.TimeoutExpired):
        return None
    if out.returncode != 0:
        return None
    found = []
    for line in out.stdout.splitlines():
        try:
            tag = json.loads(line)
        except ValueError:
            return None
        if tag.get('_type') != 'tag' or tag.get('kind') != 'function' or 'end' not in tag:
            continue
        path = os.path.normpath(tag['path'])
        found.append((path, tag['name'], tag['line'], tag['end'] - tag['line'] + 1))
    return found


def kernels_of(src, path):
    """The kernel names declared in the top comment of src/path."""
    with open(os.path.join(src, path), encoding='utf-8', errors='replace') as f:
        head = f.read().split('#include', 1)[0]
    names = set()
    for m in KERNELS.finditer(head):
        names.update(n for n in re.split(r'[\s,]+', m.group(1)) if n)
    return names


def read_allow(path):
    """{(path, name): line number} from the allow-list file; exits 2 on a bad line."""
    allow = {}
    with open(path, encoding='utf-8') as f:
        for no, line in enumerate(f, 1):
            text = line.split('#', 1)[0].strip()
            if not text:
                continue
            parts = text.split()
            if len(parts) != 2:
                print(f'{path}:{no}: want "path name", got {line.strip()!r}', file=sys.stderr)
                sys.exit(2)
            allow[(os.path.normpath(parts[0]), parts[1])] = no
    return allow


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    limit, allow_file, rest = 80, os.path.join(here, '..', 'tests', 'design', 'long_functions.txt'), []
    args = sys.argv[1:]
    while args:
        a = args.pop(0)
        if a in ('--max', '--allow') and args:
            v = args.pop(0)
            if a == '--allow':
                allow_file = v
            elif v.isdigit() and int(v) > 0:
                limit = int(v)
            else:
                print(f'long_functions: --max wants a positive whole number, got {v!r}', file=sys.stderr)
                return 2
        elif a.startswith('-') or len(rest) == 1:
            print('usage: long_functions.py [--max N] [--allow FILE] [SRC_DIR]', file=sys.stderr)
            return 2
        else:
            rest.append(a)
    src = rest[0] if rest else os.path.join(here, '..', 'src')
    if not os.path.isdir(src):
        print(f'long_functions: {src}: not a directory', file=sys.stderr)
        return 2
    found = functions(src)
    if found is None:
        if os.environ.get('CI') == 'true':  # (tools/setup.sh test installs it)
            print('long_functions: FAIL: no universal-ctags with --output-format=json (apt-get install universal-ctags)')
            return 1
        print('long_functions: SKIP: needs universal-ctags with --output-format=json')
        return 77
    allow = read_allow(allow_file) if os.path.exists(allow_file) else {}
    files = sorted({p for p, _, _, _ in found})
    kernels = {(p, n) for p in files for n in kernels_of(src, p)}
    long = {(p, n): (line, length) for p, n, line, length in found if length > limit}
    errors = 0
    for (p, n), (line, length) in sorted(long.items()):
        if (p, n) in kernels:
            print(f'kernel  {p}:{line} {n}: {length} lines')
        elif (p, n) in allow:
            print(f'allowed {p}:{line} {n}: {length} lines ({allow_file}:{allow[(p, n)]})')
        else:
            print(f'FAIL {p}:{line}: {n} is {length} lines, over {limit}: split it, or name it a '
                  f'kernel in the comment at the top of {p}')
            errors += 1
    for (p, n) in sorted(kernels - set(long)):
        print(f'FAIL {p}: kernel {n} named in its top comment is not a function over {limit} lines '
              f'here: take the name out')
        errors += 1
    for (p, n), no in sorted(allow.items()):
        if (p, n) not in long:
            print(f'FAIL {allow_file}:{no}: {p} {n} is not a function over {limit} lines any more: '
                  f'take the line out')
            errors += 1
    print(f'long_functions: {len(found)} functions in {len(files)} files, {len(long)} over {limit} '
          f'lines, {errors} error(s)')
    return 1 if errors else 0


if __name__ == '__main__':
    sys.exit(main())
