"""Measuring speed against error (tools/speed_vs_error.py is the command line, speed_summary
computes the summary; tools/render_docs.py fills docs/performance.md from it): runs of plate_bench (the solver without FMI, one
JSON line per run, the floor = one solve with the sparse factor of A = M + βΔt²K measured in the
same run), the FMU's wall time through fmpy, the plain Python/SciPy baseline, the refinement
studies and the rule that decides whether a sequence converges (`converges()`)."""

from __future__ import annotations

import json
import math
import subprocess
import time
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from plateimpact.scenes import AMPLITUDE, FREQUENCY, sine

# The two scenes (README, docs/theory.md): the §5.1 forced oscillation (default scene) and the §5.2
# free vibration (static equilibrium under 8600 Pa, released at rest, lower obstacle only).
SINE = {"amplitude": AMPLITUDE, "frequency": FREQUENCY, "gap": 0.1}


FREE = {"initial_load": 8600, "lower_only": 1, "amplitude": 0.0, "gap": 0.1}


OBSTACLE = 0.1


CONTRACTION = 0.75  # a refinement sequence converges if every difference ≤ 0.75 × the previous


# ------------------------------------------------------------------------------------------
# Runs of plate_bench
# ------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Cfg:
    element: str = "argyris"
    nx: int = 14
    ny: int = 5
    dt: float = 1e-5
    modes: int = 0
    engine: str = "auto"

    @property
    def grid(self):
        return f"{self.nx}x{self.ny}"

    def label(self, dt=True):
        s = f"{'Argyris' if self.element == 'argyris' else 'FVS'} {self.nx}×{self.ny}"
        if dt:
            s += f", Δt={fmt_dt(self.dt)}"
        if self.modes:
            s += f", m={self.modes}"
        if self.engine != "auto":
            s += f", engine={self.engine}"
        return s

    def args(self):
        return [
            f"element={self.element}",
            f"nx={self.nx}",
            f"ny={self.ny}",
            f"dt={self.dt!r}",
            f"modes={self.modes}",
            f"engine={self.engine}",
        ]


def fmt_dt(dt):
    m, e = f"{dt:.0e}".split("e")
    return f"{m}e{int(e)}" if m != "1" else f"1e{int(e)}"


def fmt(x, digits=3):
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return "—"
    if x == 0:
        return "0"
    a = abs(x)
    if 1e-3 <= a < 1e4:
        return f"{x:.{digits}g}"
    return f"{x:.{max(digits - 1, 1)}e}".replace("e-0", "e-").replace("e+0", "e")


SERIES_COLUMNS = (
    "time",
    "base",
    "corner_1",
    "corner_2",
    "free_edge_mid",
    "energy",
    "energy_input",
    "energy_dissipated",
    "contact_vertices",
)


