#!/usr/bin/env python3
"""Independent reference for the box girder of the 3D deck generator.

What it models: the structure engine/generators/deck_3d.cpp builds for
tests/engine/deck_3d_box_test.cpp's box_options() (one 25 m span, the default
BoxGirderSection, generator mesh nx = 50), taken from the generator's
SPECIFICATION, not its code:
  - concrete E = 34 GPa, nu = 0.2, rho = 2500 kg/m^3; top slab 7 m x 0.3 m,
    bottom slab 5 m x 0.25 m, vertical webs 0.4 m standing on the bottom
    slab's edges, 2 m deep;
  - solid diaphragms filling the void over one generator element (L / nx =
    0.5 m) at each end and, with n intermediate ones, over the element
    floor(nx m / (n + 1)), m = 1..n (for n = 3: x in [6, 6.5], [12.5, 13],
    [18.5, 19] m);
  - bearings: w = 0 along the whole soffit line of both end faces
    (x = 0 and x = L, z = 0, |y| <= 2.5 m); v = 0 at the soffit centre of both
    ends; u = 0 at the soffit centre at x = 0;
  - two rails (y = +-0.75 m, EI = 2.059e11 x 3.217e-5 N m^2, 60.64 kg/m,
    Euler-Bernoulli) from x = -2 m to 27 m, v fixed at their two end nodes, on
    vertical pads of 3.25e7 N/m every 0.5 m: on the deck's top surface at the
    pad's (x, y) for 0 <= x <= L, on rigid ground outside.

Why it is independent: a different discretisation written separately -
20-node serendipity hexahedra (quadratic), full 3 x 3 x 3 Gauss integration,
consistent mass (the product: 8-node hexahedra with Wilson's incompatible
modes, 2 x 2 x 2 Gauss, lumped mass), on its own mesh, refined uniformly
(level r: every region's element count times r). It uses the section's
symmetry about y = 0: the vertical bending modes are solved on half the
section with v = 0 on the plane of symmetry, the torsion (and lateral) modes
with u = w = 0 there; each half carries one rail. Modes are identified by
their shape at midspan (the rigid section motion fitted by least squares, as
the C++ test does), not by their index.

What it found (2026-11-27, docs/verification.md): levels 1, 2, 3 do not
converge (torsion 19.430, 19.063, 18.688 Hz), because the specified bearings
are singular in a 3D solid (a line or a point has no stiffness in the
continuum limit): the frequencies fall with the element size at the bearing,
in this model and in the product alike. With --bearing patch-no-lateral (w = 0
over the end diaphragms' soffit, no lateral point) the model converges.
Level 1 has the product's element size at the bearing (0.5 m along x); the
C++ test compares at that level.

Usage: box_girder_reference.py [--levels 1,2,3] [--diaphragms 0,3] [--json]
                               [--bearing line] [--generator-nx 50]
       box_girder_reference.py --check tests/engine/deck_3d_box_test.cpp
Prints, per variant and level, the DOFs and the first bending and torsion
frequencies, and a Richardson estimate when three levels are given (only
meaningful for a bearing patch). --check re-runs level 1 and compares it with
the numbers typed in the C++ test (ctest box_girder_reference_reproduces).
"""
import argparse
import itertools
import json
import math
import re
import sys
import time

import numpy as np
import scipy.linalg as la
import scipy.sparse as sp
import scipy.sparse.csgraph as csgraph
import scipy.sparse.linalg as spla

# ---- the specification (deck_3d.hpp defaults, box_options())
SPAN = 25.0
TOP_W, TOP_T = 7.0, 0.3
BOT_W, BOT_T = 5.0, 0.25
WEB_T, DEPTH = 0.4, 2.0
E, NU, RHO = 34.0e9, 0.2, 2500.0
RAIL_EI, RAIL_M = 2.059e11 * 3.217e-5, 60.64
PAD_K, PAD_SPACING, RAIL_Y = 3.25e7, 0.5, 0.75
APPROACH, EXIT = 2.0, 2.0
GENERATOR_NX = 50  # the generator mesh's elements per span: a diaphragm is one of them long

# ---- the 20-node serendipity hexahedron
NODES = np.array([p for p in itertools.product((-1, 0, 1), repeat=3) if list(p).count(0) == 0] +
                 [p for p in itertools.product((-1, 0, 1), repeat=3) if list(p).count(0) == 1], dtype=float)
