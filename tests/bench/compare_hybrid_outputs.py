#!/usr/bin/env python3
"""Two builds' hybrid reductions compared: what `hybrid_bench --cost
--frequencies-out PREFIX` wrote for one deck and cut-off (PREFIX-DOFS-CUTOFF).

  python3 tests/bench/compare_hybrid_outputs.py A-233292-109 B-233292-109 TRACK INTERFACE

Prints the largest relative difference of the interior and bridge
frequencies (mode by mode), of each reduced matrix (largest |a - b| over the
largest |b|) and of the run's values. The reduced coordinates after the
TRACK track and INTERFACE interface DOFs are the modes, whose signs the
Rayleigh-Ritz step leaves to the eigensolver: each mode of A takes the sign
that matches B's coupling row in M (its largest entry) before the
comparison.
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
    q0 = int(sys.argv[3]) + int(sys.argv[4])
    ma, mb = triplets(f"{a}-M.bin"), triplets(f"{b}-M.bin")
    # The sign of each mode k: of the largest coupling entry M(g, k) in B.
    sign = {}
    for (i, j), v in mb.items():
        if j >= q0 > i and abs(v) > abs(sign.get(j, (0.0, 0.0))[1]):
            sign[j] = (i, v)
    flip = {j: (-1.0 if ma.get((i, j), 0.0) * v < 0.0 else 1.0) for j, (i, v) in sign.items()}
    print(f"modes with the sign flipped: {sum(1 for f in flip.values() if f < 0)} of {len(flip)}")
    for name in "KMC":
        ta, tb = triplets(f"{a}-{name}.bin"), triplets(f"{b}-{name}.bin")
        ta = {(i, j): v * flip.get(i, 1.0) * flip.get(j, 1.0) for (i, j), v in ta.items()}
        d = matrix_difference(ta, tb)
        ok = ok and math.isfinite(d)
        print(f"reduced {name}: {len(ta)} / {len(tb)} entries, largest |a - b| / largest |b| {d:.2e}")
        # What no choice of the modes' basis changes: the track and
        # interface block, and the coupling's Gram matrix Gq Gq' (the modes
        # of a near-double frequency may come rotated in their plane).
        tg = {k: v for k, v in ta.items() if max(k) < q0}
        ug = {k: v for k, v in tb.items() if max(k) < q0}
        gram = []
        for t in (ta, tb):
            rows = sorted({i for (i, j) in t if j >= q0 > i} | {0})
            cols = sorted({j for (i, j) in t if j >= q0})
            ri, cj = {r: x for x, r in enumerate(rows)}, {c: x for x, c in enumerate(cols)}
            G = np.zeros((len(rows), len(cols)))
            for (i, j), v in t.items():
                if j >= q0 > i:
                    G[ri[i], cj[j]] = v
            gram.append(G @ G.T)
        dg = (np.max(np.abs(gram[0] - gram[1])) / np.max(np.abs(gram[1]))
              if gram[0].shape == gram[1].shape and np.max(np.abs(gram[1])) > 0 else 0.0)
        print(f"  its track and interface block {matrix_difference(tg, ug):.2e}, coupling Gq Gq' {dg:.2e}")
    va, vb = values(a + "-values.txt"), values(b + "-values.txt")
    for k in vb:
        x, y = va.get(k, float("nan")), vb[k]
        d = abs(x - y) / abs(y) if y != 0.0 else abs(x - y)
        ok = ok and math.isfinite(d)
        print(f"{k}: {x:.12g} / {y:.12g}, relative difference {d:.2e}")
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