class Bench:
    """Runs plate_bench, caches results by configuration, keeps a log of every run.

    The per-step time and the floor used everywhere are timed with the process CPU clock
    (`step_cpu_s`, `floor_cpu_s`; equal to wall time on an idle core): the machine is shared, and
    the wall clock also counts the time the process waited for a core. Of repeated runs the one
    with the smallest step time is kept, with the floor measured in that same run."""

    def __init__(self, path, workdir, verbose=True):
        self.path = str(path)
        self.workdir = Path(workdir)
        self.verbose = verbose
        self.cache = {}
        self.log = []
        self.count = 0

    @staticmethod
    def _key(cfg, scene, horizon, comm, series):
        return (cfg, tuple(sorted(scene.items())), horizon, comm, series)

    def _once(self, cfg, scene, horizon, comm, series):
        steps = max(1, round(horizon / cfg.dt))
        self.count += 1
        args = [self.path, *cfg.args(), f"steps={steps}"]
        args += [f"{k}={v}" for k, v in scene.items()]
        if comm is not None:
            args.append(f"comm={comm!r}")
        if cfg.nx * cfg.ny >= 250:  # large meshes: a shorter floor measurement (~10 s saved)
            args.append("floor_repeats=400")
        csv = self.workdir / f"series_{self.count}.csv"
        if series:
            args.append(f"series={csv}")
        t0 = time.perf_counter()
        proc = run_binary(args)
        elapsed = time.perf_counter() - t0
        if proc.returncode != 0:
            raise RuntimeError(f"{' '.join(args)} failed: {proc.stderr.strip()}")
        r = json.loads(proc.stdout.strip().splitlines()[-1])
        r["process_s"] = elapsed
        r["step_wall_s"] = r["step_s"]
        r["floor_wall_s"] = r["floor_solve_s"]
        r["step_s"] = r.get("step_cpu_s", r["step_s"])  # older plate_bench: wall only
        r["floor_solve_s"] = r.get("floor_cpu_s", r["floor_solve_s"])
        r["step_over_floor"] = r["step_s"] / r["floor_solve_s"]
        if series:
            data = np.loadtxt(csv, delimiter=",", skiprows=1, ndmin=2)
            r["series"] = {c: data[:, i] for i, c in enumerate(SERIES_COLUMNS)}
            csv.unlink()
        if self.verbose:
            print(
                f"  [{self.count:3d}] {cfg.label()} {scene_name(scene)} {horizon:g}s: "
                f"{r['engine']}, {1e6 * r['step_s']:.2f} us/step (wall {1e6 * r['step_wall_s']:.2f}), "
                f"floor {1e6 * r['floor_solve_s']:.2f} us, {elapsed:.1f} s",
                flush=True,
            )
        return r

    def _store(self, key, cfg, runs):
        best = min(runs, key=lambda r: r["step_s"])
        best["repeats"] = len(runs)
        best["floors"] = [r["floor_solve_s"] for r in runs]
        best["cfg"] = cfg
        best["wall_per_sim_s"] = best["step_s"] / cfg.dt
        best["rtf"] = cfg.dt / best["step_s"]
        self.log.append({k: v for k, v in best.items() if k not in ("series", "cfg")})
        self.cache[key] = best
        return best

    def run(self, cfg: Cfg, scene: dict, horizon: float, comm=None, series=False, repeats=1):
        key = self._key(cfg, scene, horizon, comm, series)
        if key in self.cache and self.cache[key]["repeats"] >= repeats:
            return self.cache[key]
        return self._store(key, cfg, [self._once(cfg, scene, horizon, comm, series) for _ in range(repeats)])

    def run_group(self, items, rounds):
        """Runs that are compared with each other, interleaved round by round so that a busy
        spell of the shared machine hits all of them alike. items: (cfg, scene, horizon, comm)."""
        runs = {i: [] for i in range(len(items))}
        for _ in range(rounds):
            for i, (cfg, scene, horizon, comm) in enumerate(items):
                runs[i].append(self._once(cfg, scene, horizon, comm, False))
        return [
            self._store(self._key(cfg, scene, horizon, comm, False), cfg, runs[i])
            for i, (cfg, scene, horizon, comm) in enumerate(items)
        ]

    def export(self, cfg: Cfg, directory):
        Path(directory).mkdir(parents=True, exist_ok=True)
        proc = run_binary([self.path, *cfg.args(), f"export={directory}"])
        if proc.returncode != 0:
            raise RuntimeError(f"export failed: {proc.stderr.strip()}")
        return json.loads(proc.stdout.strip().splitlines()[-1])


def run_binary(args, attempts=40):
    """subprocess.run, retried while the binary cannot be executed (a rebuild relinking it)."""
    for attempt in range(attempts):
        try:
            return subprocess.run(args, capture_output=True, text=True)
        except OSError:
            if attempt == attempts - 1:
                raise
            time.sleep(3)


def scene_name(scene):
    return "sine" if scene.get("amplitude", 0) else "§5.2"


# ------------------------------------------------------------------------------------------
# Exported matrices: first frequency (mesh accuracy yardstick) and the Python/SciPy baseline
# ------------------------------------------------------------------------------------------
def load_export(directory):
    import scipy.io

    d = Path(directory)
    mass = scipy.io.mmread(d / "mass.mtx").tocsr()
    stiffness = scipy.io.mmread(d / "stiffness.mtx").tocsr()
    vectors = np.loadtxt(d / "vectors.txt", ndmin=2)
    contact = np.loadtxt(d / "contact_dofs.txt", dtype=int, ndmin=1)
    probes = []
    for line in (d / "probes.txt").read_text().splitlines():
        row = np.zeros(mass.shape[0])
        for token in line.split():
            i, c = token.split(":")
            row[int(i)] += float(c)
        probes.append(row)
    return dict(M=mass, K=stiffness, F=vectors[:, 0], M1=vectors[:, 1], contact=contact, probes=np.array(probes))