assert NODES.shape == (20, 3)


def shape(xi):
    """N (20) and dN/dxi (20 x 3) at the natural point xi."""
    N = np.empty(20)
    dN = np.empty((20, 3))
    for n, a in enumerate(NODES):
        if np.all(a != 0):
            f = 1.0 + xi * a
            s = float(np.dot(xi, a)) - 2.0
            N[n] = f.prod() * s / 8.0
            for d in range(3):
                others = np.prod([f[e] for e in range(3) if e != d])
                dN[n, d] = others * (a[d] * s + f[d] * a[d]) / 8.0
        else:
            f = np.where(a == 0, 1.0 - xi * xi, 1.0 + xi * a)
            df = np.where(a == 0, -2.0 * xi, a)
            N[n] = f.prod() / 4.0
            for d in range(3):
                dN[n, d] = df[d] * np.prod([f[e] for e in range(3) if e != d]) / 4.0
    return N, dN


GAUSS_X, GAUSS_W = np.polynomial.legendre.leggauss(3)
GAUSS = [(np.array([GAUSS_X[i], GAUSS_X[j], GAUSS_X[k]]), GAUSS_W[i] * GAUSS_W[j] * GAUSS_W[k])
         for i in range(3) for j in range(3) for k in range(3)]
SHAPES = [shape(p) for p, _ in GAUSS]


def elasticity():
    lam, mu = E * NU / ((1 + NU) * (1 - 2 * NU)), E / (2 * (1 + NU))
    D = np.zeros((6, 6))
    D[:3, :3] = lam
    D[:3, :3] += 2 * mu * np.eye(3)
    D[3:, 3:] = mu * np.eye(3)
    return D


D_MAT = elasticity()


def box_element(size):
    """Stiffness and consistent mass (60 x 60, DOF 3n + c) of a brick of these edge lengths."""
    half = 0.5 * np.asarray(size)
    detJ = half.prod()
    K = np.zeros((60, 60))
    M = np.zeros((60, 60))
    for (_, w), (N, dN) in zip(GAUSS, SHAPES):
        g = dN / half  # d/dx, d/dy, d/dz
        B = np.zeros((6, 60))
        B[0, 0::3], B[1, 1::3], B[2, 2::3] = g[:, 0], g[:, 1], g[:, 2]
        B[3, 0::3], B[3, 1::3] = g[:, 1], g[:, 0]  # gamma_xy
        B[4, 1::3], B[4, 2::3] = g[:, 2], g[:, 1]  # gamma_yz
        B[5, 0::3], B[5, 2::3] = g[:, 2], g[:, 0]  # gamma_xz
        K += B.T @ D_MAT @ B * (w * detJ)
        Nm = np.zeros((3, 60))
        for c in range(3):
            Nm[c, c::3] = N
        M += RHO * Nm.T @ Nm * (w * detJ)
    return K, M


# ---- the mesh
def split(lengths, counts):
    lines = [0.0]
    for length, n in zip(lengths, counts):
        start = lines[-1]
        lines += [start + length * (q + 1) / n for q in range(n)]
    return np.array(lines)


def diaphragm_intervals(n_intermediate):
    nx = GENERATOR_NX
    dx = SPAN / nx
    elements = {0, nx - 1}
    for m in range(1, n_intermediate + 1):
        elements.add(min(max(int(math.floor(nx * m / (n_intermediate + 1))), 0), nx - 1))
    return sorted((e * dx, (e + 1) * dx) for e in elements)


def x_lines(r):
    # The same breakpoints for both variants (every diaphragm face of the
    # 3-diaphragm box and midspan), elements of about 1 m / r.
    cuts = {0.0, SPAN, 0.5 * SPAN}
    for a, b in diaphragm_intervals(3):
        cuts.update((a, b))
    cuts = sorted(cuts)
    lines = [0.0]
    for a, b in zip(cuts[:-1], cuts[1:]):
        n = max(1, int(math.ceil((b - a) * r / 1.0 - 1e-9)))  # about 1 m / r
        lines += [a + (b - a) * (q + 1) / n for q in range(n)]
    return np.array(lines)


