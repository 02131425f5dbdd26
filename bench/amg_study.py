#!/usr/bin/env python3
"""Does an algebraic multigrid pay for the engine's tet4 systems?

Exports the engine's own linear systems with `snh-gpu-bench hessian` (the
PSD-projected stiffness on the free DOFs at a Newton iterate of the twist
scene's first load step, its residual and the free DOFs' positions) at
several resolutions, element types and Poisson ratios, and solves each with
one conjugate-gradient loop (relative residual |r|/|b|, x0 = 0) under
different preconditioners:

  block-jacobi  the inverted 3x3 diagonal blocks, as the engine does
  sa-scalar     PyAMG smoothed aggregation, scalar (B = constants)
  sa-rbm        SA on 3x3 node blocks with the six rigid-body modes of the
                current positions as near-nullspace B; PyAMG's default
                symmetric block Gauss-Seidel smoothing (the best case)
  sa-rbm-bj     the same hierarchy with damped block-Jacobi smoothing, 2 sweeps
                before and after (what would run on a GPU without colouring)

Cost model, in units of one fine-level product (what one engine CG iteration
costs besides vector work; for tet4 the engine's default product on CPU is
the assembled CSR matrix): a CG iteration costs 1 product plus the
preconditioner: block-Jacobi 9 n / nnz(A) (one 3x3 block per node), AMG one
V-cycle (cycle_products: smoothing, residuals, transfers on every level, the
coarsest solve).
Setup, which a Newton solver pays every iteration because the Hessian
changes, is converted to products by this machine's measured time of one
fine-level sparse product (scipy CSR, one thread, like PyAMG's compiled
setup routines); a setup on the device would have its own ratio.

--lag-res adds, for tet4, a hierarchy built at one Newton iterate and used on
the systems of later ones: frozen whole, or refreshed (aggregates and
prolongators kept, Galerkin operators and smoothers rebuilt).

Writes OUT_DIR/amg_study.json (every record) and OUT_DIR/amg_study.md.
"""
import argparse
import json
import os
import platform
import subprocess
import sys
import time

import numpy as np
import scipy
import scipy.io
import scipy.sparse as sp

import pyamg

TOLERANCES = (1e-2, 1e-6)
# Coarsen until a level has about this many DOFs at most (the engine's
# geometric multigrid stops at 1000), then a sparse LU.
COARSEST_DOFS = 1000


def export(bench, work, element, nu, res, newton_iterations, reuse):
    prefix = os.path.join(work, f"twist_{element}_nu{nu}_res{res}_it{newton_iterations}")
    if not (reuse and os.path.exists(prefix + ".json")):
        cmd = [bench, "hessian", "twist", "--element", element, "--nu", str(nu), "--res", str(res),
               "--newton-iterations", str(newton_iterations), "--out", prefix]
        print("  $", " ".join(cmd), flush=True)
        subprocess.run(cmd, check=True)
    with open(prefix + ".json") as f:
        meta = json.load(f)
    t0 = time.perf_counter()
    a = sp.csr_matrix(scipy.io.mmread(prefix + ".mtx"))
    b = np.asarray(scipy.io.mmread(prefix + "_rhs.mtx")).ravel()
    dofs = np.loadtxt(prefix + "_dofs.csv", delimiter=",", skiprows=1)
    meta["seconds_read"] = time.perf_counter() - t0
    return meta, a, b, dofs


def rigid_body_modes(dofs):
    """Six columns: translations x, y, z and rotations about x, y, z through
    the centroid of the current positions, evaluated at each free DOF."""
    comp = dofs[:, 2].astype(int)
    x = dofs[:, 6:9]
    p = x - x.mean(axis=0)
    n = len(comp)
    b = np.zeros((n, 6))
    b[np.arange(n), comp] = 1.0
    # rotation about axis k: e_k x p
    rot = {0: (np.zeros(n), -p[:, 2], p[:, 1]), 1: (p[:, 2], np.zeros(n), -p[:, 0]),
           2: (-p[:, 1], p[:, 0], np.zeros(n))}
    for k in range(3):
        b[:, 3 + k] = np.choose(comp, rot[k])
    return b


def node_blocks_contiguous(dofs):
    """True when every free vertex has all three DOFs, in order (3x3 blocks)."""
    comp = dofs[:, 2].astype(int)
    vert = dofs[:, 1].astype(int)
    if len(comp) % 3:
        return False
    return bool(np.all(comp.reshape(-1, 3) == [0, 1, 2]) and np.all(vert.reshape(-1, 3) == vert[::3, None]))


