#!/usr/bin/env python3
"""Writes one small simply supported beam in every matrix format railvsi reads,
with writers that are not railvsi's: SciPy's mmwrite (Matrix Market) and
hb_write (Harwell-Boeing RSA and RUA), and, from the documented layouts,
Harwell-Boeing elemental RSE and RUE (Duff, Grimes & Lewis 1992, Users' Guide for the
Harwell-Boeing Sparse Matrix Collection), the Abaqus *MATRIX INPUT data lines
(row node, row DOF, column node, column DOF, value) and an ANSYS-style
.mapping file (equation, node, DOF label).

The beam: Euler-Bernoulli, Hermite elements (DOFs v, theta = dv/dx per node),
consistent mass, v fixed at both ends. Equations in node order, vertical
before rotation: node 1 UR3; nodes 2..n: U2, UR3; node n+1 UR3.

usage: write_beam_files.py OUT_DIR SPAN_M ELEMENTS EI_NM2 MASS_KG_PER_M
"""
import json
import os
import sys

import numpy as np
import scipy.io
import scipy.sparse
from scipy.io._harwell_boeing.hb import HBInfo, HBMatrixType


def element_matrices(EI, m, h):
    # Closed forms (e.g. Przemieniecki, Theory of Matrix Structural Analysis):
    # the cubic Hermite beam's stiffness and consistent mass.
    k = EI / h**3 * np.array([[12, 6 * h, -12, 6 * h],
                              [6 * h, 4 * h * h, -6 * h, 2 * h * h],
                              [-12, -6 * h, 12, -6 * h],
                              [6 * h, 2 * h * h, -6 * h, 4 * h * h]])
    mm = m * h / 420 * np.array([[156, 22 * h, 54, -13 * h],
                                 [22 * h, 4 * h * h, 13 * h, -3 * h * h],
                                 [54, 13 * h, 156, -22 * h],
                                 [-13 * h, -3 * h * h, -22 * h, 4 * h * h]])
    return k, mm


