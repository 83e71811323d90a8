"""The user-facing examples: they run (quick mode), the sine-sweep controller is exact and reaches
the FMU through the input derivatives, and the Dask response map equals the serial loop."""

import csv
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from plateimpact import PlateImpactFMU
from plateimpact.response_map import RESULT_COLUMNS, dask_map, grid, serial_map
from plateimpact.sweep import CSV_COLUMNS, SineSweep

REPO = Path(__file__).resolve().parent.parent
EXAMPLES = REPO / "examples"

EPS = np.finfo(float).eps


@pytest.fixture(scope="module")
def fmu(fmu_path):
    if not Path(fmu_path).is_file():
        pytest.skip(f"FMU not built: {fmu_path}")
    return str(fmu_path)


def run_example(script, fmu, out, *extra):
    """Runs `script --quick` into `out`; returns the folder it wrote to, `out/quick/` (the README's one
    rule: a smoke run never writes beside a full run's files), having checked it wrote nothing else."""
    cmd = [sys.executable, str(EXAMPLES / script), "--quick", "--fmu", fmu, "--out", str(out), *extra]
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=240, cwd=REPO)
    assert r.returncode == 0, f"{script} failed:\n{r.stdout[-2000:]}\n{r.stderr[-4000:]}"
    assert sorted(p.name for p in Path(out).iterdir()) == ["quick"], f"{script} --quick wrote beside a full run's files"
    return Path(out) / "quick"


def read_csv(path, columns):
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        if columns is not None:
            assert reader.fieldnames == list(columns), reader.fieldnames
        rows = list(reader)
    assert rows, f"{path} has no rows"
    return rows


def assert_finite(rows, columns):
    for r in rows:
        for c in columns:
            assert math.isfinite(float(r[c])), (c, r)


# -- each example runs in quick mode and writes its outputs -------------------------------------
def test_sine_sweep_quick(fmu, tmp_path):
    q = run_example("sine_sweep.py", fmu, tmp_path)
    cols = CSV_COLUMNS  # the columns plateimpact.sweep documents
    rows = read_csv(q / "sine_sweep.csv", cols)
    assert_finite(rows, cols)
    assert len(rows) == 51  # 0.05 s at 1 ms, plus t = 0
    assert (q / "sine_sweep.png").stat().st_size > 10_000


def test_paper_scenes_quick(fmu, tmp_path):
    q = run_example("paper_scenes.py", fmu, tmp_path)
    for png in (
        "paper_fig05-07_forced",
        "paper_fig08_gap",
        "paper_fig09-11_frequencies",
        "paper_fig12-13_free",
        "paper_fig14-16_free_zoom",
        "paper_fig17-18_energy",
        "paper_dt_convergence",
    ):
        assert (q / f"{png}.png").stat().st_size > 10_000, png
    runs = read_csv(q / "paper_scenes.csv", None)  # the script's own columns
    RUN_COLUMNS = list(runs[0])
    assert len(runs) == 2 * (5 + 2 + 6 + 5)
    numeric = [
        c
        for c in RUN_COLUMNS
        if c not in ("scene", "element", "first_contact_time", "c1_c2_split_time", "first_peak", "last_peak")
    ]
    assert_finite(runs, numeric)
    for r in runs:  # the FMU's energy ledger holds in every scene
        assert float(r["ledger_residual"]) <= 1e-9 * max(1.0, float(r["energy_input"]), float(r["energy_initial"]))
    # issue 56: --quick stopped the free vibration (and the forced one) before the first impact
    for r in runs:
        if r["scene"] in ("forced", "free"):
            assert int(r["contact_episodes"]) > 0, (r["scene"], r["element"], r["dt"])
    pairs = read_csv(q / "paper_scenes_elements.csv", None)
    assert_finite(pairs, [c for c in pairs[0] if c != "scene"])


def test_frequency_response_quick(fmu, tmp_path):
    q = run_example("frequency_response.py", fmu, tmp_path, "--no-progress")
    cols = RESULT_COLUMNS + ("wall_s", "setup_s")
    rows = read_csv(q / "frequency_response.csv", cols + ("plate_shared",))
    assert len(rows) == 4
    assert_finite(rows, cols)
    # 4 points on 2 worker processes: each process builds the plate once, the other points share it
    if os.environ.get("PLATEIMPACT_CACHE_MB") != "0":
        assert sum(r["plate_shared"] == "True" for r in rows) >= 2, rows
    assert (q / "frequency_response.png").stat().st_size > 10_000


