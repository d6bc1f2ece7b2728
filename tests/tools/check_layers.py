#!/usr/bin/python3
"""The layering check of granflow's sources (docs/ARCHITECTURE.md, "Layers").

usage: check_layers.py [SRC_DIR]       check every #include "layer/..." of SRC_DIR (default src/)
       check_layers.py --print-layers  the layers, lowest first, one line each ("a b" = peers)

Each folder of src/ is a layer; a file may include its own layer and the layers below it, never
one above it or a peer (two layers of the same rank, such as levelset/ and rheology/, or momentum/
and projection/, do not see each other). A folder that is not in LAYERS is an error too: a new layer takes its place in
the order here and in docs/ARCHITECTURE.md. Exit 0 when clean, 1 with one line per violation.
"""
import os
import re
import sys

# Lowest first. Layers on one line are peers of the same rank.
LAYERS = [
    ["core"],
    ["grid"],
    ["fields"],
    ["operators"],
    ["boundary"],
    ["linsolve"],
    ["levelset", "rheology", "vof"],
    ["momentum", "projection", "interface"],
    ["stepper"],
    ["diagnostics"],
    ["io"],
    ["sim"],
    ["setup"],
]
RANK = {name: r for r, names in enumerate(LAYERS) for name in names}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"/]+)/[^"]+"')


def check(src):
    problems = []
    for layer in sorted(os.listdir(src)):
        path = os.path.join(src, layer)
        if not os.path.isdir(path):
            continue
        if layer not in RANK:
            problems.append(f"{layer}/: a folder that is not a layer of tests/tools/check_layers.py")
            continue
        for dirpath, _, files in os.walk(path):
            for f in sorted(files):
                if not f.endswith((".hpp", ".cpp", ".h")):
                    continue
                fpath = os.path.join(dirpath, f)
                rel = os.path.relpath(fpath, src)
                with open(fpath, encoding="utf-8") as fh:
                    for n, line in enumerate(fh, 1):
                        m = INCLUDE.match(line)
                        if not m:
                            continue
                        target = m.group(1)
                        if target == layer:
                            continue
                        if target not in RANK:
                            problems.append(f"{rel}:{n}: includes {target}/, not a layer")
                        elif RANK[target] > RANK[layer]:
                            problems.append(f"{rel}:{n}: {layer}/ includes {target}/, a layer "
                                            f"above it")
                        elif RANK[target] == RANK[layer]:
                            problems.append(f"{rel}:{n}: {layer}/ includes its peer {target}/")
    return problems


def main(argv):
    if len(argv) > 1 and argv[1] == "--print-layers":
        for names in LAYERS:
            print(" ".join(names))
        return 0
    src = argv[1] if len(argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "..", "src")
    problems = check(src)
    for p in problems:
        print(p)
    print("layering: " + ("ok" if not problems else f"{len(problems)} violation(s)"))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