class Model:
    """Half the box (y >= 0) in 20-node bricks, one rail, for one symmetry class."""

    def __init__(self, r, n_intermediate, symmetric, bearing="line"):
        self.bearing = bearing
        self.X = x_lines(r)
        half_void = 0.5 * BOT_W - WEB_T
        self.Y = split([half_void, WEB_T, 0.5 * (TOP_W - BOT_W)], [2 * r, r, r])
        self.Z = split([BOT_T, DEPTH - TOP_T - BOT_T, TOP_T], [r, 2 * r, r])
        self.symmetric = symmetric
        diaphragms = diaphragm_intervals(n_intermediate)
        nx, ny, nz = len(self.X) - 1, len(self.Y) - 1, len(self.Z) - 1
        xc, yc, zc = [0.5 * (a[1:] + a[:-1]) for a in (self.X, self.Y, self.Z)]
        in_diaphragm = np.array([any(a < x < b for a, b in diaphragms) for x in xc])
        top = zc > DEPTH - TOP_T
        under = yc < 0.5 * BOT_W
        web = yc > 0.5 * BOT_W - WEB_T
        bottom = zc < BOT_T
        cells = []
        for i, j, k in itertools.product(range(nx), range(ny), range(nz)):
            if top[k] or (under[j] and (in_diaphragm[i] or bottom[k] or web[j])):
                cells.append((i, j, k))
        cells = np.array(cells)
        # Nodes on the doubled grid (2 nx + 1, ...): corners and edge midpoints.
        shape3 = (2 * nx + 1, 2 * ny + 1, 2 * nz + 1)
        corner = 2 * cells + 1
        grid_nodes = corner[:, None, :] + NODES.astype(int)[None, :, :]  # (cells, 20, 3)
        flat = np.ravel_multi_index(grid_nodes.reshape(-1, 3).T, shape3)
        used, inverse = np.unique(flat, return_inverse=True)
        self.conn = inverse.reshape(-1, 20)
        self.grid = np.array(np.unravel_index(used, shape3)).T  # doubled-grid index per node
        gx = np.empty(2 * nx + 1)
        gx[0::2], gx[1::2] = self.X, 0.5 * (self.X[1:] + self.X[:-1])
        gy = np.empty(2 * ny + 1)
        gy[0::2], gy[1::2] = self.Y, 0.5 * (self.Y[1:] + self.Y[:-1])
        gz = np.empty(2 * nz + 1)
        gz[0::2], gz[1::2] = self.Z, 0.5 * (self.Z[1:] + self.Z[:-1])
        self.xyz = np.column_stack([gx[self.grid[:, 0]], gy[self.grid[:, 1]], gz[self.grid[:, 2]]])
        self.node_of = {tuple(g): n for n, g in enumerate(map(tuple, self.grid))}
        self.cells = cells
        self.gx, self.gy, self.gz = gx, gy, gz
        self.assemble()

    def assemble(self):
        X, Y, Z, cells = self.X, self.Y, self.Z, self.cells
        n_deck = 3 * len(self.xyz)
        sizes = np.column_stack([np.diff(X)[cells[:, 0]], np.diff(Y)[cells[:, 1]], np.diff(Z)[cells[:, 2]]])
        keys, group = np.unique(np.round(sizes, 12), axis=0, return_inverse=True)
        group = group.ravel()
        rows, cols, kv, mv = [], [], [], []
        for g, size in enumerate(keys):
            Ke, Me = box_element(size)
            conn = self.conn[group == g]
            dofs = (3 * conn[:, :, None] + np.arange(3)[None, None, :]).reshape(-1, 60)
            rows.append(np.repeat(dofs, 60, axis=1).ravel())
            cols.append(np.tile(dofs, (1, 60)).ravel())
            kv.append(np.tile(Ke.ravel(), len(conn)))
            mv.append(np.tile(Me.ravel(), len(conn)))
        # ---- one rail (y = +0.75) on pads: Hermite beam elements between pad stations
        s = PAD_SPACING
        before = int(math.ceil(APPROACH / s - 1e-9))
        count = int(math.ceil((SPAN + EXIT + before * s) / s - 1e-9)) + 1
        rx = -before * s + s * np.arange(count)
        rail_v = n_deck + 2 * np.arange(count)
        rail_rot = rail_v + 1
        n_total = n_deck + 2 * count
        for e in range(count - 1):
            h = rx[e + 1] - rx[e]
            ke = RAIL_EI / h**3 * np.array([[12, 6 * h, -12, 6 * h], [6 * h, 4 * h * h, -6 * h, 2 * h * h],
                                            [-12, -6 * h, 12, -6 * h], [6 * h, 2 * h * h, -6 * h, 4 * h * h]])
            me = RAIL_M * h / 420 * np.array([[156, 22 * h, 54, -13 * h], [22 * h, 4 * h * h, 13 * h, -3 * h * h],
                                              [54, 13 * h, 156, -22 * h], [-13 * h, -3 * h * h, -22 * h, 4 * h * h]])
            d = np.array([rail_v[e], rail_rot[e], rail_v[e + 1], rail_rot[e + 1]])
            rows.append(np.repeat(d, 4))
            cols.append(np.tile(d, 4))
            kv.append(ke.ravel())
            mv.append(me.ravel())
        for q, x in enumerate(rx):
            g = [(rail_v[q], 1.0)]
            if -1e-9 <= x <= SPAN + 1e-9:
                g += [(d, -w) for d, w in self.top_point(x, RAIL_Y)]
            d = np.array([a for a, _ in g])
            c = np.array([b for _, b in g])
            rows.append(np.repeat(d, len(d)))
            cols.append(np.tile(d, len(d)))
            kv.append(PAD_K * np.outer(c, c).ravel())
            mv.append(np.zeros(len(d) ** 2))
        rows, cols = np.concatenate(rows), np.concatenate(cols)
        K = sp.csr_matrix((np.concatenate(kv), (rows, cols)), shape=(n_total, n_total))
        M = sp.csr_matrix((np.concatenate(mv), (rows, cols)), shape=(n_total, n_total))
        # ---- constraints
        fixed = set([rail_v[0], rail_v[-1]])
        x, y, z = self.xyz.T

        def soffit_of(zn):
            return abs(zn) < 1e-9

        for n in range(len(self.xyz)):
            on_plane = abs(y[n]) < 1e-9
            end = abs(x[n]) < 1e-9 or abs(x[n] - SPAN) < 1e-9
            if self.bearing.startswith("patch"):  # diagnostic: w = 0 under the whole end diaphragm
                dx = SPAN / GENERATOR_NX
                if soffit_of(z[n]) and (x[n] < dx + 1e-9 or x[n] > SPAN - dx - 1e-9):
                    fixed.add(3 * n + 2)
            soffit = abs(z[n]) < 1e-9
            if on_plane:  # the plane of symmetry
                fixed.update([3 * n + 1] if self.symmetric else [3 * n, 3 * n + 2])
            if end and soffit:  # the bearing line (every node on it lies under the bottom slab)
                fixed.add(3 * n + 2)
                if on_plane and not self.bearing.endswith("no-lateral"):
                    fixed.add(3 * n + 1)  # lateral bearing at the soffit centre, both ends
                    if abs(x[n]) < 1e-9:
                        fixed.add(3 * n)  # longitudinal bearing, first end
        self.free = np.setdiff1d(np.arange(n_total), np.array(sorted(fixed)))
        self.K = K[self.free][:, self.free].tocsc()
        self.M = M[self.free][:, self.free].tocsc()
        self.n_total = n_total

    def top_point(self, x, y):
        """Deck w DOFs and weights interpolating w on the top face at (x, y)."""
        i = min(int(np.searchsorted(self.X, x, side="right")) - 1, len(self.X) - 2)
        j = min(int(np.searchsorted(self.Y, y, side="right")) - 1, len(self.Y) - 2)
        k = len(self.Z) - 2
        xi = np.array([2 * (x - 0.5 * (self.X[i] + self.X[i + 1])) / (self.X[i + 1] - self.X[i]),
                       2 * (y - 0.5 * (self.Y[j] + self.Y[j + 1])) / (self.Y[j + 1] - self.Y[j]), 1.0])
        N, _ = shape(xi)
        out = []
        for n, a in enumerate(NODES.astype(int)):
            if abs(N[n]) > 1e-14:
                node = self.node_of[(2 * i + 1 + a[0], 2 * j + 1 + a[1], 2 * k + 1 + a[2])]
                out.append((3 * node + 2, N[n]))
        return out

    def modes(self, count, sigma_hz):
        # Shift-invert Lanczos on a banded Cholesky factor of K - sigma M
        # (sigma below the class's first mode, so positive definite), the
        # DOFs in reverse Cuthill-McKee order: LAPACK's dpbtrf, much faster
        # here than SuperLU.
        sigma = math.copysign((2 * math.pi * sigma_hz) ** 2, sigma_hz)
        A = (self.K - sigma * self.M).tocsr()
        perm = csgraph.reverse_cuthill_mckee(A, symmetric_mode=True)
        Ap = sp.triu(A[perm][:, perm]).tocoo()
        bw = int((Ap.col - Ap.row).max())
        band = np.zeros((bw + 1, A.shape[0]))
        band[bw + Ap.row - Ap.col, Ap.col] = Ap.data
        factor = la.cholesky_banded(band, overwrite_ab=True, check_finite=False)
        inverse = np.empty_like(perm)
        inverse[perm] = np.arange(len(perm))

        def solve(b):
            return la.cho_solve_banded((factor, False), b[perm], check_finite=False)[inverse]

        op = spla.LinearOperator(A.shape, matvec=solve, dtype=float)
        values, vectors = spla.eigsh(self.K, k=count, M=self.M, sigma=sigma, which="LM", OPinv=op, tol=1e-10)
        order = np.argsort(values)
        full = np.zeros((self.n_total, count))
        full[self.free] = vectors[:, order]
        return np.sqrt(np.maximum(values[order], 0.0)) / (2 * math.pi), full

    def section_motion(self, phi, x_m, zc):
        """At x: the rigid motion (v0, w0, theta about (y = 0, z = zc)) fitted to
        the whole section's (v, w) (the half mirrored), the share of the motion it
        explains, and the rotation's share of that."""
        at = np.nonzero(np.abs(self.xyz[:, 0] - x_m) < 1e-9)[0]
        y, z = self.xyz[at, 1], self.xyz[at, 2]
        v, w = phi[3 * at + 1], phi[3 * at + 2]
        mirror = y > 1e-9
        # Mirror: symmetric class (v odd, w even), antisymmetric (v even, w odd).
        sv, sw = (-1.0, 1.0) if self.symmetric else (1.0, -1.0)
        y = np.concatenate([y, -y[mirror]])
        z = np.concatenate([z, z[mirror]])
        v = np.concatenate([v, sv * v[mirror]])
        w = np.concatenate([w, sw * w[mirror]])
        G = np.zeros((2 * len(y), 3))
        G[0::2, 0], G[0::2, 2] = 1.0, -(z - zc)
        G[1::2, 1], G[1::2, 2] = 1.0, y
        d = np.empty(2 * len(y))
        d[0::2], d[1::2] = v, w
        c, *_ = np.linalg.lstsq(G, d, rcond=None)
        fitted = G @ c
        rigid = fitted @ fitted / (d @ d)
        twist = (c[2] ** 2 * (G[:, 2] @ G[:, 2])) / (fitted @ fitted)
        return c, rigid, twist


