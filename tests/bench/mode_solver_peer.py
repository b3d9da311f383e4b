#!/usr/bin/env python3
"""The mode solver bench's peer: SciPy's eigsh in shift-invert mode (ARPACK
mode 3 on a SuperLU factor of K - sigma M) on the bench's Matrix Market files.

Usage: mode_solver_peer.py DIR MODES SIGMA TOL
Reads DIR/K.mtx and DIR/M.mtx; prints one JSON line: the CPU seconds of
eigsh alone (eigenvectors included, as the bench's solver computes them) and
the frequencies in Hz, ascending.
"""
import json
import math
import sys
import time

import scipy.io
import scipy.sparse.linalg


def main():
    directory, modes, sigma, tol = sys.argv[1], int(sys.argv[2]), float(sys.argv[3]), float(sys.argv[4])
    K = scipy.io.mmread(f"{directory}/K.mtx").tocsc()
    M = scipy.io.mmread(f"{directory}/M.mtx").tocsc()
    start = time.process_time()
    values, _ = scipy.sparse.linalg.eigsh(K, k=modes, M=M, sigma=sigma, which="LM", tol=tol)
    cpu_s = time.process_time() - start
    hz = sorted(math.sqrt(max(v, 0.0)) / (2.0 * math.pi) for v in values)
    print(json.dumps({"cpu_s": cpu_s, "frequencies_hz": hz}))


if __name__ == "__main__":
    main()