def first_frequency(bench, cfg, workdir):
    """Lowest natural frequency of the clamped plate (Hz), from the exported M, K (SciPy)."""
    from scipy.sparse.linalg import eigsh

    d = Path(workdir) / f"export_{cfg.element}_{cfg.grid}"
    bench.export(cfg, d)
    e = load_export(d)
    vals = eigsh(e["K"].tocsc(), k=1, M=e["M"].tocsc(), sigma=0.0, which="LM", return_eigenvectors=False)
    return float(np.sqrt(vals.min()) / (2 * np.pi)), int(e["M"].shape[0])


def python_baseline(
    export_dir, dt, steps, comm, split, beta=0.5, amplitude=AMPLITUDE, frequency=FREQUENCY, gap=OBSTACLE
):
    """The same three-level scheme as NewmarkScheme (docs/theory.md §3–4) in plain
    Python/SciPy: A = M + βΔt²K factored once (scipy.sparse.linalg.factorized), the free
    solution every step, and on steps where it violates a bound the full step QP
    min ½wᵀAw − wᵀb, obstacle − z⁺ ≤ w_C ≤ obstacle − z⁺, solved by OSQP (set up once, q/l/u
    updated per step, warm-started, polished). The base input follows the FMU's
    value + derivative interpolation inside each communication step, as plate_bench feeds it.
    `split`: the step count (a whole number of communication steps) at which the wall clock is
    also read, to split free flight from the contact phase."""
    import osqp
    import scipy.sparse as sp
    from scipy.sparse.linalg import factorized

    e = load_export(export_dir)
    M, K, M1, C, P = e["M"], e["K"], e["M1"], e["contact"], e["probes"]
    n, m = M.shape[0], len(C)
    t_setup = time.perf_counter()
    A = (M + beta * dt * dt * K).tocsc()
    solve = factorized(A)
    # OSQP on A as it is fails (A's diagonal spans ~1e-10 … 1e-1 on the default mesh): solve
    # for x = D⁻¹w with the Jacobi scaling D = diag(A)^-½, the usual preconditioning.
    dg = 1.0 / np.sqrt(A.diagonal())
    D = sp.diags(dg)
    H = sp.triu(D @ A @ D).tocsc()
    Cx = sp.csc_matrix((dg[C], (np.arange(m), C)), shape=(m, n))
    settings = dict(verbose=False, eps_abs=1e-9, eps_rel=1e-9, polishing=True, max_iter=100000)
    qp = osqp.OSQP()
    qp.setup(H, np.zeros(n), Cx, -np.ones(m), np.ones(m), **settings)
    setup_s = time.perf_counter() - t_setup
    unscaled_status = None

    w = np.zeros(n)
    w_prev = w.copy()
    kw = K @ w
    z = z_prev = 0.0
    per = max(1, round(comm / dt))
    rows = [(0.0, *(P @ w + z))]
    qp_steps, qp_s, statuses = 0, 0.0, {}
    clock = time.process_time  # CPU time, like plate_bench's step_cpu_s (shared machine)
    t0 = clock()
    t0_wall = time.perf_counter()
    t_split = None
    done = 0
    while done < steps:
        if done == split:
            t_split = clock() - t0
        t = done * dt
        v, d1, d2 = sine(amplitude, frequency, t)
        for k in range(1, min(per, steps - done) + 1):
            s = k * dt
            z_next = v + s * (d1 + 0.5 * s * d2)
            rhs = -(dt * dt) * kw - (z_next - 2 * z + z_prev) * M1
            w_next = 2 * w - w_prev + solve(rhs)
            y = w_next[C]
            lo, hi = -gap - z_next, gap - z_next
            if (y < lo).any() or (y > hi).any():
                tq = clock()
                b = A @ w_next
                qp.update(q=-(D @ b), l=np.full(m, lo), u=np.full(m, hi))
                r = qp.solve()
                statuses[r.info.status] = statuses.get(r.info.status, 0) + 1
                w_next = dg * r.x
                qp_steps += 1
                qp_s += clock() - tq
                if unscaled_status is None:  # once, untimed: what OSQP says on the unscaled QP
                    tu = clock()
                    raw = osqp.OSQP()
                    raw.setup(
                        sp.triu(A).tocsc(),
                        -b,
                        sp.csc_matrix((np.ones(m), (np.arange(m), C)), shape=(m, n)),
                        np.full(m, lo),
                        np.full(m, hi),
                        **settings,
                    )
                    unscaled_status = raw.solve().info.status
                    t0 += clock() - tu
            w_prev, w = w, w_next
            kw = K @ w
            z_prev, z = z, z_next
        done += min(per, steps - done)
        rows.append((done * dt, *(P @ w + z)))
    wall = clock() - t0
    real = time.perf_counter() - t0_wall
    rows = np.array(rows)
    t_split = wall if t_split is None else t_split
    return dict(
        dofs=n,
        steps=steps,
        setup_s=setup_s,
        cpu_s=wall,
        wall_s=real,
        step_s=wall / steps,
        qp_steps=qp_steps,
        qp_step_s=qp_s / max(qp_steps, 1),
        free_phase_step_s=t_split / split,
        contact_phase_step_s=(wall - t_split) / max(steps - split, 1),
        statuses=statuses,
        unscaled_status=unscaled_status,
        time=rows[:, 0],
        corner_1=rows[:, 1],
    )


