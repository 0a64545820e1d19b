#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""include_graph.py: no circle between the files of src/ (issue 34, item 3).

A node is a source file and its header (src/render/hy_frame.c and
src/render/hy_frame.h are the node src/render/hy_frame; a header with no .c
of its name, such as hy_scene_internal.h, is a node of its own).  There is an
edge from A to B when A includes B's header ('#include "b.h"'); with --calls
also when A's .c calls a function that B's .c defines (not static).  Any
cycle of two or more nodes is a circle: the checker prints each one (its
nodes and one edge between each pair with its reason) and exits 1; with none
it exits 0.  The test (include_graph, suites cli and design) runs it without
--calls; --calls still finds the pipeline's driver and two stages calling
each other (scene_run.c, scene_draw.c, scene_data.c) and hy_signal.c with
hy_resample.c (one header, two files): a report, not yet a test.

    python3 tools/include_graph.py [--calls] [SRC_DIR]     (default: src/ beside tools/)

Generated headers (hy_models.h, hy_shaders.h) are not in the tree and are
passed over.  Headers that only declare (types, X-macro tables) are nodes of
their own and have no outgoing call edges.
"""
import os
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)
# a function definition at column 0: a return type, the name, '(' ... and no ';'
DEFINE = re.compile(r'^(?!static\b)(?:[A-Za-z_][\w ]*[\w\*]\s*\**)\b([A-Za-z_]\w*)\s*\([^;{]*\)\s*\{', re.M)
CALL = re.compile(r'\b([A-Za-z_]\w*)\s*\(')
COMMENT = re.compile(r'/\*.*?\*/|//[^\n]*', re.S)
STRING = re.compile(r'"(?:\\.|[^"\\\n])*"')


def strip(text):
    return COMMENT.sub(' ', text)


def nodes_of(src):
    files = {}
    for root, _, names in os.walk(src):
        for n in names:
            if n.endswith(('.c', '.h')):
                files.setdefault(os.path.join(root, n), None)
    return sorted(files)


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    args = [a for a in sys.argv[1:] if a != '--calls']
    calls = '--calls' in sys.argv[1:]
    src = args[0] if args else os.path.join(here, '..', 'src')
    src = os.path.normpath(src)
    paths = nodes_of(src)
    node = {p: os.path.splitext(os.path.relpath(p, src))[0] for p in paths}
    by_header = {}
    for p in paths:
        if p.endswith('.h'):
            by_header.setdefault(os.path.basename(p), []).append(p)
    text = {}
    for p in paths:
        with open(p, encoding='utf-8', errors='replace') as f:
            text[p] = strip(f.read())
    defined = {}
    for p in paths:
        if p.endswith('.c'):
            for m in DEFINE.finditer(text[p]):
                if m.group(1) not in ('if', 'for', 'while', 'switch', 'return', 'sizeof'):
                    defined.setdefault(m.group(1), set()).add(node[p])
    edges = {}

    def edge(a, b, why):
        if a != b:
            edges.setdefault(a, {}).setdefault(b, why)

    for p in paths:
        a = node[p]
        d = os.path.dirname(p)
        for inc in INCLUDE.findall(text[p]):
            local = os.path.normpath(os.path.join(d, inc))
            targets = [local] if local in node else by_header.get(os.path.basename(inc), [])
            for t in targets:
                edge(a, node[t], '%s includes "%s"' % (os.path.relpath(p, src), inc))
        if calls and p.endswith('.c'):
            body = STRING.sub('""', text[p])
            for name in set(CALL.findall(body)):
                for b in sorted(defined.get(name, ())):
                    if len(defined[name]) == 1:  # a name defined twice (per backend) is no edge
                        edge(a, b, '%s calls %s()' % (os.path.relpath(p, src), name))
    # Tarjan's strongly connected components, iteratively
    index, low, onstack, stack, sccs, counter = {}, {}, set(), [], [], [0]
    allnodes = sorted(set(node.values()))

    def strongconnect(v0):
        work = [(v0, iter(sorted(edges.get(v0, {}))))]
        index[v0] = low[v0] = counter[0]
        counter[0] += 1
        stack.append(v0)
        onstack.add(v0)
        while work:
            v, it = work[-1]
            for w in it:
                if w not in index:
                    index[w] = low[w] = counter[0]
                    counter[0] += 1
                    stack.append(w)
                    onstack.add(w)
                    work.append((w, iter(sorted(edges.get(w, {})))))
                    break
                if w in onstack:
                    low[v] = min(low[v], index[w])
            else:
                work.pop()
                if work:
                    low[work[-1][0]] = min(low[work[-1][0]], low[v])
                if low[v] == index[v]:
                    comp = []
                    while True:
                        w = stack.pop()
                        onstack.discard(w)
                        comp.append(w)
                        if w == v:
                            break
                    if len(comp) > 1:
                        sccs.append(sorted(comp))

    for v in allnodes:
        if v not in index:
            strongconnect(v)
    for comp in sorted(sccs):
        print('circle: ' + ' <-> '.join(comp))
        members = set(comp)
        for a in comp:
            for b, why in sorted(edges.get(a, {}).items()):
                if b in members:
                    print('    %s -> %s: %s' % (a, b, why))
    print('%d node(s), %d circle(s)' % (len(allnodes), len(sccs)))
    return 1 if sccs else 0


if __name__ == '__main__':
    sys.exit(main())