def block_jacobi(a):
    """The inverted 3x3 diagonal blocks (as the engine's setup_preconditioner);
    every free vertex must carry its three DOFs (node_blocks_contiguous)."""
    n = a.shape[0] // 3
    bsr = a.tobsr(blocksize=(3, 3))
    rows = np.repeat(np.arange(n), np.diff(bsr.indptr))
    on_diagonal = bsr.indices == rows
    blocks = np.zeros((n, 3, 3))
    blocks[rows[on_diagonal]] = bsr.data[on_diagonal]
    inv = np.linalg.inv(blocks)
    m = sp.bsr_matrix((inv, np.arange(n), np.arange(n + 1)), shape=a.shape).tocsr()
    return lambda r: m @ r


def pcg(a, b, apply_m, tolerances, max_iterations):
    """Preconditioned CG from x0 = 0; the iteration and time at which
    |r| <= tol |b| first holds, for each tolerance."""
    t0 = time.perf_counter()
    bnorm = np.linalg.norm(b)
    x = np.zeros_like(b)
    r = b.copy()
    z = apply_m(r)
    p = z.copy()
    rz = r @ z
    reached = {}
    pending = sorted(tolerances, reverse=True)
    it = 0
    while pending and it < max_iterations:
        q = a @ p
        alpha = rz / (p @ q)
        x += alpha * p
        r -= alpha * q
        it += 1
        rel = np.linalg.norm(r) / bnorm
        while pending and rel <= pending[0]:
            reached[pending.pop(0)] = (it, time.perf_counter() - t0)
        z = apply_m(r)
        rz_new = r @ z
        p = z + (rz_new / rz) * p
        rz = rz_new
    for tol in pending:
        reached[tol] = (None, time.perf_counter() - t0)
    return reached


def cycle_products(ml, smoothing_products):
    """One V-cycle's work in fine-level products: per level but the coarsest,
    pre- and post-smoothing (smoothing_products each: a symmetric Gauss-Seidel
    sweep is a forward and a backward sweep, 2; two block-Jacobi sweeps, 2),
    the residual (1) and restriction and prolongation (nnz(P) each); the
    coarsest level's triangular solves counted as dense factors (n^2). PyAMG's
    own cycle_complexity counts one product per smoothing and no transfers."""
    work = 0.0
    for level in ml.levels[:-1]:
        work += (2 * smoothing_products + 1) * level.A.nnz + 2 * level.P.nnz
    n_coarse = ml.levels[-1].A.shape[0]
    work += n_coarse * n_coarse
    return work / ml.levels[0].A.nnz


def matvec_seconds(a, repeats=20):
    x = np.random.default_rng(1).standard_normal(a.shape[0])
    a @ x
    t0 = time.perf_counter()
    for _ in range(repeats):
        a @ x
    return (time.perf_counter() - t0) / repeats


def solvers(a, dofs):
    """(name, setup callable returning (apply_m, info))."""
    blocked = node_blocks_contiguous(dofs)
    if not blocked:
        raise SystemExit("amg_study: a free vertex without all three DOFs; 3x3 blocks assume whole vertices")

    def bj():
        return block_jacobi(a), {"cycle_complexity": 9.0 * a.shape[0] / 3 / a.nnz,
                                 "operator_complexity": 1.0, "levels": 1}

    def amg(ml):
        return ml.aspreconditioner(cycle="V"), {
            "cycle_complexity": cycle_products(ml, 2),
            "pyamg_cycle_complexity": float(ml.cycle_complexity(cycle="V")),
            "operator_complexity": float(ml.operator_complexity()),
            "levels": len(ml.levels),
            "coarsest_dofs": int(ml.levels[-1].A.shape[0])}

    def sa_scalar():
        return amg(pyamg.smoothed_aggregation_solver(a, max_coarse=COARSEST_DOFS, coarse_solver="splu"))

    def sa_rbm(smoother):
        def setup():
            a_b = a.tobsr(blocksize=(3, 3)) if blocked else a
            kw = {} if smoother is None else {"presmoother": smoother, "postsmoother": smoother}
            # max_coarse counts nodes (blocks); below the first level a node carries the 6 modes.
            ml = pyamg.smoothed_aggregation_solver(a_b, B=rigid_body_modes(dofs), max_coarse=COARSEST_DOFS // 6,
                                                   coarse_solver="splu", **kw)
            return amg(ml)
        return setup

    bj_smoother = ("block_jacobi", {"omega": 4.0 / 3.0, "iterations": 2, "withrho": True})
    return [("block-jacobi", bj), ("sa-scalar", sa_scalar), ("sa-rbm", sa_rbm(None)),
            ("sa-rbm-bj", sa_rbm(bj_smoother))]