# -- the sweep controller -------------------------------------------------------------------------
LAWS = {
    "linear": lambda f0, f1, T, t: f0 + (f1 - f0) * t / T,
    "log": lambda f0, f1, T, t: f0 * (f1 / f0) ** (t / T),
}


@pytest.mark.parametrize("law", ["linear", "log"])
def test_sweep_frequency_law_and_phase(law):
    A, f0, f1, T = 0.02, 2.0, 40.0, 8.0
    sw = SineSweep(A, f0, f1, T, law)
    ts = np.linspace(0.0, T, 2001)
    f_law = np.array([LAWS[law](f0, f1, T, t) for t in ts])

    # the law, and the phase's analytic derivative is 2π f(t)
    f_sw = np.array([sw.frequency(t) for t in ts])
    np.testing.assert_allclose(f_sw, f_law, rtol=1e-9, atol=0)
    ph = np.array([sw.phase(t) for t in ts])
    np.testing.assert_allclose(ph[:, 1], 2 * np.pi * f_law, rtol=1e-9, atol=0)

    # the frequency carried by the produced signal itself: z = A sin φ, ż = A φ' cos φ, so
    # φ' = |ż| / sqrt(A² − z²) — well conditioned where |z| ≤ A/2 (there sqrt(A² − z²) ≥ 0.87 A)
    sig = np.array([sw(t) for t in ts])
    k = np.abs(sig[:, 0]) <= 0.5 * A
    assert k.sum() > 500
    f_sig = np.abs(sig[k, 1]) / np.sqrt(A * A - sig[k, 0] ** 2) / (2 * np.pi)
    np.testing.assert_allclose(f_sig, f_law[k], rtol=1e-9, atol=0)

    # finite differences of the phase function. Central differences with step h err by
    # h²/6·max|g'''| (truncation) + eps·max|g|/h (rounding of g, twice, over 2h); the bound is
    # taken with a factor 4 of slack. g = φ for φ', g = φ' for φ''.
    phi = lambda t: sw.phase(t)[0]  # noqa: E731
    dphi = lambda t: sw.phase(t)[1]  # noqa: E731
    k_log = math.log(f1 / f0) / T
    # |φ'''| = 2π|f''|, |φ''''| = 2π|f'''|: zero for the linear law
    f2 = 0.0 if law == "linear" else f1 * k_log**2
    f3 = 0.0 if law == "linear" else f1 * k_log**3
    phi_max = abs(phi(T))
    inner = ts[(ts > 0.01) & (ts < T - 0.01)]
    h1 = 1e-5
    fd1 = np.array([(phi(t + h1) - phi(t - h1)) / (2 * h1) for t in inner])
    bound1 = 4 * (h1**2 / 6 * 2 * np.pi * f2 + EPS * phi_max / h1)
    err1 = np.max(np.abs(fd1 - np.array([dphi(t) for t in inner])))
    assert err1 <= bound1, (err1, bound1)
    h2 = 1e-4
    fd2 = np.array([(dphi(t + h2) - dphi(t - h2)) / (2 * h2) for t in inner])
    bound2 = 4 * (h2**2 / 6 * 2 * np.pi * f3 + EPS * 2 * np.pi * f1 / h2)
    err2 = np.max(np.abs(fd2 - np.array([sw.phase(t)[2] for t in inner])))
    assert err2 <= bound2, (err2, bound2)

    # the signal's derivatives against finite differences of z (same error model;
    # |z'''| ≤ A(φ'³ + 3φ'|φ''| + |φ'''|), |z''''| ≤ A(φ'⁴ + 6φ'²|φ''| + 3φ''² + 4φ'|φ'''| + |φ''''|))
    w1 = 2 * np.pi * f1  # max φ'
    w2 = 2 * np.pi * ((f1 - f0) / T if law == "linear" else f1 * k_log)  # max |φ''|
    w3, w4 = 2 * np.pi * f2, 2 * np.pi * f3
    z3 = A * (w1**3 + 3 * w1 * w2 + w3)
    z4 = A * (w1**4 + 6 * w1**2 * w2 + 3 * w2**2 + 4 * w1 * w3 + w4)
    z = lambda t: sw(t)[0]  # noqa: E731
    zd = lambda t: sw(t)[1]  # noqa: E731
    h = 1e-6
    # rounding: φ carries eps·|φ| absolute error, so z = A sin φ carries A·eps·(|φ| + 1)
    # and ż = A φ' cos φ carries A φ'·eps·(|φ| + 2)
    e_zd = max(abs((z(t + h) - z(t - h)) / (2 * h) - zd(t)) for t in inner)
    b_zd = 4 * (h**2 / 6 * z3 + A * EPS * (phi_max + 1) / h)
    assert e_zd <= b_zd, (e_zd, b_zd)
    e_zdd = max(abs((zd(t + h) - zd(t - h)) / (2 * h) - sw(t)[2]) for t in inner)
    b_zdd = 4 * (h**2 / 6 * z4 + A * w1 * EPS * (phi_max + 2) / h)
    assert e_zdd <= b_zdd, (e_zdd, b_zdd)


