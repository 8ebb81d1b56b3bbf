#!/usr/bin/env python3
"""Largest relative difference between the numbers of two wetroad JSON results.

Walks both files' trees in step and compares every numeric leaf present in both (timings,
provenance and version strings are skipped: they differ between any two runs). Prints the
worst leaves and exits 1 when one exceeds --rtol (relative to max(|a|, |b|), leaves below
--atol in both ignored).

Usage: scripts/compare-results.py before.json after.json [--rtol 1e-12] [--atol 1e-300]
"""
import argparse
import json
import sys

SKIP = {"timings", "provenance", "version", "wall_s", "wall_setup", "seconds"}


def leaves(node, path=""):
    if isinstance(node, dict):
        for k, v in node.items():
            if k not in SKIP:
                yield from leaves(v, f"{path}/{k}")
    elif isinstance(node, list):
        for i, v in enumerate(node):
            yield from leaves(v, f"{path}[{i}]")
    elif isinstance(node, (int, float)) and not isinstance(node, bool):
        yield path, float(node)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("before")
    ap.add_argument("after")
    ap.add_argument("--rtol", type=float, default=1e-12)
    ap.add_argument("--atol", type=float, default=1e-300)
    a = ap.parse_args()
    with open(a.before) as f:
        before = dict(leaves(json.load(f)))
    with open(a.after) as f:
        after = dict(leaves(json.load(f)))
    diffs = []
    for k in before.keys() & after.keys():
        x, y = before[k], after[k]
        scale = max(abs(x), abs(y))
        if scale <= a.atol:
            continue
        diffs.append((abs(x - y) / scale, k, x, y))
    diffs.sort(reverse=True)
    worst = diffs[0][0] if diffs else 0.0
    print(f"{len(diffs)} numbers compared, largest relative difference {worst:.3g}")
    for d, k, x, y in diffs[:5]:
        if d > 0:
            print(f"  {d:.3g}  {k}: {x!r} -> {y!r}")
    return 1 if worst > a.rtol else 0


if __name__ == "__main__":
    sys.exit(main())