def fmu_wall(fmu, horizon, comm=1e-4, **parameters):
    """Wall time of the default scene through the FMU (fmpy FMU2Slave), instantiation included."""
    from plateimpact import PlateImpactFMU, sine

    n = round(horizon / comm)
    t0, c0 = time.perf_counter(), time.process_time()
    with PlateImpactFMU(fmu, **parameters) as plate:
        t1 = time.perf_counter()
        for k in range(n):
            plate.step(comm, base=sine(SINE["amplitude"], SINE["frequency"], k * comm))
            plate.outputs()
        t2 = time.perf_counter()
    return dict(total_s=time.perf_counter() - t0, cpu_s=time.process_time() - c0, init_s=t1 - t0, stepping_s=t2 - t1)


# ------------------------------------------------------------------------------------------
# Quantities, convergence, errors
# ------------------------------------------------------------------------------------------
def first_impact(r):
    s = r["series"]
    hit = np.nonzero(s["contact_vertices"] > 0)[0]
    return float(s["time"][hit[0]]) if hit.size else float("nan")


def traj_difference(a, b, until):
    """max |corner_1(a) − corner_1(b)| over the common output times ≤ until, relative to
    max |corner_1(b)| there."""
    ta = np.round(a["series"]["time"], 9)
    tb = np.round(b["series"]["time"], 9)
    common, ia, ib = np.intersect1d(ta, tb, return_indices=True)
    keep = common <= until + 1e-12
    ca = a["series"]["corner_1"][ia[keep]]
    cb = b["series"]["corner_1"][ib[keep]]
    return float(np.max(np.abs(ca - cb)) / np.max(np.abs(cb)))


def converges(diffs, resolution):
    """The rule: at least two successive differences, each ≤ CONTRACTION × the previous one, or
    within its resolution (e.g. the output step for an impact time); a difference smaller than
    its own resolution counts as its resolution when the next one is compared with it."""
    if len(diffs) < 2 or not all(np.isfinite(diffs)):
        return False
    return all(
        d2 <= max(CONTRACTION * max(d1, r1), r2)
        for d1, d2, r1, r2 in zip(diffs[:-1], diffs[1:], resolution[:-1], resolution[1:])
    )


def refinement_factors(cfgs):
    """How much finer each member is than the previous one (Δt ratio, or cells ratio in x)."""
    return [a.dt / b.dt if a.dt != b.dt else b.nx / a.nx for a, b in zip(cfgs[:-1], cfgs[1:])]