def _drive(fmu, sweep, dt, h, mode, stop):
    """Corner displacement of an obstacle-free plate driven by the sweep at comm step h.

    mode "exact":  h = dt and the derivative is the secant (z(t+h) − z(t))/h, so every
                   internal step sees the exact sample z(t_{n+1}) (the FMU follows z + ż s).
    mode "deriv":  the controller's (z, ż, z̈) — error of the clamp inside a step A ω³ s³/6.
    mode "held":   value only, held over the step — error A ω s."""
    n = round(stop / h)
    out = np.empty(n)
    with PlateImpactFMU(
        fmu, element="argyris", nx=6, ny=2, dt=dt, obstacle_lower_enabled=False, obstacle_upper_enabled=False
    ) as plate:
        for k in range(n):
            t = k * h
            z = sweep(t)
            if mode == "exact":
                signal = (z[0], (sweep(t + h)[0] - z[0]) / h, 0.0)
            elif mode == "deriv":
                signal = z
            else:
                signal = (z[0], 0.0, 0.0)
            plate.step(h, base=signal)
            out[k] = plate.outputs()["corner_1"]
    return out


def test_sweep_reaches_fmu_through_input_derivatives(fmu):
    """With input derivatives the FMU sees the sweep a direct evaluation gives, to third order
    in the communication step; with held inputs only to first order.

    Reference: comm step = Δt with exact samples. At comm step h = mΔt the corner's deviation
    from it (max over 0.3 s, 5 → 40 Hz, the plate's second bending mode ≈ 37 Hz inside) was
    measured at m = 10 / 20: derivatives 6.3e-5 / 4.2e-4 m (×6.7 for twice the step, ~h³),
    held 1.1e-2 / 2.5e-2 m (×2.2, ~h). Asserted with margin: held/deriv > 50 at m = 10, the
    derivative error grows ≥ ×5 when h doubles, the held one ≤ ×3."""
    sw = SineSweep(0.01, 5.0, 40.0, 0.3, "linear")
    dt, stop = 1e-4, 0.3
    ref = _drive(fmu, sw, dt, dt, "exact", stop)
    err = {}
    for m in (10, 20):
        r = ref[m - 1 :: m]
        err[("deriv", m)] = np.max(np.abs(_drive(fmu, sw, dt, m * dt, "deriv", stop) - r))
        err[("held", m)] = np.max(np.abs(_drive(fmu, sw, dt, m * dt, "held", stop) - r))
    print({k: f"{v:.3g}" for k, v in err.items()})
    assert err[("held", 10)] / err[("deriv", 10)] > 50, err
    assert err[("deriv", 20)] / err[("deriv", 10)] >= 5, err
    assert err[("held", 20)] / err[("held", 10)] <= 3, err
    assert err[("deriv", 10)] < 2e-3 * np.max(np.abs(ref)), err


# -- the Dask map -------------------------------------------------------------------------------
def test_dask_map_equals_serial_loop(fmu):
    """A 3×2 map on a 2-worker LocalCluster (processes) against the same function called in a
    loop here: bitwise equal floats (each task is a fresh, deterministic FMU instance)."""
    distributed = pytest.importorskip("distributed")
    points = grid([6.0, 20.0, 35.0], [0.012, 0.04])
    kw = dict(amplitude=0.01, stop_time=0.1, settle=0.05, dt=1e-4, comm_step=1e-3, element="argyris", nx=6, ny=2)
    serial = serial_map(fmu, points, **kw)
    with (
        distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster,
        distributed.Client(cluster) as client,
    ):
        parallel = dask_map(client, fmu, points, progress=False, **kw)
    assert any(r["energy_dissipated"] > 0 for r in serial)  # some points do impact
    for s, p in zip(serial, parallel):
        for c in RESULT_COLUMNS:
            assert s[c] == p[c], (c, s, p)  # exact equality, not approximate


def smoke_mark(png):
    """The Description a figure was saved with (examples mark --quick figures as smoke runs)."""
    from PIL import Image

    with Image.open(png) as image:
        return image.text.get("Description", "")


