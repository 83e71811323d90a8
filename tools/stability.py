"""The stability stress matrix of PlateImpact: ONE table of cases, the runner and the checks.

Shared by python_tests/test_stability.py (short horizons) and tools/stability_report.py
(the same cases, optionally longer with --full, written to docs/stability.md). Nothing here
knows pytest.

The matrix varies one factor at a time around a base case, the paper's §5.1 forced
oscillation on the default plate:

    1.2 x 0.4 x 0.01 m steel, 14 x 5 cells (Argyris), obstacles at -/+ gap with gap = 0.1 m,
    base z(t) = 0.9 gap sin(2 pi f t) with f = 10 Hz, dt = 1e-5 s, beta = 1/2, no load.

The base amplitude is 0.9 of the gap in every case (0.09 m at the default gap, as in the
paper), so shrinking the gap keeps the clamp inside it; "base at 0.99 of the gap" is its own
case. Special cases: beta = 0 at 0.9x and 1.1x the stability bound, a plate that starts pressed
onto the lower obstacle, load steps of 1e5 Pa.

Every case is driven as a co-simulation master drives the FMU (fmpy's FMU2Slave): the inputs
are given at each communication point with their first and second time derivatives, and the
outputs are read after every communication step. Every case that runs checks (see
`failures`): no NaN/Inf in any output; no probe vertex past an obstacle by more than 1e-12 m
(with restitution e > 0: by more than 2 e * 30 m/s * dt, the law's own overshoot: it holds
(u_{n+1} + e u_{n-1})/(1+e) on the obstacle, so u_{n+1} may pass it by e times the travel of
two steps, docs/theory.md §12); the energy ledger energy = E0 + energy_input - energy_dissipated -
energy_damped closes to 1e-9 of the largest energy seen; energy_dissipated never decreases
(with the paper's law; with e > 0 or a singular mass it is a net amount); every contact QP
converged (KKT residual <= 1e-10); and contact actually happened (otherwise the case proves
nothing about contact). The laws beyond the paper (singular mass, restitution, Rayleigh
damping) have their own rows.
"""

from __future__ import annotations

import math
import re
import time
from dataclasses import dataclass, field
from typing import Optional

from fmpy.fmi1 import FMICallException  # fmpy raises this one for FMI 2.0 calls too

# The one FMU driver, shared with the examples.
from plateimpact.driver import PlateImpactFMU
from plateimpact.scenes import sine

# ---------------------------------------------------------------------------------------------
# Limits of the checks (the numbers)

PENETRATION_LIMIT = 1e-12  # m, a vertex past an obstacle
PENETRATION_SPEED = 30.0  # m/s, bound of the vertex speeds in the matrix (base 5.7 m/s, plate)
LEDGER_LIMIT = 1e-9  # |E - (E0 + input - dissipated)| / largest |E| seen
KKT_LIMIT = 1e-10  # relative KKT residual of every per-step QP

# ---------------------------------------------------------------------------------------------
# Input laws: callables t -> (value, first derivative, second derivative) at a communication
# point; the FMU follows value + d1 s + d2 s^2 / 2 inside the step.


@dataclass(frozen=True)
class Sine:
    amplitude: float
    frequency: float

    def __call__(self, t):
        return sine(self.amplitude, self.frequency, t)

    def describe(self):
        return f"{self.amplitude:g} sin(2π·{self.frequency:g} t) m"


@dataclass(frozen=True)
class Steps:
    """Piecewise constant: value levels[j] from times[j] on (times as fractions of the horizon),
    held through each communication step (derivatives 0). The switching times are rounded to
    communication points."""

    levels: tuple  # Pa
    fractions: tuple  # of the horizon, increasing, first 0

    def bind(self, horizon):
        return _BoundSteps(self, horizon)

    def describe(self):
        parts = [f"{v:g} Pa from {f:g} T" for v, f in zip(self.levels, self.fractions)]
        return "steps: " + ", ".join(parts)


@dataclass(frozen=True)
class _BoundSteps:
    steps: Steps
    horizon: float

    def __call__(self, t):
        value = self.steps.levels[0]
        for v, f in zip(self.steps.levels, self.steps.fractions):
            if t >= f * self.horizon * (1 - 1e-12):
                value = v
        return (value, 0.0, 0.0)