def sequence_report(name, labels, values, diffs, resolution, unit="", factors=None):
    ok = converges(diffs, resolution)
    ratios = [d2 / d1 if d1 > 0 else float("nan") for d1, d2 in zip(diffs[:-1], diffs[1:])]
    # observed order from the last two differences: d_i ~ C step^p, factor f between members
    orders = []
    if factors is not None:
        for i, r in enumerate(ratios):
            f = math.sqrt(factors[i] * factors[i + 1])
            orders.append(math.log(1 / r) / math.log(f) if r > 0 and f > 1 else float("nan"))
    # a-posteriori uncertainty of the finest member: geometric tail of the last contraction
    q = ratios[-1] if ratios else float("nan")
    tail = diffs[-1] * q / (1 - q) if ok and ratios and 0 <= q < 1 else float("nan")
    if ok and ratios and q == 0:
        tail = max(resolution[-1], diffs[-1])
    return dict(
        name=name,
        labels=labels,
        values=values,
        diffs=list(map(float, diffs)),
        resolution=list(map(float, resolution)),
        ratios=ratios,
        converges=ok,
        tail=float(tail),
        unit=unit,
        orders=orders,
    )


# ------------------------------------------------------------------------------------------
# The plan
# ------------------------------------------------------------------------------------------
def make_plan(quick):
    A, F = "argyris", "fvs"
    if quick:
        return dict(
            quick=True,
            scaling=[(A, 7, 3), (F, 10, 4)],
            scaling_steps=2000,
            scaling_repeats=1,
            # the suite's smoke run (python_tests/test_speed_report.py) asserts no timing: each
            # comparison timed once, and the short study's rows timed from their series runs
            free_rounds=1,
            baseline_rounds=1,
            baseline_tries=1,
            short_timing_runs=False,
            short_T=0.06,
            pre_impact=0.045,
            short=[Cfg(A, 7, 3, dt) for dt in (1e-3, 1e-4, 1e-5)]
            + [Cfg(F, nx, ny, 1e-5) for nx, ny in ((10, 4), (20, 7), (40, 14))]
            + [Cfg(A, 7, 3, 1e-5, modes=m) for m in (10, 40)],
            short_ref=Cfg(F, 40, 14, 1e-5),
            short_seqs=[
                ("Δt, Argyris 7×3", [Cfg(A, 7, 3, dt) for dt in (1e-3, 1e-4, 1e-5)], "dt"),
                ("h, FVS, Δt=1e-5", [Cfg(F, nx, ny, 1e-5) for nx, ny in ((10, 4), (20, 7), (40, 14))], "h"),
            ],
            free_T=0.5,
            free=[Cfg(A, 7, 3, dt) for dt in (1e-4, 1e-5, 5e-6)]
            + [Cfg(A, 7, 3, 1e-5, modes=m) for m in (10, 40, 120)]
            + [Cfg(A, 7, 3, 1e-5, engine="sparse")],
            free_seqs=[("Δt, Argyris 7×3", [Cfg(A, 7, 3, dt) for dt in (1e-4, 1e-5, 5e-6)])],
            free_modes_base=Cfg(A, 7, 3, 1e-5),
            free_modes=(10, 40, 120),
            long_T=0.3,
            long=[Cfg(A, 7, 3, 1e-5), Cfg(A, 7, 3, 1e-5, engine="sparse"), Cfg(A, 7, 3, 1e-5, modes=40)],
            default=Cfg(A, 7, 3, 1e-4),
            default_T=0.05,
            default_repeats=1,
            baseline=dict(cfg=Cfg(A, 7, 3, 1e-4), steps=600, comm=1e-4, split=490),
            pairs=[((A, 7, 3), (F, 20, 7))],
            modes_setup=Cfg(F, 20, 7, 1e-5, modes=40),
            freq_grids=[(A, 7, 3), (F, 10, 4), (F, 20, 7), (F, 40, 14)],
        )
    grids_a = [(7, 3), (14, 5), (28, 10)]
    grids_f = [(20, 7), (40, 14), (80, 28)]
    decades = (1e-3, 1e-4, 1e-5, 1e-6)
    short = []
    for nx, ny in grids_a:
        short += [Cfg(A, nx, ny, dt) for dt in decades]
    for nx, ny in grids_f:
        short += [Cfg(F, nx, ny, dt) for dt in decades]
    short += [Cfg(A, 14, 5, dt, modes=m) for dt in (1e-5, 1e-6) for m in (10, 40, 160, 400)]
    short += [Cfg(F, 20, 7, 1e-5, modes=m) for m in (10, 40, 160)]
    fine_dt = (1e-3, 1e-4, 1e-5, 5e-6, 2e-6, 1e-6, 5e-7)
    free = [Cfg(A, 14, 5, dt) for dt in fine_dt] + [Cfg(A, 7, 3, dt) for dt in fine_dt]
    free += [Cfg(F, 20, 7, dt) for dt in fine_dt[:-1]]
    free += [Cfg(A, 28, 10, dt) for dt in (1e-3, 1e-4, 1e-5)] + [Cfg(F, 40, 14, dt) for dt in (1e-4, 1e-5)]
    free += [Cfg(A, 14, 5, 1e-5, engine="sparse")]
    modes_a = (10, 20, 40, 80, 160, 300, 500, 650, 700, 733)
    free += [Cfg(A, 14, 5, 1e-5, modes=m) for m in modes_a]
    free += [Cfg(A, 14, 5, 1e-6, modes=m) for m in (40, 160, 650)]
    free += [Cfg(F, 20, 7, 1e-5, modes=m) for m in (10, 40, 160, 320, 440)]
    return dict(
        quick=False,
        scaling=[(A, 7, 3), (A, 14, 5), (A, 28, 10), (A, 56, 20), (F, 10, 4), (F, 20, 7), (F, 40, 14), (F, 80, 28)],
        scaling_steps=6000,
        scaling_repeats=3,
        free_rounds=3,  # the modes-against-exact speed-ups (study_free)
        baseline_rounds=3,  # the C++ runs the Python/SciPy baseline is compared with
        baseline_tries=2,  # the baseline's own runs, the fastest kept
        short_timing_runs=True,  # study_short: each configuration timed again without its series
        short_T=0.06,
        pre_impact=0.045,
        short=short,
        short_ref=Cfg(A, 28, 10, 1e-6),
        short_seqs=[
            ("Δt, Argyris 14×5", [Cfg(A, 14, 5, dt) for dt in decades], "dt"),
            ("Δt, FVS 20×7", [Cfg(F, 20, 7, dt) for dt in decades], "dt"),
            ("h, Argyris, Δt=1e-6", [Cfg(A, nx, ny, 1e-6) for nx, ny in grids_a], "h"),
            ("h, FVS, Δt=1e-6", [Cfg(F, nx, ny, 1e-6) for nx, ny in grids_f], "h"),
        ],
        free_T=0.5,
        free=free,
        free_seqs=[
            ("Δt, Argyris 14×5", [Cfg(A, 14, 5, dt) for dt in fine_dt]),
            ("Δt, Argyris 7×3", [Cfg(A, 7, 3, dt) for dt in fine_dt]),
            ("Δt, FVS 20×7", [Cfg(F, 20, 7, dt) for dt in fine_dt[:-1]]),
            ("h, Argyris, Δt=1e-5", [Cfg(A, nx, ny, 1e-5) for nx, ny in grids_a]),
            ("h, FVS, Δt=1e-5", [Cfg(F, nx, ny, 1e-5) for nx, ny in grids_f[:2]]),
        ],
        free_modes_base=Cfg(A, 14, 5, 1e-5),
        free_modes=modes_a,
        long_T=1.0,
        long=[
            Cfg(A, 14, 5, 1e-5),
            Cfg(A, 14, 5, 1e-5, engine="sparse"),
            Cfg(A, 14, 5, 5e-6),
            Cfg(A, 7, 3, 1e-5),
            Cfg(F, 20, 7, 1e-5),
        ]
        + [Cfg(A, 14, 5, 1e-5, modes=m) for m in (10, 40, 160, 400, 650)],
        default=Cfg(A, 14, 5, 1e-5),
        default_T=1.0,
        default_repeats=3,
        baseline=dict(cfg=Cfg(A, 14, 5, 1e-5), steps=6000, comm=1e-4, split=4900),
        pairs=[((A, 7, 3), (F, 20, 7)), ((A, 14, 5), (F, 40, 14)), ((A, 28, 10), (F, 80, 28))],
        modes_setup=Cfg(F, 40, 14, 1e-5, modes=40),
        freq_grids=[(A, 7, 3), (A, 14, 5), (A, 28, 10), (A, 56, 20), (F, 10, 4), (F, 20, 7), (F, 40, 14), (F, 80, 28)],
    )


