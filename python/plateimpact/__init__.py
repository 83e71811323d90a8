"""Drive and check PlateImpact.fmu from Python.

- `plateimpact.driver`: `PlateImpactFMU`, the FMU driver (parameters by name, inputs with or
  without derivatives, outputs as a dict), and `sine`.
- `plateimpact.scenes`: the scenes of the accuracy reports and the exact-base reference run.
- `plateimpact.sweep`: the sine-sweep controller and its master loop.
- `plateimpact.response_map`: frequency × gap response maps, serial or on Dask.
- `plateimpact.stability`: the stability matrix (cases, runner, checks).
"""

from .driver import PlateImpactFMU, signal, sine, unzipped

__all__ = ["PlateImpactFMU", "signal", "sine", "unzipped"]