def rbm_hierarchy(a, dofs):
    a_b = a.tobsr(blocksize=(3, 3)) if node_blocks_contiguous(dofs) else a
    return pyamg.smoothed_aggregation_solver(a_b, B=rigid_body_modes(dofs), max_coarse=COARSEST_DOFS // 6,
                                             coarse_solver="splu")


def refreshed_hierarchy(old, a):
    """The aggregates and prolongators of `old` kept, every operator rebuilt
    as the Galerkin product of `a` (what a Newton solver could do per
    iteration instead of a full setup)."""
    levels = []
    fine = a.tobsr(blocksize=old.levels[0].A.blocksize) if sp.isspmatrix_bsr(old.levels[0].A) else a
    for i, old_level in enumerate(old.levels):
        level = pyamg.multilevel.MultilevelSolver.Level()
        level.A = fine if i == 0 else levels[-1].R @ levels[-1].A @ levels[-1].P
        if i + 1 < len(old.levels):
            level.P, level.R = old_level.P, old_level.R
        levels.append(level)
    ml = pyamg.multilevel.MultilevelSolver(levels, coarse_solver="splu")
    smoother = ("block_gauss_seidel", {"sweep": "symmetric"})
    pyamg.relaxation.smoothing.change_smoothers(ml, smoother, smoother)
    return ml


def lagged_case(args, nu, res, later):
    """tet4: SA with rigid-body modes built at Newton iteration
    args.newton_iterations, used for the systems of later iterations, frozen
    (no setup) or refreshed (Galerkin operators recomputed), against a fresh
    setup and block-Jacobi on the same later system."""
    meta0, a0, _, dofs0 = export(args.bench, args.work, "tet4", nu, res, args.newton_iterations, args.reuse)
    old = rbm_hierarchy(a0, dofs0)
    out = []
    for k in later:
        meta, a, b, dofs = export(args.bench, args.work, "tet4", nu, res, k, args.reuse)
        t_mv = matvec_seconds(a)
        variants = [("block-jacobi", lambda: (block_jacobi(a), None)),
                    ("sa-rbm", lambda: (None, rbm_hierarchy(a, dofs))),
                    ("sa-rbm-frozen", lambda: (None, old)),
                    ("sa-rbm-refreshed", lambda: (None, refreshed_hierarchy(old, a)))]
        for name, setup in variants:
            t0 = time.perf_counter()
            apply_m, ml = setup()
            if ml is not None:
                apply_m = ml.aspreconditioner(cycle="V")
            apply_m(np.zeros(a.shape[0]))
            setup_s = 0.0 if name == "sa-rbm-frozen" else time.perf_counter() - t0
            per_it = 1.0 + (9.0 * a.shape[0] / 3 / a.nnz if ml is None else cycle_products(ml, 2))
            reached = pcg(a, b, apply_m, TOLERANCES, args.max_cg)
            rec = {"element": "tet4", "poisson_ratio": round(meta["poisson_ratio"], 6), "resolution": res,
                   "free_dofs": int(a.shape[0]), "newton_iterations_before": k,
                   "hierarchy_from_newton_iterations": args.newton_iterations if "frozen" in name or
                   "refreshed" in name else k, "method": name, "setup_seconds": setup_s,
                   "matvec_seconds": t_mv, "setup_products": setup_s / t_mv, "products_per_cg_iteration": per_it}
            for tol in TOLERANCES:
                it, secs = reached[tol]
                key = f"{tol:.0e}"
                rec[f"iterations_{key}"] = it
                rec[f"total_products_{key}"] = None if it is None else it * per_it + setup_s / t_mv
            print(f"    lagged {k:2d} {name:17s} setup {setup_s:6.2f} s  it(1e-2) {rec['iterations_1e-02']}  "
                  f"it(1e-6) {rec['iterations_1e-06']}", flush=True)
            out.append(rec)
    return out


