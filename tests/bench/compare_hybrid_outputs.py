#!/usr/bin/env python3
"""Two builds' hybrid reductions compared: what `hybrid_bench --cost
--frequencies-out PREFIX` wrote for one deck and cut-off (PREFIX-DOFS-CUTOFF).

  python3 tests/bench/compare_hybrid_outputs.py A-233292-109 B-233292-109

Prints the largest relative difference of the interior and bridge
frequencies (mode by mode), of each reduced matrix (largest |a - b| over the
largest |b|) and of the run's values.
Exits 1 when a file is missing, the sizes differ or a value is not finite.
"""
import math
import sys

import numpy as np


def frequencies(path):
    with open(path) as f:
        return np.array([float(line) for line in f if line.strip()])


def triplets(path):
    raw = np.fromfile(path, dtype=np.dtype([("i", "<i4"), ("j", "<i4"), ("v", "<f8")]))
    return {(int(r), int(c)): float(v) for r, c, v in raw}


def matrix_difference(a, b):
    keys = set(a) | set(b)
    largest = max(abs(v) for v in b.values())
    worst = max(abs(a.get(k, 0.0) - b.get(k, 0.0)) for k in keys)
    return worst / largest


def values(path):
    with open(path) as f:
        return {k: float(v) for k, v in (line.split() for line in f if line.strip())}


def main():
    a, b = sys.argv[1], sys.argv[2]
    ok = True
    for suffix in (".txt", "-bridge.txt"):
        fa, fb = frequencies(a + suffix), frequencies(b + suffix)
        if fa.shape != fb.shape:
            print(f"{suffix}: {fa.size} against {fb.size} frequencies")
            ok = False
            continue
        d = np.max(np.abs(fa / fb - 1.0)) if fa.size else 0.0
        ok = ok and math.isfinite(d)
        print(f"frequencies{suffix[:-4]}: {fa.size} modes, largest relative difference {d:.2e}")
    for name in "KMC":
        ta, tb = triplets(f"{a}-{name}.bin"), triplets(f"{b}-{name}.bin")
        d = matrix_difference(ta, tb)
        ok = ok and math.isfinite(d)
        print(f"reduced {name}: {len(ta)} / {len(tb)} entries, largest |a - b| / largest |b| {d:.2e}")
    va, vb = values(a + "-values.txt"), values(b + "-values.txt")
    for k in vb:
        x, y = va.get(k, float("nan")), vb[k]
        d = abs(x - y) / abs(y) if y != 0.0 else abs(x - y)
        ok = ok and math.isfinite(d)
        print(f"{k}: {x:.12g} / {y:.12g}, relative difference {d:.2e}")
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