@dataclass(frozen=True)
class Constant:
    value: float

    def __call__(self, t):
        return (self.value, 0.0, 0.0)

    def describe(self):
        return f"{self.value:g} Pa" if self.value else "0"


# ---------------------------------------------------------------------------------------------
# The table


@dataclass(frozen=True)
class Case:
    name: str
    varied: str  # what differs from the base case (for the report)
    params: dict  # FMU parameters set in initialization mode (beyond defaults)
    base: Sine
    load: object  # Constant or Steps
    # internal steps of the fast horizon (the test): 0.1 s at dt = 1e-5 s for most cases, the first
    # impacts (0.05 s on); issue 54 halved it from 0.2 s, the longer horizons are --full's
    # (docs/stability.json)
    steps: int
    per_comm: int = 10  # internal steps per communication step
    full_steps: Optional[int] = None  # internal steps with --full (report); default: steps
    bound_factor: Optional[float] = None  # beta < 1/4: dt = factor x the FMU's stability bound
    refused: bool = False  # initialization must fail (fmi2Error naming dt and the bound)
    starts_in_contact: bool = False  # the initial static state must already touch an obstacle

    @property
    def restitution(self):
        return float(self.params.get("restitution", 0.0))

    @property
    def net_dissipation(self):
        """energy_dissipated is a net amount (may decrease): restitution > 0 or a singular mass."""
        return self.restitution > 0 or int(self.params.get("mass", 1)) != 1

    @property
    def penetration_limit(self):
        """Restitution e > 0 constrains (u_{n+1} + e u_{n-1})/(1+e): u_{n+1} may pass the obstacle
        by e times the travel of two steps."""
        e = self.restitution
        return PENETRATION_LIMIT if e == 0 else 2 * e * PENETRATION_SPEED * self.params.get("dt", DT0)

    @property
    def obstacles(self):
        return (self.params.get("obstacle_lower", -0.1), self.params.get("obstacle_upper", 0.1))


GAP = 0.1  # m, default obstacles at -/+ GAP
AMPLITUDE = 0.9  # base amplitude as a fraction of the gap
F0 = 10.0  # Hz, base-case frequency
DT0 = 1e-5  # s, base-case time step
COARSE = {"nx": 7, "ny": 3}  # the beta = 0 cases: larger bound, 1e5 steps stay cheap


def _case(
    name,
    varied,
    *,
    gap=GAP,
    amplitude=AMPLITUDE,
    frequency=F0,
    dt=DT0,
    load=Constant(0.0),
    steps,
    per_comm=10,
    full_steps=None,
    bound_factor=None,
    refused=False,
    starts_in_contact=False,
    **params,
):
    p = {"obstacle_lower": -gap, "obstacle_upper": gap, **params}
    if bound_factor is None:
        p["dt"] = dt
    return Case(
        name=name,
        varied=varied,
        params=p,
        base=Sine(amplitude * gap, frequency),
        load=load,
        steps=steps,
        per_comm=per_comm,
        full_steps=full_steps,
        bound_factor=bound_factor,
        refused=refused,
        starts_in_contact=starts_in_contact,
    )