def study_case(meta, a, b, dofs, max_iterations):
    t_mv = matvec_seconds(a)
    out = []
    for name, setup in solvers(a, dofs):
        t0 = time.perf_counter()
        apply_m, info = setup()
        apply_m(np.zeros(a.shape[0]))  # PyAMG builds the coarsest solve at the first cycle: setup too
        setup_s = time.perf_counter() - t0
        reached = pcg(a, b, apply_m, TOLERANCES, max_iterations)
        per_it = 1.0 + info["cycle_complexity"]
        rec = {"element": meta["element_type"], "poisson_ratio": round(meta["poisson_ratio"], 6),
               "resolution": meta["resolution"], "free_dofs": int(a.shape[0]), "nonzeros": int(a.nnz),
               "newton_iterations_before": meta["newton_iterations"], "method": name,
               "setup_seconds": setup_s, "matvec_seconds": t_mv, "setup_products": setup_s / t_mv,
               "products_per_cg_iteration": per_it, **info}
        for tol in TOLERANCES:
            it, secs = reached[tol]
            key = f"{tol:.0e}"
            rec[f"iterations_{key}"] = it
            rec[f"solve_seconds_{key}"] = secs
            rec[f"solve_products_{key}"] = None if it is None else it * per_it
            rec[f"total_products_{key}"] = None if it is None else it * per_it + setup_s / t_mv
        print(f"    {name:13s} setup {setup_s:7.2f} s  it(1e-2) {rec['iterations_1e-02']}  "
              f"it(1e-6) {rec['iterations_1e-06']}  solve(1e-6) {rec['solve_seconds_1e-06']:.2f} s  "
              f"cycle {per_it:.2f} products", flush=True)
        out.append(rec)
    return out


def fmt(v, digits=1):
    if v is None:
        return "–"
    if isinstance(v, int):
        return f"{v:,}"
    return f"{v:,.{digits}f}"