def centroid_z():
    web_h = DEPTH - TOP_T - BOT_T
    parts = [(TOP_W * TOP_T, DEPTH - 0.5 * TOP_T), (BOT_W * BOT_T, 0.5 * BOT_T), (2 * WEB_T * web_h, BOT_T + 0.5 * web_h)]
    return sum(a * z for a, z in parts) / sum(a for a, _ in parts)


def solve(r, n_intermediate, bearing="line"):
    zc = centroid_z()
    out = {"level": r, "intermediate_diaphragms": n_intermediate}
    for symmetric in (True, False):
        start = time.time()
        m = Model(r, n_intermediate, symmetric, bearing)
        hz, shapes = m.modes(6, 1.0 if symmetric else 5.0)
        out["dofs_two_halves"] = out.get("dofs_two_halves", 0) + len(m.free)
        found = None
        for q in range(len(hz)):
            c, rigid, twist = m.section_motion(shapes[:, q], 0.5 * SPAN, zc)
            if symmetric and rigid > 0.99 and abs(c[1]) > 0.0:
                found = ("bending_hz", hz[q])
            if not symmetric and twist > 0.9 and rigid > 0.8:
                found = ("torsion_hz", hz[q])
            if found:
                out[found[0]] = float(hz[q])
                out[found[0].replace("_hz", "_shape")] = {"rigid_share": float(rigid), "twist_share": float(twist)}
                break
        out["symmetric_hz" if symmetric else "antisymmetric_hz"] = [float(f) for f in hz]
        out["seconds"] = out.get("seconds", 0.0) + time.time() - start
    # The whole model's DOFs: both halves share the plane of symmetry.
    return out