CASES = [
    _case("base", "— (base case)", steps=10_000, full_steps=100_000),
    # obstacles: the gap (base amplitude stays 0.9 of it)
    _case("gap_0.01", "gap 0.01 m", gap=0.01, steps=10_000, full_steps=100_000),
    _case("gap_0.001", "gap 0.001 m", gap=0.001, steps=10_000, full_steps=100_000),
    _case("gap_1e-4", "obstacles 1e-4 m from the plate on both sides", gap=1e-4, steps=10_000, full_steps=100_000),
    _case("base_0.99_gap", "base amplitude 0.99 of the gap", amplitude=0.99, steps=10_000, full_steps=100_000),
    # base frequency
    _case("f_35Hz", "base at 35 Hz", frequency=35.0, steps=10_000, full_steps=100_000),
    _case("f_100Hz", "base at 100 Hz", frequency=100.0, steps=10_000, full_steps=100_000),
    # time step (beta = 1/2)
    _case("dt_1e-2", "dt = 1e-2 s", dt=1e-2, per_comm=1, steps=200, full_steps=1_000),
    _case("dt_1e-3", "dt = 1e-3 s", dt=1e-3, per_comm=1, steps=1_000, full_steps=10_000),
    _case("dt_1e-6", "dt = 1e-6 s", dt=1e-6, per_comm=10, steps=70_000, full_steps=500_000),
    # Newmark beta
    _case("beta_0.25", "β = ¼", beta=0.25, steps=10_000, full_steps=100_000),
    _case(
        "beta_0_0.9x_bound",
        "β = 0, dt = 0.9 × bound, 7 × 3 cells",
        beta=0.0,
        bound_factor=0.9,
        steps=100_000,
        full_steps=1_000_000,
        **COARSE,
    ),
    _case(
        "beta_0_1.1x_bound",
        "β = 0, dt = 1.1 × bound, 7 × 3 cells (refused)",
        beta=0.0,
        bound_factor=1.1,
        refused=True,
        steps=0,
        **COARSE,
    ),
    _case(
        "beta_0_1.1x_bound_14x5",
        "β = 0, dt = 1.1 × bound, default cells (refused)",
        beta=0.0,
        bound_factor=1.1,
        refused=True,
        steps=0,
    ),
    # plate
    _case("thickness_0.001", "thickness 0.001 m", thickness=0.001, steps=10_000, full_steps=100_000),
    # 56 x 20 cells cost ~10 ms per step (10.6k dofs) and the first impact of the base case is
    # at t = 0.0496 s: at dt = 1e-5 that is 5000 steps before anything happens, so this case
    # runs at dt = 1e-4 (beta = 1/2, unconditionally stable) to reach contact in 800 steps.
    _case("grid_56x20", "56 × 20 cells (dt = 1e-4 s)", nx=56, ny=20, dt=1e-4, per_comm=1, steps=800, full_steps=5_000),
    # initial state and load
    _case(
        "pressed_held",
        "starts pressed onto the lower obstacle (initial_load = load = -2e4 Pa)",
        initial_load=-2e4,
        load=Constant(-2e4),
        starts_in_contact=True,
        steps=10_000,
        full_steps=100_000,
    ),
    _case(
        "pressed_released",
        "starts pressed onto the lower obstacle (initial_load = -2e4 Pa), load 0 from t = 0",
        initial_load=-2e4,
        starts_in_contact=True,
        steps=10_000,
        full_steps=100_000,
    ),
    # impact laws beyond the paper (docs/theory.md §11-13)
    _case("singular_p0", "mass = singular_p0", mass=2, steps=10_000, full_steps=100_000),
    _case("singular_p1dg", "mass = singular_p1dg", mass=3, steps=10_000, full_steps=100_000),
    _case("singular_p0_fvs", "mass = singular_p0, FVS element", mass=2, element=2, steps=10_000, full_steps=100_000),
    _case(
        "singular_p0_dt_1e-3",
        "mass = singular_p0, dt = 1e-3 s",
        mass=2,
        dt=1e-3,
        per_comm=1,
        steps=1_000,
        full_steps=10_000,
    ),
    _case("restitution_0.5", "restitution 0.5", restitution=0.5, steps=10_000, full_steps=100_000),
    _case("restitution_1", "restitution 1", restitution=1.0, steps=10_000, full_steps=100_000),
    _case(
        "restitution_1_dt_1e-3",
        "restitution 1, dt = 1e-3 s",
        restitution=1.0,
        dt=1e-3,
        per_comm=1,
        steps=1_000,
        full_steps=10_000,
    ),
    _case(
        "damping",
        "Rayleigh damping a = 5 1/s, b = 1e-5 s",
        damping_mass=5.0,
        damping_stiffness=1e-5,
        steps=10_000,
        full_steps=100_000,
    ),
    _case(
        "all_laws",
        "singular_p0, restitution 0.5, damping a = 5 1/s, b = 1e-5 s",
        mass=2,
        restitution=0.5,
        damping_mass=5.0,
        damping_stiffness=1e-5,
        steps=10_000,
        full_steps=100_000,
    ),
    _case(
        "load_steps_1e5",
        "load steps of 1e5 Pa: 0, +1e5, 0, -1e5, 0",
        load=Steps((0.0, 1e5, 0.0, -1e5, 0.0), (0.0, 0.2, 0.4, 0.6, 0.8)),
        steps=10_000,
        full_steps=100_000,
    ),
]