# ------------------------------------------------------------------------------------------
# Studies
# ------------------------------------------------------------------------------------------
def study_scaling(bench, plan):
    rows = []
    for element, nx, ny in plan["scaling"]:
        cells = nx * ny
        steps = plan["scaling_steps"] if cells <= 600 else 600
        small = cells <= 150
        rounds = plan["scaling_repeats"] if small else (2 if cells <= 600 else 1)
        engines = ["auto", "sparse", "modal"] if small else ["auto"]
        items = [(Cfg(element, nx, ny, 1e-5, engine=e), SINE, steps * 1e-5, None) for e in engines]
        res = dict(zip(engines, bench.run_group(items, rounds)))
        if "sparse" not in res:
            res["sparse"] = (
                res["auto"]
                if res["auto"]["engine"] == "sparse"
                else bench.run(Cfg(element, nx, ny, 1e-5, engine="sparse"), SINE, steps * 1e-5)
            )
        rows.append(
            dict(
                element=element,
                nx=nx,
                ny=ny,
                dofs=res["auto"]["dofs"],
                steps=steps,
                rounds=rounds,
                auto=res["auto"],
                sparse=res["sparse"],
                modal=res.get("modal"),
            )
        )
    return rows


def study_short(bench, plan):
    # errors from runs that write every step (comm = Δt, so t₁ is resolved to Δt); their timing
    # would include the CSV writing, so each configuration is timed in a second run without
    # series at the FMU's communication step (1e-4 s, or Δt if larger) — but in the quick plan,
    # whose times nobody reads
    runs = {c: bench.run(c, SINE, plan["short_T"], comm=c.dt, series=True) for c in plan["short"]}
    timing = (
        {c: bench.run(c, SINE, plan["short_T"], comm=max(c.dt, 1e-4)) for c in plan["short"]}
        if plan["short_timing_runs"]
        else runs
    )
    ref = plan["short_ref"]
    until = plan["pre_impact"]
    seqs = {"trajectory": [], "impact": []}
    for name, cfgs, kind in plan["short_seqs"]:
        rs = [runs[c] for c in cfgs]
        labels = [c.label() for c in cfgs]
        dtraj = [traj_difference(a, b, until) for a, b in zip(rs[:-1], rs[1:])]
        seqs["trajectory"].append(
            sequence_report(
                name, labels, [None] * len(rs), dtraj, [1e-12] * len(dtraj), "relative", refinement_factors(cfgs)
            )
        )
        t1 = [first_impact(r) for r in rs]
        dt1 = [abs(b - a) for a, b in zip(t1[:-1], t1[1:])]
        res = [max(a.dt, b.dt) for a, b in zip(cfgs[:-1], cfgs[1:])]
        seqs["impact"].append(sequence_report(name, labels, t1, dt1, res, "s", refinement_factors(cfgs)))
    quantities = {}
    for q in ("trajectory", "impact"):
        ok = all(s["converges"] for s in seqs[q])
        # uncertainty of the reference: the worst Δt tail among the Δt sequences that end at the
        # reference's Δt, plus the worst h tail among the h sequences that end at the reference
        dt_tails = [
            s["tail"]
            for s, (_, cfgs, kind) in zip(seqs[q], plan["short_seqs"])
            if kind == "dt" and cfgs[-1].dt == ref.dt
        ]
        h_tails = [
            s["tail"] for s, (_, cfgs, kind) in zip(seqs[q], plan["short_seqs"]) if kind == "h" and cfgs[-1] == ref
        ]
        unc = max(dt_tails, default=0.0) + max(h_tails, default=0.0)
        quantities[q] = dict(
            converges=ok, sequences=seqs[q], ref=ref.label(), ref_uncertainty=unc if ok else float("nan")
        )
    t1_ref = first_impact(runs[ref])
    rows = []
    for c, r in runs.items():
        row = dict(cfg=c, run=timing[c], t1=first_impact(r))
        row["err_trajectory"] = (
            traj_difference(r, runs[ref], until) if quantities["trajectory"]["converges"] and c != ref else None
        )
        row["err_impact"] = abs(row["t1"] - t1_ref) if quantities["impact"]["converges"] and c != ref else None
        rows.append(row)
    quantities["impact"]["ref_value"] = t1_ref
    return dict(rows=rows, quantities=quantities, runs=runs)


