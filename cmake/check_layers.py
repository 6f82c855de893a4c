#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The core's layering gate: modules keep their insides, and nothing goes round in circles.

A module is a folder of lib/ (lib/common is shared by all). Checks:

1. includes: a file of lib/ includes only public headers (sbr/...), its own module's
   headers and lib/common's; never another module's (their _internal.h and the like);
2. include circles: no header reaches itself through its includes (lib/ and include/sbr/);
3. with --archive: from the archive's symbols (nm), no file uses another module's
   private functions (sbr_<module>_priv_*, or any symbol defined in another module that
   its public headers do not declare), and no circle between the archive's files: when
   a.c uses b.c, b.c does not use a.c, directly or through others (a circle is one file
   split in two, or two modules that are one).

Prints each finding and a summary; exit 1 when there is one.
"""
import argparse
import os
import re
import subprocess
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def module_of(root, path):
    rel = os.path.relpath(path, os.path.join(root, "lib"))
    return rel.split(os.sep)[0] if not rel.startswith("..") else None


def source_files(root):
    out = []
    for top in ("lib", os.path.join("include", "sbr")):
        for dirpath, _, names in os.walk(os.path.join(root, top)):
            for n in sorted(names):
                if n.endswith((".c", ".h", ".inc")):
                    out.append(os.path.normpath(os.path.join(dirpath, n)))
    return sorted(out)


def resolve(root, path, name):
    for base in (os.path.dirname(path), os.path.join(root, "include"), os.path.join(root, "lib")):
        cand = os.path.normpath(os.path.join(base, name))
        if os.path.isfile(cand):
            return cand
    return None


def include_graph(root):
    graph = {}
    for path in source_files(root):
        with open(path, encoding="utf-8") as f:
            text = f.read()
        graph[path] = [t for t in (resolve(root, path, n) for n in INCLUDE.findall(text)) if t]
    return graph


def cycles(graph):
    """The strongly connected components with more than one node, or a node on itself
    (Tarjan's algorithm, iterative)."""
    index, low, on, stack, out = {}, {}, set(), [], []
    counter = [0]
    for start in sorted(graph):
        if start in index:
            continue
        work = [(start, iter(sorted(graph.get(start, ()))))]
        index[start] = low[start] = counter[0]
        counter[0] += 1
        stack.append(start)
        on.add(start)
        while work:
            node, it = work[-1]
            nxt = next(it, None)
            if nxt is not None:
                if nxt not in index:
                    index[nxt] = low[nxt] = counter[0]
                    counter[0] += 1
                    stack.append(nxt)
                    on.add(nxt)
                    work.append((nxt, iter(sorted(graph.get(nxt, ())))))
                elif nxt in on:
                    low[node] = min(low[node], index[nxt])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                comp = []
                while True:
                    w = stack.pop()
                    on.discard(w)
                    comp.append(w)
                    if w == node:
                        break
                if len(comp) > 1 or node in graph.get(node, ()):
                    out.append(sorted(comp))
    return out


def check_includes(root, graph):
    found = []
    for path, targets in sorted(graph.items()):
        mod = module_of(root, path)
        if mod is None:
            continue
        for t in targets:
            tmod = module_of(root, t)
            if tmod is not None and tmod not in (mod, "common"):
                found.append(f"{os.path.relpath(path, root)}: includes "
                             f"{os.path.relpath(t, root)} (module {tmod}'s insides)")
    for comp in cycles(graph):
        found.append("include circle: " + " -> ".join(os.path.relpath(p, root) for p in comp))
    return found


def public_declarations(root):
    names = set()
    inc = os.path.join(root, "include", "sbr")
    for n in sorted(os.listdir(inc)) if os.path.isdir(inc) else ():
        if n.endswith(".h"):
            with open(os.path.join(inc, n), encoding="utf-8") as f:
                names.update(re.findall(r"\b(sbr_\w+)\s*\(", f.read()))
                f.seek(0)
                names.update(re.findall(r"\bextern\s+const\s+\w+\s+(sbr_\w+)", f.read()))
    return names


def archive_symbols(nm, archive):
    """{object: (defined set, undefined set)} from `nm archive`."""
    text = subprocess.run([nm, archive], check=True, capture_output=True, text=True).stdout
    objs, cur = {}, None
    for line in text.splitlines():
        if line.endswith(":") and not line.startswith(" "):
            cur = line[:-1]
            objs[cur] = (set(), set())
            continue
        parts = line.split()
        if cur is None or len(parts) < 2:
            continue
        kind, name = parts[-2], parts[-1]
        if kind == "U":
            objs[cur][1].add(name)
        elif kind.isupper():
            objs[cur][0].add(name)
    return objs


def object_modules(root):
    """object file name (a.c.o / a.o / a.c.obj) -> module, from lib/'s sources."""
    out = {}
    for dirpath, _, names in os.walk(os.path.join(root, "lib")):
        for n in names:
            if n.endswith(".c"):
                mod = module_of(root, os.path.join(dirpath, n))
                for o in (n + ".o", n + ".obj", n[:-2] + ".o"):
                    out[o] = (mod, os.path.relpath(os.path.join(dirpath, n), root))
    return out


def check_archive(root, nm, archive):
    objs = archive_symbols(nm, archive)
    mods = object_modules(root)
    public = public_declarations(root)
    owner = {}
    for o, (defined, _) in objs.items():
        for s in defined:
            owner[s] = o
    found, graph = [], {}
    for o, (_, undefined) in sorted(objs.items()):
        mod, src = mods.get(o, (None, o))
        graph[src] = set()
        for s in sorted(undefined):
            d = owner.get(s)
            if d is None or d == o:
                continue
            dmod, dsrc = mods.get(d, (None, d))
            graph[src].add(dsrc)
            if dmod not in (mod, "common") and (s not in public or "_priv_" in s):
                found.append(f"{src}: uses {s} of {dsrc} (module {dmod}'s insides)")
    for comp in cycles(graph):
        found.append("circle between files: " + " <-> ".join(comp))
    return found, len(objs)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--source", required=True, help="the project's root")
    ap.add_argument("--archive", help="the core's archive (libsbr.a) for the symbol checks")
    ap.add_argument("--nm", default="nm")
    ap.add_argument("--expect-findings", type=int,
                    help="the gate's self-test: exit 0 only when exactly this many are found")
    a = ap.parse_args()
    graph = include_graph(a.source)
    found = check_includes(a.source, graph)
    summary = f"{len(graph)} files of lib/ and include/sbr/"
    if a.archive:
        more, n = check_archive(a.source, a.nm, a.archive)
        found += more
        summary += f", {n} objects of {os.path.basename(a.archive)}"
    for f in found:
        print(f)
    print(f"check_layers: {summary}: {len(found)} finding(s)")
    if a.expect_findings is not None:
        return 0 if len(found) == a.expect_findings else 1
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