CASE_NAMES = [c.name for c in CASES]
assert len(set(CASE_NAMES)) == len(CASE_NAMES)

# ---------------------------------------------------------------------------------------------
# Driving the FMU


class _Instance(PlateImpactFMU):
    """One FMU instance, initialized by the runner (so a refused initialization keeps its
    log, (status, category, message) in .log), stepped at the runner's times."""

    def __init__(self, fmu_path):
        super().__init__(fmu_path, instance_name="stability", initialize=False)

    def step(self, t, h, base, load):
        self.time = t
        return super().step(h, base=base, load=load)


# The FMU's refusal names the bound: "... dt < 2/sqrt((1-4 beta) kappa_h) = <bound> s ...".
BOUND_PATTERN = re.compile(r"dt < 2/sqrt\(\(1-4 beta\) kappa_h\) = ([0-9.eE+-]+) s")


def refusal(fmu_path, params):
    """Initialize with `params` (beta < 1/4 and a dt past the bound) and return
    (the exception, the logged error messages). Raises AssertionError if the FMU accepts."""
    inst = _Instance(fmu_path)
    try:
        try:
            inst.initialize(params, 0.0, 0.0)
        except FMICallException as e:
            return e, inst.errors()
        raise AssertionError(f"the FMU accepted {params}")
    finally:
        inst.close()


def stability_bound(fmu_path, params):
    """The FMU's stability bound 2/sqrt((1-4 beta) kappa_h) for `params` (beta < 1/4), read
    from the error the FMU logs when dt is past it (kappa_h is not an output: this is what
    a user does)."""
    # Past the bound, but not past half the plate's first period (refused before the bound is
    # computed): the first dt of these the FMU refuses for stability.
    for dt in (1e-2, 1e-3, 1e-4):
        _, errors = refusal(fmu_path, {**params, "dt": dt})
        for m in errors:
            match = BOUND_PATTERN.search(m)
            if match:
                return float(match.group(1))
    raise AssertionError(f"no stability bound in the FMU's log: {errors}")


def resolved_params(case, fmu_path):
    """The case's FMU parameters with dt filled in (beta = 0 cases: factor x the bound)."""
    if case.bound_factor is None:
        return dict(case.params), None
    bound = stability_bound(fmu_path, case.params)
    return {**case.params, "dt": case.bound_factor * bound}, bound


def _vertex_probes(params):
    """The probe outputs that sit on mesh vertices: the two free corners always, the middle of
    the free edge only when ny is even (otherwise it lies between two vertices, and contact is
    enforced at the vertices only, so it may legitimately pass an obstacle a little)."""
    probes = ["corner_1", "corner_2"]
    if int(params.get("ny", 5)) % 2 == 0:
        probes.append("free_edge_mid")
    return probes


