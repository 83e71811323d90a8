"""Response map of the impacting plate (excitation frequency × obstacle gap): one independent FMU
simulation per map point, in a loop or as Dask tasks (examples/frequency_response.py is its
command line)."""

from __future__ import annotations

import re
import time

from .tasks import local_fmu, on_dask

RESULT_COLUMNS = (
    "frequency",
    "gap",
    "amplitude",
    "max_abs_corner",
    "energy_dissipated_per_cycle",
    "energy_dissipated",
    "contact_fraction",
)
CSV_COLUMNS = RESULT_COLUMNS + ("wall_s", "setup_s", "plate_shared")


def simulate_point(
    fmu,
    frequency,
    gap,
    amplitude=0.01,
    stop_time=2.0,
    settle=1.0,
    dt=1e-4,
    comm_step=1e-3,
    element="argyris",
    nx=14,
    ny=5,
):
    """One map point: a fresh FMU instance driven by A sin(2πf t) with obstacles at ±gap.

    `fmu` is a path, or the FMU file's bytes (then written to a temporary file once per process).
    Deterministic: the same arguments give bitwise the same floats. `setup_s`: the wall time of
    the instance's setup (instantiate to the end of initialization, the FMU already extracted);
    `plate_shared`: whether the FMU took its discretization from its cache (the first point of a
    plate in a process builds it, the next ones share it: README, "Performance")."""
    # imported here, on the worker: the task then carries no reference to the driver class
    # (which holds ctypes callbacks and could not be pickled by value)
    from plateimpact.driver import PlateImpactFMU, unzipped
    from plateimpact.scenes import sine

    if amplitude >= gap:
        raise ValueError(
            f"amplitude {amplitude} must be below the gap {gap}: the clamped edge may not pass the obstacles"
        )
    t_start = time.perf_counter()
    fmu = local_fmu(fmu)
    unzipped(fmu)  # extracted (once per process) before the setup is timed
    n = round(stop_time / comm_step)
    k_settle = round(settle / comm_step)
    max_c = 0.0
    contact = 0
    e_settle = 0.0
    log = []
    t_setup = time.perf_counter()
    with PlateImpactFMU(
        fmu,
        logger=lambda status, category, message: log.append(message),
        element=element,
        nx=nx,
        ny=ny,
        dt=dt,
        obstacle_lower=-gap,
        obstacle_upper=gap,
    ) as plate:
        setup = time.perf_counter() - t_setup
        shared = any(re.search(r"discretization: (\d+) of \1 parts shared", m) for m in log)
        for k in range(n):
            plate.step(comm_step, base=sine(amplitude, frequency, k * comm_step))
            o = plate.outputs()
            max_c = max(max_c, abs(o["corner_1"]), abs(o["corner_2"]))
            if k + 1 == k_settle:
                e_settle = o["energy_dissipated"]
            if k + 1 > k_settle and o["contact_vertices"] > 0:
                contact += 1
        e_end = o["energy_dissipated"]
    cycles = (stop_time - settle) * frequency
    return {
        "frequency": float(frequency),
        "gap": float(gap),
        "amplitude": float(amplitude),
        "max_abs_corner": max_c,
        "energy_dissipated_per_cycle": (e_end - e_settle) / cycles,
        "energy_dissipated": e_end,
        "contact_fraction": contact / max(1, n - k_settle),
        "wall_s": time.perf_counter() - t_start,
        "setup_s": setup,
        "plate_shared": shared,
    }


def grid(frequencies, gaps):
    """The map points, gap-major (row = gap, column = frequency)."""
    return [(f, g) for g in gaps for f in frequencies]


def serial_map(fmu, points, **kw):
    """The reference: the same function called in a loop, in this process."""
    return [simulate_point(fmu, f, g, **kw) for f, g in points]


def dask_map(client, fmu, points, progress=True, **kw):
    """The map on a Dask cluster: one task per point; results in the order of `points`."""
    return on_dask(client, simulate_point, fmu, [((f, g), kw) for f, g in points], progress, desc="map", unit="sim")