def study_free(bench, plan):
    base = plan["free_modes_base"]
    # the modes-against-exact speed-ups are headline numbers: exact and modes interleaved, 3 rounds
    # (the quick plan: 1)
    group = [
        c
        for c in plan["free"]
        if (c.element, c.nx, c.ny, c.dt, c.engine) == (base.element, base.nx, base.ny, base.dt, "auto")
    ]
    runs = dict(
        zip(group, bench.run_group([(c, FREE, plan["free_T"], max(c.dt, 1e-4)) for c in group], plan["free_rounds"]))
    )
    for c in plan["free"]:
        if c not in runs:
            runs[c] = bench.run(c, FREE, plan["free_T"], comm=max(c.dt, 1e-4))
    seqs = []
    for name, cfgs in plan["free_seqs"]:
        e = [runs[c]["energy_dissipated"] for c in cfgs]
        d = [abs(b - a) for a, b in zip(e[:-1], e[1:])]
        seqs.append(
            sequence_report(name, [c.label() for c in cfgs], e, d, [1e-6] * len(d), "J", refinement_factors(cfgs))
        )
    ok = all(s["converges"] for s in seqs)
    exact = runs[base]
    modes = []
    for c, r in runs.items():
        if c.modes:
            ex = runs.get(replace(c, modes=0))
            if ex is None:
                continue
            modes.append(
                dict(
                    cfg=c,
                    run=r,
                    exact=ex,
                    rel_err=(r["energy_dissipated"] - ex["energy_dissipated"]) / ex["energy_dissipated"],
                    speedup=ex["step_s"] / r["step_s"],
                )
            )
    sparse = runs.get(replace(base, engine="sparse"))
    roundoff = abs(sparse["energy_dissipated"] - exact["energy_dissipated"]) if sparse else None
    return dict(runs=runs, sequences=seqs, converges=ok, modes=modes, roundoff=roundoff, base=base)