@dataclass
class Result:
    case: Case
    dt: float = float("nan")
    bound: Optional[float] = None  # beta < 1/4: the FMU's stability bound
    steps: int = 0  # internal steps taken
    comm_steps: int = 0
    horizon: float = 0.0  # s simulated
    wall: float = 0.0  # s of wall time (initialization included)
    refused_exception: Optional[Exception] = None  # the exception of a refused initialization
    refused_log: list = field(default_factory=list)
    step_error: Optional[str] = None  # a failed fmi2DoStep/initialization (with the log)
    nonfinite: Optional[str] = None  # first non-finite output (name and time)
    e0: float = float("nan")
    energy_max: float = 0.0  # largest |energy| seen (E0 included)
    ledger_error: float = 0.0  # max over comm points of |E - (E0 + in - diss)| / max|E| so far
    ledger_error_abs: float = 0.0  # the same, in J
    energy_input: float = 0.0  # final values
    energy_dissipated: float = 0.0
    energy_damped: float = 0.0
    energy_final: float = float("nan")
    energy_min: float = math.inf  # smallest energy seen (a norm of the state when stable)
    dissipation_drop: float = 0.0  # most negative change of energy_dissipated (0: never)
    penetration: float = -math.inf  # max over comm points and vertex probes of (lower - u, u - upper)
    penetration_time: float = float("nan")  # where it occurred, s
    midedge_overshoot: float = -math.inf  # the same for free_edge_mid when it is not a vertex
    contact_start: int = 0  # contact_vertices of the initial state
    contact_max: int = 0  # largest contact_vertices seen at a communication point
    comm_with_contact: int = 0  # communication points with contact_vertices > 0
    kkt_max: float = 0.0
    qp_iterations_total: int = 0
    qp_iterations_max: int = 0

    @property
    def qp_iterations_mean(self):
        """Active-set iterations per internal time step (steps without any QP count 0)."""
        return self.qp_iterations_total / self.steps if self.steps else 0.0

    @property
    def ledger_error_final(self):
        """The ledger error at the end of the run, relative to the largest |energy| seen."""
        err = abs(self.energy_final - (self.e0 + self.energy_input - self.energy_dissipated - self.energy_damped))
        return err / self.energy_max if self.energy_max > 0 else (0.0 if err == 0 else math.inf)

    @property
    def contact_seen(self):
        return self.contact_max > 0 or self.energy_dissipated > 0.0


def run_case(case, fmu_path, full=False):
    """Run one case; returns a Result with everything the checks and the report need."""
    r = Result(case=case)
    wall0 = time.perf_counter()
    params, r.bound = resolved_params(case, fmu_path)
    r.dt = params.get("dt", DT0)
    if case.refused:
        e, log = refusal(fmu_path, params)
        r.refused_exception, r.refused_log = e, log
        r.wall = time.perf_counter() - wall0
        return r

    total = case.full_steps if (full and case.full_steps) else case.steps
    n_comm = total // case.per_comm
    h = case.per_comm * r.dt
    horizon = n_comm * h
    load = case.load.bind(horizon) if isinstance(case.load, Steps) else case.load
    lower, upper = case.obstacles
    probes = _vertex_probes(params)
    midedge = "free_edge_mid" not in probes

    inst = _Instance(fmu_path)
    try:
        try:
            inst.initialize(params, case.base(0.0)[0], load(0.0)[0])
        except FMICallException as e:
            r.step_error = f"initialization: {e}; log: {inst.errors()}"
            return r
        out = inst.outputs()
        r.e0 = out["energy"]
        r.energy_max = abs(r.e0)
        prev_diss = out["energy_dissipated"]

        def observe(out, t):
            nonlocal prev_diss
            for k, v in out.items():
                if not math.isfinite(v):
                    r.nonfinite = r.nonfinite or f"{k} = {v} at t = {t:.9g} s"
            e = out["energy"]
            r.energy_max = max(r.energy_max, abs(e))
            r.energy_min = min(r.energy_min, e)
            err = abs(e - (r.e0 + out["energy_input"] - out["energy_dissipated"] - out["energy_damped"]))
            r.ledger_error_abs = max(r.ledger_error_abs, err)
            if r.energy_max > 0:
                r.ledger_error = max(r.ledger_error, err / r.energy_max)
            elif err > 0:
                r.ledger_error = math.inf
            r.dissipation_drop = min(r.dissipation_drop, out["energy_dissipated"] - prev_diss)
            prev_diss = out["energy_dissipated"]
            for p in probes:
                d = max(lower - out[p], out[p] - upper)
                if d > r.penetration:
                    r.penetration, r.penetration_time = d, t
            if midedge:
                u = out["free_edge_mid"]
                r.midedge_overshoot = max(r.midedge_overshoot, lower - u, u - upper)
            r.contact_max = max(r.contact_max, out["contact_vertices"])
            r.comm_with_contact += out["contact_vertices"] > 0

        r.contact_start = out["contact_vertices"]
        observe(out, 0.0)
        for k in range(n_comm):
            t = k * h
            try:
                inst.step(t, h, case.base(t), load(t))
            except FMICallException as e:
                r.step_error = f"fmi2DoStep at t = {t:.9g} s: {e}; log: {inst.errors()}"
                try:
                    out = inst.outputs()  # the state of the last good step
                    observe(out, t)
                except FMICallException:
                    pass
                break
            r.comm_steps += 1
            out = inst.outputs()
            observe(out, t + h)
        r.steps = r.comm_steps * case.per_comm
        r.horizon = r.comm_steps * h
        r.energy_input = out["energy_input"]
        r.energy_dissipated = out["energy_dissipated"]
        r.energy_damped = out["energy_damped"]
        r.energy_final = out["energy"]
        r.kkt_max = out["qp_kkt_residual_max"]
        r.qp_iterations_total = out["qp_iterations_total"]
        r.qp_iterations_max = out["qp_iterations_max"]
    finally:
        inst.close()
        r.wall = time.perf_counter() - wall0
    return r


