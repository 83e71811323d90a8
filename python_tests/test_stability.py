"""The stability stress matrix (tools/stability.py), short horizons.

One test per case of the shared table. A case that runs must show: no NaN/Inf; no probe vertex
past an obstacle by more than 1e-12 m; the energy ledger energy = E0 + energy_input -
energy_dissipated closed to 1e-9 of the largest energy seen at every communication point;
energy_dissipated never decreasing; every contact QP converged (KKT residual <= 1e-10, which
also bounds the infeasibility of every vertex, not only the probes: see
stability.failures); a non-negative discrete energy; and contact actually happening.
beta = 0 at 1.1x the stability bound must be refused at initialization with fmi2Error, the log
naming dt and the bound. tools/stability_report.py runs the same table into
docs/stability.json (docs/stability.md).
"""

import pytest
from stability import CASES, FMICallException, failures, run_case

# The sanitizer stage of test.sh runs this file against the ASan+UBSan build (pytest.ini).
pytestmark = pytest.mark.sanitizer


# The cases the sanitizer stage runs (the others repeat their code paths at more cost): many
# contacts, large dt, beta = 0 and its bound, the sparse engine (56 x 20), a start pressed onto
# an obstacle, the impact laws (singular mass, restitution, damping).
SANITIZER_CASES = {
    "gap_1e-4",
    "dt_1e-2",
    "beta_0_0.9x_bound",
    "beta_0_1.1x_bound",
    "beta_0_1.1x_bound_14x5",
    "grid_56x20",
    "pressed_held",
    "singular_p0_dt_1e-3",
    "restitution_1_dt_1e-3",
    "all_laws",
}


@pytest.mark.parametrize(
    "case",
    [pytest.param(c, id=c.name, marks=() if c.name in SANITIZER_CASES else pytest.mark.repeats_paths) for c in CASES],
)
def test_stability_case(case, fmu_path):
    r = run_case(case, fmu_path)
    if case.refused:
        assert isinstance(r.refused_exception, FMICallException), r.refused_exception
    problems = failures(r)
    assert not problems, f"{case.name} ({case.varied}), parameters {case.params}, dt = {r.dt:.6g} s: " + "; ".join(
        problems
    )
    if not case.refused:
        assert r.steps == case.steps
        print(
            f"{case.name}: {r.steps} steps, penetration {r.penetration:.2e} m, ledger "
            f"{r.ledger_error:.2e}, lost {r.energy_dissipated:.4g} J, QP it/step "
            f"{r.qp_iterations_mean:.3f} max {r.qp_iterations_max}, KKT {r.kkt_max:.1e}, "
            f"wall {r.wall:.2f} s"
        )


def test_bound_read_from_the_log_brackets_the_accepted_dt(fmu_path):
    """The bound the matrix parses from the FMU's log is the one the FMU enforces: 0.99x is
    accepted, 1.01x refused (coarse grid of the beta = 0 cases)."""
    from stability import COARSE, _Instance, refusal, stability_bound

    params = {"beta": 0.0, **COARSE}
    bound = stability_bound(fmu_path, params)
    assert 1e-7 < bound < 1e-4
    e, log = refusal(fmu_path, {**params, "dt": 1.01 * bound})
    assert any("dt = " in m and "kappa_h" in m for m in log), log
    inst = _Instance(fmu_path)
    try:
        inst.initialize({**params, "dt": 0.99 * bound}, 0.0, 0.0)
    finally:
        inst.close()