def richardson(levels, values):
    """Converged value and observed order from three levels r (h ~ 1 / r)."""
    (r1, r2, r3), (f1, f2, f3) = levels, values
    # f(r) = f_inf + C r^-p; solve for p by bisection on the ratio of differences.
    target = (f2 - f1) / (f3 - f2)

    def g(p):
        return (r1 ** -p - r2 ** -p) / (r2 ** -p - r3 ** -p) - target

    lo, hi = 0.05, 12.0
    if g(lo) * g(hi) > 0:
        return None, None
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if g(lo) * g(mid) <= 0:
            hi = mid
        else:
            lo = mid
    p = 0.5 * (lo + hi)
    C = (f3 - f2) / (r3 ** -p - r2 ** -p)
    return f3 - C * r3 ** -p, p


def check(test_cpp):
    """Re-run level 1 and compare with the constants typed in the C++ test."""
    text = open(test_cpp, encoding="utf-8").read()
    failed = 0
    global GENERATOR_NX
    for name, n, nx in (("kReferenceLevel1", 0, 50), ("kReferenceLevel1Diaphragms", 3, 50),
                        ("kReferenceLevel1Nx100", 0, 100)):
        GENERATOR_NX = nx
        match = re.search(name + r"\{([0-9.eE+-]+),\s*([0-9.eE+-]+)\}", text)
        if not match:
            print(f"{test_cpp}: no {name}{{bending, torsion}}")
            return 1
        typed = {"bending_hz": float(match.group(1)), "torsion_hz": float(match.group(2))}
        row = solve(1, n)
        for key, value in typed.items():
            got = row.get(key, float("nan"))
            ok = abs(got - value) <= 1e-4 * value  # typed to 4 decimals
            failed += not ok
            print(f"{name} {key}: typed {value}, re-run {got:.6f}: {'ok' if ok else 'NOT REPRODUCED'}")
    return 1 if failed else 0