def test_stress_sweep_quick(fmu, tmp_path):
    q = run_example("stress_sweep.py", fmu, tmp_path)
    series = ("time", "frequency", "base", "root_stress", "root_stress_peak", "probe_1", "probe_1_acceleration")
    rows = read_csv(q / "stress_sweep.csv", series)
    assert_finite(rows, series)
    assert len(rows) == 50  # 0.05 s at 1 ms
    peaks = [float(r["root_stress_peak"]) for r in rows]
    assert peaks == sorted(peaks) and all(float(r["root_stress"]) <= p for r, p in zip(rows, peaks))
    env = read_csv(q / "stress_envelope.csv", ("frequency", "root_stress_max", "root_stress_peak", "transmissibility"))
    assert_finite(env, ("frequency", "root_stress_max", "root_stress_peak", "transmissibility"))
    assert (q / "stress_sweep.png").stat().st_size > 10_000
    assert smoke_mark(q / "stress_sweep.png").startswith("smoke run (--quick)")


def test_stress_sweep_probe_off_the_plate_is_the_fmus_message(fmu, tmp_path):
    """Issue 46: `--probe 1.5 0.2` (past the 1.2 m plate) ended in a 22-line traceback that hid the
    FMU's message; now it is that message, one line, and exit status 2."""
    cmd = [sys.executable, str(EXAMPLES / "stress_sweep.py"), "--quick", "--fmu", fmu, "--out", str(tmp_path)]
    r = subprocess.run([*cmd, "--probe", "1.5", "0.2"], capture_output=True, text=True, timeout=240, cwd=REPO)
    assert r.returncode == 2, (r.stdout, r.stderr)
    assert "Traceback" not in r.stderr and len(r.stderr.strip().splitlines()) == 1, r.stderr
    assert "the FMU refused the run" in r.stderr and "probe_1_x" in r.stderr and "1.5" in r.stderr, r.stderr
    assert "length" in r.stderr, r.stderr  # the allowed range
    assert not list(tmp_path.glob("*.csv"))


def test_default_scene_quick_keeps_the_full_scene_and_says_smoke(fmu, tmp_path):
    """Issue 46: a quick default_scene wrote out/default_scene.csv, the README's 1 s scene, with an
    unmarked figure; it writes into <out>/quick/ now (issue 56: every example), the figure marked as a smoke run."""
    q = run_example("default_scene.py", fmu, tmp_path)
    rows = read_csv(q / "default_scene.csv", None)
    assert float(rows[-1]["time"]) == pytest.approx(0.1)
    assert smoke_mark(q / "default_scene.png") == "smoke run (--quick): the first 0.1 s only"


# -- every example takes the options the README promises ----------------------------------------
@pytest.mark.parametrize("script", sorted(p.name for p in EXAMPLES.glob("*.py")))
def test_every_example_takes_fmu_out_and_quick(script):
    """README.md: "every example takes `--fmu`, `--out DIR` (where it writes its files) and
    `--quick` (a smoke run)" — each one's --help lists the three."""
    r = subprocess.run([sys.executable, str(EXAMPLES / script), "--help"], capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stderr[-2000:]
    for option in ("--fmu", "--out", "--quick"):
        assert option in r.stdout, f"{script} has no {option}"
    assert "--fmu" in (REPO / "README.md").read_text() and "--quick" in (REPO / "README.md").read_text()


def test_stop_under_tip_counts_its_landings_as_impacts_lower(fmu, tmp_path):
    """examples/stop_under_tip.py printed contact_onsets_lower as its "landings" (86 in 0.5 s where
    impacts_lower reads 6: issue 71). Its landings are impacts_lower now, the onsets named beside them;
    the landings counted from its CSV (contact episodes of the stop's force parted by a quarter of the
    strip's first period T1 = 0.164 s, impacts_lower's rule) are the printed ones, and fewer than the onsets."""
    cmd = [sys.executable, str(EXAMPLES / "stop_under_tip.py"), "--quick", "--fmu", fmu, "--out", str(tmp_path)]
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=240, cwd=REPO)
    assert r.returncode == 0, r.stderr[-4000:]
    landings = int(r.stdout.split(" landings on the stop (impacts_lower")[0].rsplit(" ", 1)[1])
    onsets = int(r.stdout.split(" contact onsets (contact_onsets_lower")[0].rsplit(" ", 1)[1])
    rows = read_csv(tmp_path / "quick" / "stop_under_tip.csv", None)
    touching = [float(r["time"]) for r in rows if float(r["contact_force_lower"]) != 0.0]
    episodes = sum(1 for k, t in enumerate(touching) if k == 0 or t - touching[k - 1] >= 0.164 / 4)
    assert landings == episodes >= 1 and onsets > landings, r.stdout
