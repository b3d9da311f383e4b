#!/usr/bin/env python3
"""Craig-Bampton against MacNeal-Rubin (free-interface modes with residual
flexibility, primal form) for the hybrid structure, measured on an exported
railvsi model (K.mtx, M.mtx, C.mtx, map.json from `vsi generate deck-3d`).

Written separately from the C++ (SciPy only). Both reductions keep the
track T in FE and reduce the bridge B = I + G (G: bridge DOFs a track DOF
couples to). In primal form MacNeal-Rubin spans the static interface
solutions plus the bridge's free-interface modes, Craig-Bampton the same
static solutions plus the modes with G held, so the two differ only in
which modes enrich the static basis:
  CB: u_I = Psi u_G + Phi_fixed q
  MR: u_I = Psi u_G + (Phi_free_I - Psi Phi_free_G) q
A moving force group crosses the rail at constant speed; each model is
stepped by the same average-acceleration Newmark scheme; the deck output
points' displacement and acceleration are compared with the full model's.
"""
import argparse, json, sys, time
import numpy as np
import scipy.io, scipy.sparse as sp, scipy.sparse.linalg as spla, scipy.linalg as la
from scipy.signal import butter, sosfiltfilt


def load(d):
    K = sp.csc_matrix(scipy.io.mmread(f"{d}/K.mtx"))
    M = sp.csc_matrix(scipy.io.mmread(f"{d}/M.mtx"))
    C = sp.csc_matrix(scipy.io.mmread(f"{d}/C.mtx"))
    m = json.load(open(f"{d}/map.json"))
    return K, M, C, m


def rail_load_matrix(m, xs):
    """Nodal vertical forces of a unit force at each x on every rail
    (linear sharing between the two nearest rail nodes; rotations left out:
    the same in every model, so the comparison does not depend on it)."""
    rows, cols, vals = [], [], []
    for k, x in enumerate(xs):
        for r in m["rail_lines"]:
            xr = np.asarray(r["x_m"]); dv = r["dof_v"]
            j = np.searchsorted(xr, x) - 1
            if j < 0 or j + 1 >= len(xr):
                continue
            t = (x - xr[j]) / (xr[j + 1] - xr[j])
            for dof, w in ((dv[j], 1 - t), (dv[j + 1], t)):
                if dof is None or dof < 0:
                    continue
                rows.append(dof); cols.append(k); vals.append(-w)
    return rows, cols, vals