def main():
    out, span, n_el, EI, m = sys.argv[1], float(sys.argv[2]), int(sys.argv[3]), float(sys.argv[4]), float(sys.argv[5])
    os.makedirs(out, exist_ok=True)
    h = span / n_el
    labels = []  # (node, dof) per equation, Abaqus DOF numbers
    v, rot, x = [], [], []
    for i in range(n_el + 1):
        node = i + 1
        x.append(span * i / n_el)
        if 0 < i < n_el:
            v.append(len(labels))
            labels.append((node, 2))
        else:
            v.append(-1)
        rot.append(len(labels))
        labels.append((node, 6))
    n = len(labels)
    K = np.zeros((n, n))
    M = np.zeros((n, n))
    elements = []  # (equations, k, m) with the fixed DOFs left out
    for e in range(n_el):
        dofs = [v[e], rot[e], v[e + 1], rot[e + 1]]
        k, mm = element_matrices(EI, m, h)
        keep = [a for a in range(4) if dofs[a] >= 0]
        elements.append(([dofs[a] for a in keep], k[np.ix_(keep, keep)], mm[np.ix_(keep, keep)]))
        for a in keep:
            for b in keep:
                K[dofs[a], dofs[b]] += k[a, b]
                M[dofs[a], dofs[b]] += mm[a, b]

    for name, A in (("K", K), ("M", M)):
        S = scipy.sparse.csc_matrix(A)
        scipy.io.mmwrite(os.path.join(out, f"beam_{name}_sym.mtx"), S, symmetry="symmetric", precision=17)
        scipy.io.mmwrite(os.path.join(out, f"beam_{name}_gen.mtx"), S, symmetry="general", precision=17)
        # RUA: hb_write's own choice; RSA: the same writer told the type.
        scipy.io.hb_write(os.path.join(out, f"beam_{name}_gen.rua"), S)
        lower = scipy.sparse.csc_matrix(np.tril(A))
        info = HBInfo.from_data(lower)
        info.mxtype = HBMatrixType("real", "symmetric", "assembled")
        scipy.io.hb_write(os.path.join(out, f"beam_{name}.rsa"), lower, hb_info=info)
        with open(os.path.join(out, f"beam_{name}.mapping"), "w") as f:
            f.write("Matrix Eqn   Node   DOF\n")
            for i, (node, dof) in enumerate(labels):
                f.write(f"{i + 1:10d} {node:6d}   {'UY' if dof == 2 else 'ROTZ'}\n")
        write_elemental(os.path.join(out, f"beam_{name}.rse"), n, elements, 1 if name == "K" else 2, True)
        write_elemental(os.path.join(out, f"beam_{name}_full.rue"), n, elements, 1 if name == "K" else 2, False)
        # Abaqus: K as the full square, M as its upper triangle.
        with open(os.path.join(out, f"beam_{name}.abq"), "w") as f:
            f.write("** beam, written from the *MATRIX INPUT data line layout\n")
            for j in range(n):
                for i in range(n):
                    if A[i, j] != 0.0 and (name == "K" or i <= j):
                        f.write(f"{labels[i][0]}, {labels[i][1]}, {labels[j][0]}, {labels[j][1]}, {A[i, j]!r}\n")

    with open(os.path.join(out, "nodes.csv"), "w") as f:
        f.write("node,x,y,z\n")
        for i in range(n_el + 1):
            f.write(f"{i + 1},{x[i]!r},0,0\n")
    mid = n_el // 2
    index_map = {"rail_lines": [{"name": "deck", "x_m": x, "dof_v": v, "dof_rot": rot}],
                 "output_points": [{"name": "mid", "x_m": x[mid], "dof": v[mid]}]}
    json.dump(index_map, open(os.path.join(out, "map_index.json"), "w"), indent=1)
    for style, vert, rotation in (("abaqus", "U2", "UR3"), ("ansys", "UY", "ROTZ")):
        labelled = {"nodes_csv": "nodes.csv",
                    "rail_lines": [{"name": "deck", "nodes": list(range(1, n_el + 2)),
                                    "vertical_dof": vert, "rotation_dof": rotation}],
                    "output_points": [{"name": "mid", "node": mid + 1, "dof": vert}]}
        json.dump(labelled, open(os.path.join(out, f"map_{style}.json"), "w"), indent=1)


def write_elemental(path, n, elements, which, symmetric):
    # RSE: per element its variable list (1-based) and the lower triangle of
    # its matrix by columns; RUE: all of it by columns. Pointers into the
    # variable lists.
    ptr, ind, val = [1], [], []
    for dofs, k, mm in elements:
        A = k if which == 1 else mm
        ind += [d + 1 for d in dofs]
        ptr.append(len(ind) + 1)
        for c in range(len(dofs)):
            for r in range(c if symmetric else 0, len(dofs)):
                val.append(A[r, c])

    def cards(values, per_line, fmt):
        lines = []
        for i in range(0, len(values), per_line):
            lines.append("".join(fmt % v for v in values[i:i + per_line]))
        return lines

    p = cards(ptr, 10, "%8d")
    i = cards(ind, 10, "%8d")
    v = cards(val, 3, "%26.17E")
    with open(path, "w") as f:
        f.write("%-72s%-8s\n" % ("beam, elemental", "beam"))
        f.write("%14d%14d%14d%14d%14d\n" % (len(p) + len(i) + len(v), len(p), len(i), len(v), 0))
        f.write("%-14s%14d%14d%14d%14d\n" % ("RSE" if symmetric else "RUE", n, len(elements), len(ind), len(val)))
        f.write("%-16s%-16s%-20s\n" % ("(10I8)", "(10I8)", "(3E26.17)"))
        f.write("\n".join(p + i + v) + "\n")


if __name__ == "__main__":
    main()