def study_long(bench, plan):
    runs = {c: bench.run(c, SINE, plan["long_T"], comm=1e-4, series=True) for c in plan["long"]}
    rows = []
    for c, r in runs.items():
        s = r["series"]
        rel = np.abs(s["corner_1"] - s["base"])
        period = 1.0 / SINE["frequency"]
        k = np.floor(s["time"] / period + 1e-9).astype(int)
        periods = [rel[k == i].max() for i in range(1, int(plan["long_T"] / period)) if (k == i).any()]
        rows.append(
            dict(
                cfg=c,
                run=r,
                max_corner=float(np.max(np.abs(s["corner_1"]))),
                max_corner_any=float(max(np.max(np.abs(s["corner_1"])), np.max(np.abs(s["corner_2"])))),
                period_envelope=float(np.mean(periods)) if periods else float("nan"),
                energy_dissipated=r["energy_dissipated"],
            )
        )
    pinned = all(abs(row["max_corner_any"] - OBSTACLE) < 1e-9 for row in rows)
    by = {row["cfg"]: row for row in rows}
    base = plan["long"][0]
    sparse = by.get(replace(base, engine="sparse"))
    noise = (
        (abs(sparse["period_envelope"] - by[base]["period_envelope"]) / by[base]["period_envelope"])
        if sparse
        else float("nan")
    )
    half = by.get(replace(base, dt=base.dt / 2))
    dt_change = (
        (abs(half["period_envelope"] - by[base]["period_envelope"]) / by[base]["period_envelope"])
        if half
        else float("nan")
    )
    return dict(rows=rows, pinned=pinned, roundoff_rel=noise, dt_half_rel=dt_change, base=base)