def main():
    global GENERATOR_NX
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--levels", default="1,2,3")
    ap.add_argument("--diaphragms", default="0,3")
    ap.add_argument("--json", action="store_true")
    ap.add_argument("--generator-nx", type=int, default=GENERATOR_NX,
                    help="the generator mesh's nx, which sets the diaphragms' length and place (50: box_options())")
    ap.add_argument("--check", metavar="TEST_CPP",
                    help="compare level 1 with the numbers typed in this C++ test (kReferenceLevel1*); exit 1 if not reproduced")
    ap.add_argument("--bearing", default="line", choices=["line", "patch", "no-lateral", "patch-no-lateral"],
                    help="line: the generator's (default); patch: w = 0 under the end diaphragms; no-lateral: "
                         "without the lateral bearings (diagnostics)")
    args = ap.parse_args()
    GENERATOR_NX = args.generator_nx
    if args.check:
        return check(args.check)
    levels = [int(v) for v in args.levels.split(",")]
    report = []
    for n in [int(v) for v in args.diaphragms.split(",")]:
        rows = [solve(r, n, args.bearing) for r in levels]
        entry = {"intermediate_diaphragms": n, "levels": rows}
        for key in ("bending_hz", "torsion_hz"):
            if len(rows) == 3 and all(key in row for row in rows):
                f_inf, p = richardson(levels, [row[key] for row in rows])
                entry[key + "_richardson"] = f_inf
                entry[key + "_order"] = p
        report.append(entry)
        if not args.json:
            for row in rows:
                print(f"diaphragms {n} level {row['level']}: {row['dofs_two_halves']} DOFs (two halves), "
                      f"bending {row.get('bending_hz', float('nan')):.4f} Hz, torsion {row.get('torsion_hz', float('nan')):.4f} Hz, "
                      f"{row['seconds']:.1f} s; sym {['%.3f' % f for f in row['symmetric_hz']]}, "
                      f"antisym {['%.3f' % f for f in row['antisymmetric_hz']]}", flush=True)
            for key in ("bending_hz", "torsion_hz"):
                if key + "_richardson" in entry:
                    print(f"diaphragms {n} {key}: Richardson {entry[key + '_richardson']}, order {entry[key + '_order']}")
    if args.json:
        print(json.dumps(report))


if __name__ == "__main__":
    sys.exit(main())