class Newmark:
    """Average acceleration (gamma 1/2, beta 1/4), factor once."""
    def __init__(self, K, M, C, dt, dense):
        self.K, self.M, self.C, self.dt = K, M, C, dt
        A = K + (2 / dt) * C + (4 / dt ** 2) * M
        if dense:
            self.lu = la.cho_factor(np.asarray(A))
            self.solve = lambda b: la.cho_solve(self.lu, b)
        else:
            f = spla.splu(sp.csc_matrix(A))
            self.solve = f.solve

    def run(self, force_at, steps, out_rows):
        n = self.K.shape[0]; dt = self.dt
        u = np.zeros(n); v = np.zeros(n)
        f0 = force_at(0)
        # start from the static state under the first load position
        u = spla.spsolve(sp.csc_matrix(self.K), f0) if sp.issparse(self.K) else np.linalg.solve(self.K, f0)
        a = np.zeros(n)
        ys = np.zeros((steps + 1, out_rows.shape[0])); yd = np.zeros_like(ys)
        yd[0] = out_rows @ u; ys[0] = out_rows @ a
        for s in range(1, steps + 1):
            f = force_at(s)
            rhs = f + self.M @ ((4 / dt ** 2) * u + (4 / dt) * v + a) + self.C @ ((2 / dt) * u + v)
            un = self.solve(rhs)
            an = (4 / dt ** 2) * (un - u) - (4 / dt) * v - a
            v = v + 0.5 * dt * (a + an); u = un; a = an
            yd[s] = out_rows @ u; ys[s] = out_rows @ a
        return yd, ys


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("model_dir")
    ap.add_argument("--cutoffs", default="30,60,100,150,225")
    ap.add_argument("--speed-kmh", type=float, default=300.0)
    ap.add_argument("--dt-s", type=float, default=2.5e-4)
    ap.add_argument("--axles-m", default="0,2.5,17.375,19.875",
                    help="axle positions of the force group (m, behind the first)")
    ap.add_argument("--filter-hz", type=float, default=30.0)
    ap.add_argument("--eig", type=int, default=0,
                    help="instead of time histories: the lowest EIG frequencies of the coupled model, "
                         "full against each reduction (largest relative error)")
    ap.add_argument("--load", choices=["moving", "impact"], default="moving",
                    help="moving: the force group crosses the rail; impact: a 2 ms half-sine "
                         "force on both rails at the middle span's centre, then 0.3 s free")
    args = ap.parse_args()

    K, M, C, mp = load(args.model_dir)
    n = K.shape[0]
    T = np.array(sorted(mp["track_dofs"]))
    isT = np.zeros(n, bool); isT[T] = True
    coupled = (abs(K) + abs(M) + abs(C)).tocsr()[T, :].tocoo().col
    isG = np.zeros(n, bool); isG[coupled] = True; isG &= ~isT
    G = np.flatnonzero(isG); I = np.flatnonzero(~isT & ~isG); B = np.flatnonzero(~isT)
    print(f"# {args.model_dir}: {n} DOFs, track {len(T)}, interface {len(G)}, interior {len(I)}")

    KII = K[I][:, I]; MII = M[I][:, I]; KIG = K[I][:, G]
    t0 = time.process_time()
    fII = spla.splu(sp.csc_matrix(KII))
    Psi = -fII.solve(np.asarray(KIG.todense()))
    print(f"# constraint modes: {time.process_time() - t0:.1f} s CPU")

    fmax = max(float(c) for c in args.cutoffs.split(","))
    def modes(Kx, Mx, fcut):
        k = 20
        while True:
            k = min(k, Kx.shape[0] - 2)
            w2, V = spla.eigsh(Kx, M=Mx, k=k, sigma=0.0, which="LM")
            o = np.argsort(w2); w2, V = w2[o], V[:, o]
            f = np.sqrt(np.maximum(w2, 0)) / (2 * np.pi)
            if f[-1] > fcut or k == Kx.shape[0] - 2:
                return f, V
            k *= 2
    t0 = time.process_time(); f_fix, V_fix = modes(KII, MII, fmax); t_fix = time.process_time() - t0
    KBB = K[B][:, B]; MBB = M[B][:, B]
    t0 = time.process_time(); f_free, V_free = modes(KBB, MBB, fmax); t_free = time.process_time() - t0
    print(f"# fixed-interface modes: {len(f_fix)} to {f_fix[-1]:.1f} Hz ({t_fix:.1f} s); "
          f"free-interface: {len(f_free)} to {f_free[-1]:.1f} Hz ({t_free:.1f} s)")
    print(f"# first fixed-interface {f_fix[:3].round(3)} Hz, first free {f_free[:3].round(3)} Hz")
    posI = {d: i for i, d in enumerate(B)}
    iI = np.array([posI[d] for d in I]); iG = np.array([posI[d] for d in G])

    def basis_fn(kind, m):
        """n x (nT + nG + m) transformation, dense (fine at these sizes)."""
        nT, nG = len(T), len(G)
        Tm = np.zeros((n, nT + nG + m))
        Tm[T, np.arange(nT)] = 1.0
        Tm[G, nT + np.arange(nG)] = 1.0
        Tm[np.ix_(I, nT + np.arange(nG))] = Psi
        if m:
            Q = V_fix[:, :m] if kind == "CB" else V_free[iI, :m] - Psi @ V_free[iG, :m]
            Tm[np.ix_(I, nT + nG + np.arange(m))] = Q
        return Tm

    if args.eig:
        def low(Kx, Mx):
            w2 = spla.eigsh(Kx, M=Mx, k=args.eig, sigma=0.0, which="LM", return_eigenvectors=False)
            return np.sort(np.sqrt(np.maximum(w2, 0)) / (2 * np.pi))
        ref = low(K, M)
        print(f"# full model: lowest {args.eig} coupled frequencies {ref[0]:.4f} ... {ref[-1]:.4f} Hz")
        print("| model | cut-off Hz | modes | largest rel. error of the lowest coupled frequencies | "
              "below 30 Hz | below 60 Hz |")
        for fc in [float(c) for c in args.cutoffs.split(",")]:
            for kind, fl in (("CB", f_fix), ("MR", f_free)):
                m = int(np.sum(fl <= fc))
                Tm = basis_fn(kind, m)
                Kr = sp.csc_matrix(Tm.T @ (K @ Tm)); Mr = sp.csc_matrix(Tm.T @ (M @ Tm))
                fr = low(0.5 * (Kr + Kr.T), 0.5 * (Mr + Mr.T))
                e = np.abs(fr - ref) / ref
                print(f"| {kind} | {fc:g} | {m} | {e.max():.2e} | {e[ref < 30].max() if np.any(ref < 30) else 0:.2e} | "
                      f"{e[ref < 60].max() if np.any(ref < 60) else 0:.2e} |", flush=True)
        return 0

    outs = mp["output_points"]
    out_dofs = [o["dof"] for o in outs]
    v = args.speed_kmh / 3.6
    axles = np.array([float(a) for a in args.axles_m.split(",")])
    x0 = mp["bridge_start_m"] - 5.0 - axles[-1]
    x1 = mp["bridge_end_m"] + 5.0
    steps = int(np.ceil((x1 - x0) / v / args.dt_s))
    # load operator per step: sparse n x steps built lazily
    def force_full(s):
        xs = x0 + v * s * args.dt_s + axles.max() - axles
        r, c, val = rail_load_matrix(mp, xs)
        f = np.zeros(n); np.add.at(f, r, val)
        return f
    if args.load == "impact":
        xs_mid = 0.5 * (mp["supports_x_m"][1] + mp["supports_x_m"][2]) if len(mp["supports_x_m"]) > 2 \
            else 0.5 * (mp["bridge_start_m"] + mp["bridge_end_m"])
        r, c, val = rail_load_matrix(mp, [xs_mid])
        f_unit = np.zeros(n); np.add.at(f_unit, r, val)
        t_on, t_pulse = 0.01, 0.002
        steps = int(np.ceil(0.3 / args.dt_s))
        def force_full(s):
            t = s * args.dt_s - t_on
            return f_unit * (np.sin(np.pi * t / t_pulse) if 0.0 <= t <= t_pulse else 0.0)

    def run(Kr, Mr, Cr, Tmat, dense):
        out = np.zeros((len(out_dofs), Kr.shape[0]))
        for j, d in enumerate(out_dofs):
            out[j] = Tmat[d] if Tmat is not None else np.eye(1, n, d)[0]
        if Tmat is not None:
            # every load acts on the rails, which are track DOFs: the reduced
            # coordinates start with u_T itself
            nr = Kr.shape[0]
            def force(s):
                fr = np.zeros(nr); fr[:len(T)] = force_full(s)[T]; return fr
        else:
            force = force_full
        nm = Newmark(Kr, Mr, Cr, args.dt_s, dense)
        return nm.run(force, steps, out)

    t0 = time.process_time()
    ref_d, ref_a = run(K, M, C, None, False)
    print(f"# load: {args.load}; full model: {steps} steps, {time.process_time() - t0:.1f} s CPU")
    sos = butter(4, args.filter_hz, fs=1 / args.dt_s, output="sos")
    ref_af = sosfiltfilt(sos, ref_a, axis=0)

    print("| model | cut-off Hz | modes | " + " | ".join(
        f"{o['name']} disp | acc | acc {args.filter_hz:g} Hz" for o in outs) + " |")
    for fc in [float(c) for c in args.cutoffs.split(",")]:
        for kind, fl in (("CB", f_fix), ("MR", f_free)):
            m = int(np.sum(fl <= fc))
            Tm = basis_fn(kind, m)
            Kr = Tm.T @ (K @ Tm); Mr = Tm.T @ (M @ Tm); Cr = Tm.T @ (C @ Tm)
            Kr = 0.5 * (Kr + Kr.T); Mr = 0.5 * (Mr + Mr.T); Cr = 0.5 * (Cr + Cr.T)
            # the track couples to the interface only: the reduced matrices are
            # sparse outside their (interface + modes) block
            d, a = run(sp.csc_matrix(Kr), sp.csc_matrix(Mr), sp.csc_matrix(Cr), Tm, False)
            af = sosfiltfilt(sos, a, axis=0)
            cells = []
            for j in range(len(outs)):
                e = lambda y, r: (np.abs(y[:, j]).max() - np.abs(r[:, j]).max()) / np.abs(r[:, j]).max() * 100
                cells.append(f"{e(d, ref_d):+.3f} % | {e(a, ref_a):+.3f} % | {e(af, ref_af):+.3f} %")
            print(f"| {kind} | {fc:g} | {m} | " + " | ".join(cells) + " |", flush=True)
    print("# reference peaks (full): " + "; ".join(
        f"{o['name']}: {np.abs(ref_d[:, j]).max():.4e} m, {np.abs(ref_a[:, j]).max():.4e} m/s2, "
        f"filtered {np.abs(ref_af[:, j]).max():.4e} m/s2" for j, o in enumerate(outs)))


if __name__ == "__main__":
    sys.exit(main())