def write_markdown(path, records, command, environment, lagged=()):
    lines = ["# Algebraic multigrid for the engine's systems", "",
             f"Made by `{command}` on {environment}.", "",
             "Systems: `snh-gpu-bench hessian twist` (projected stiffness on the free DOFs after "
             f"{records[0]['newton_iterations_before']} Newton updates of load step 1, right-hand side its residual). "
             "CG from zero to |r| ≤ tol |b|. Work in fine-level products: iterations × (1 + preconditioner cost; "
             "block-Jacobi 9n/nnz, AMG one V-cycle: 2+2 smoothing products, residual and transfers on every level, "
             "coarsest solve as dense factors) plus the setup converted by the measured time of one scipy CSR "
             "product on the same matrix. Timings are single-threaded on a shared 2-core machine: iterations and "
             "products are the robust figures.", "",
             "| element | ν | res | free DOF | method | CG it 1e-2 | CG it 1e-6 | setup s | solve s 1e-6 | "
             "products / CG it | work 1e-2 (products, incl. setup) | work 1e-6 (products, incl. setup) | "
             "op. complexity |",
             "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
    for r in records:
        lines.append(
            f"| {r['element']} | {r['poisson_ratio']} | {r['resolution']} | {r['free_dofs']:,} | {r['method']} | "
            f"{fmt(r['iterations_1e-02'])} | {fmt(r['iterations_1e-06'])} | {fmt(r['setup_seconds'], 2)} | "
            f"{fmt(r['solve_seconds_1e-06'], 2)} | {fmt(r['products_per_cg_iteration'], 2)} | "
            f"{fmt(r['total_products_1e-02'], 0)} | {fmt(r['total_products_1e-06'], 0)} | "
            f"{fmt(r['operator_complexity'], 2)} |")
    lines += ["", "## Growth of CG iterations from the smallest to the largest resolution", "",
              "| element | ν | method | it 1e-6 smallest → largest | ratio | free DOF ratio |", "| --- | --- | --- | --- | --- | --- |"]
    keys = sorted({(r["element"], r["poisson_ratio"], r["method"]) for r in records})
    for e, nu, m in keys:
        rs = sorted([r for r in records if (r["element"], r["poisson_ratio"], r["method"]) == (e, nu, m)],
                    key=lambda r: r["free_dofs"])
        if len(rs) < 2 or rs[0]["iterations_1e-06"] is None or rs[-1]["iterations_1e-06"] is None:
            continue
        lines.append(f"| {e} | {nu} | {m} | {rs[0]['iterations_1e-06']} → {rs[-1]['iterations_1e-06']} | "
                     f"{rs[-1]['iterations_1e-06'] / rs[0]['iterations_1e-06']:.2f} | "
                     f"{rs[-1]['free_dofs'] / rs[0]['free_dofs']:.1f} |")
    if lagged:
        lines += ["", "## A hierarchy kept across Newton iterations (tet4, SA with rigid-body modes)", "",
                  "Built at the first system's Newton iterate and used for a later one: frozen (no setup at all) "
                  "or refreshed (aggregates and prolongators kept, Galerkin operators and smoothers rebuilt from "
                  "the later Hessian).", "",
                  "| ν | res | free DOF | system after Newton it | method | hierarchy from it | CG it 1e-2 | "
                  "CG it 1e-6 | setup s | setup (products) | work 1e-2 (products) | work 1e-6 (products) |",
                  "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
        for r in lagged:
            lines.append(
                f"| {r['poisson_ratio']} | {r['resolution']} | {r['free_dofs']:,} | {r['newton_iterations_before']} | "
                f"{r['method']} | {r['hierarchy_from_newton_iterations']} | {fmt(r['iterations_1e-02'])} | "
                f"{fmt(r['iterations_1e-06'])} | {fmt(r['setup_seconds'], 2)} | {fmt(r['setup_products'], 0)} | "
                f"{fmt(r['total_products_1e-02'], 0)} | {fmt(r['total_products_1e-06'], 0)} |")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bench", default="build/snh-gpu-bench")
    ap.add_argument("--work", default="build/amg-study", help="where the exported systems go")
    ap.add_argument("--out-dir", default="bench-results")
    ap.add_argument("--res", default="14,22,31", help="twist resolutions (DOF = 3 (res + 1)^3)")
    ap.add_argument("--hex-res", default=None, help="resolutions of the hex8 reference (default: --res)")
    ap.add_argument("--nu", default="0.45,0.49")
    ap.add_argument("--newton-iterations", type=int, default=2)
    ap.add_argument("--max-cg", type=int, default=20000)
    ap.add_argument("--lag-res", default="", help="tet4 resolutions of the kept-hierarchy experiment (none: skip)")
    ap.add_argument("--lag-iterations", default="3,6", help="later Newton iterates the kept hierarchy is used on")
    ap.add_argument("--reuse", action="store_true", help="reuse exported systems already in --work")
    ap.add_argument("--markdown-only", action="store_true", help="rewrite amg_study.md from amg_study.json")
    args = ap.parse_args()
    if args.markdown_only:
        with open(os.path.join(args.out_dir, "amg_study.json")) as f:
            d = json.load(f)
        write_markdown(os.path.join(args.out_dir, "amg_study.md"), d["records"], d["command"], d["environment"],
                       d.get("kept_hierarchy", ()))
        return
    os.makedirs(args.work, exist_ok=True)
    os.makedirs(args.out_dir, exist_ok=True)
    cases = []
    for nu in [float(v) for v in args.nu.split(",")]:
        for element, res_list in (("tet4", args.res), ("hex8", args.hex_res or args.res)):
            for res in [int(v) for v in res_list.split(",")]:
                cases.append((element, nu, res))
    environment = (f"this machine ({os.cpu_count()} cores), python {platform.python_version()}, "
                   f"numpy {np.__version__}, scipy {scipy.__version__}, pyamg {pyamg.__version__}")
    command = "scripts/amg_study.sh " + " ".join(sys.argv[1:])
    records = []
    for element, nu, res in cases:
        print(f"{element} nu {nu} res {res}", flush=True)
        meta, a, b, dofs = export(args.bench, args.work, element, nu, res, args.newton_iterations, args.reuse)
        records += study_case(meta, a, b, dofs, args.max_cg)
        del a, b, dofs
        # Written after every case, so that a cut-short run still leaves its records.
        with open(os.path.join(args.out_dir, "amg_study.json"), "w") as f:
            json.dump({"command": command, "environment": environment, "records": records}, f, indent=1)
        write_markdown(os.path.join(args.out_dir, "amg_study.md"), records, command, environment)
    lagged = []
    for nu in [float(v) for v in args.nu.split(",")]:
        for res in [int(v) for v in args.lag_res.split(",") if v]:
            print(f"kept hierarchy: tet4 nu {nu} res {res}", flush=True)
            lagged += lagged_case(args, nu, res, [int(v) for v in args.lag_iterations.split(",")])
            with open(os.path.join(args.out_dir, "amg_study.json"), "w") as f:
                json.dump({"command": command, "environment": environment, "records": records,
                           "kept_hierarchy": lagged}, f, indent=1)
            write_markdown(os.path.join(args.out_dir, "amg_study.md"), records, command, environment, lagged)
    print("wrote", os.path.join(args.out_dir, "amg_study.md"))


if __name__ == "__main__":
    main()