def failures(r):
    """The checks of the issue, as a list of messages (empty: the case passes)."""
    case = r.case
    if case.refused:
        msgs = []
        text = " ".join(r.refused_log)
        e = r.refused_exception
        if (
            not isinstance(e, FMICallException)
            or "fmi2ExitInitializationMode" not in str(e)
            or "status 3" not in str(e)
        ):  # fmi2Error = 3
            msgs.append(f"initialization not refused with fmi2Error: {e!r}")
        if f"dt = {r.dt:g}" not in text:
            msgs.append(f"the log does not name dt = {r.dt:g}: {r.refused_log}")
        match = BOUND_PATTERN.search(text)
        if not match or not math.isclose(float(match.group(1)), r.bound, rel_tol=1e-12):
            msgs.append(f"the log does not name the bound {r.bound:g} s: {r.refused_log}")
        return msgs
    msgs = []
    if r.step_error:
        msgs.append(r.step_error)
    if r.nonfinite:
        msgs.append(f"non-finite output: {r.nonfinite}")
    if not r.penetration <= case.penetration_limit:
        msgs.append(f"a probe vertex is {r.penetration:.3g} m past an obstacle (limit {case.penetration_limit:g})")
    if not r.ledger_error <= LEDGER_LIMIT:
        msgs.append(
            f"energy ledger off by {r.ledger_error:.3g} of the largest energy "
            f"({r.ledger_error_abs:.3g} J; limit {LEDGER_LIMIT:g})"
        )
    # For beta >= 1/4, and for beta < 1/4 below the bound, the discrete energy is a norm of the
    # state: a negative value would mean the scheme left its stability region.
    if not r.energy_min >= -LEDGER_LIMIT * r.energy_max:
        msgs.append(f"negative discrete energy {r.energy_min:.3g} J")
    if r.dissipation_drop < 0.0 and not case.net_dissipation:
        msgs.append(f"energy_dissipated decreased by {-r.dissipation_drop:.3g} J")
    # Every QP converged: the stepper fails the step when a QP does not converge or its KKT
    # residual exceeds 1e-10 (caught above as a step error); the running maximum says the same.
    # The residual includes primal feasibility max(lower - y, y - upper) of every vertex,
    # relative to the largest |bound| or |free solution| of that QP (solver/plate/BoxQP.cpp,
    # kktResidual), so KKT <= 1e-10 also bounds the penetration of every vertex, not only the
    # probes, by 1e-10 x that scale; the QP moreover puts active vertices on the obstacle
    # exactly and accepts free ones only within 1e-15 (1 + |bound|) of it.
    if not r.kkt_max <= KKT_LIMIT:
        msgs.append(f"QP KKT residual {r.kkt_max:.3g} > {KKT_LIMIT:g}")
    if case.starts_in_contact and not r.contact_start > 0:
        msgs.append("the initial state does not touch an obstacle")
    if not r.contact_seen:
        msgs.append("no contact in the horizon: the case proves nothing about contact")
    if r.steps < case.steps and not r.step_error:
        msgs.append(f"only {r.steps} of {case.steps} steps taken")
    return msgs
