"""Drive and check PlateImpact.fmu from Python.

- `plateimpact.driver`: `PlateImpactFMU`, the FMU driver (parameters by name, inputs with or
  without derivatives, outputs as a dict).
- `plateimpact.scenes`: the default scene's base (`default_base`, `sine`), the scenes of the accuracy
  reports and the exact-base reference run.
- `plateimpact.sweep`: the sine-sweep controller and its master loop.
- `plateimpact.response_map`: frequency × gap response maps, serial or on Dask.
- `plateimpact.interface`: the table of variables of docs/variables.md, written from the model description.

The studies and report writers of docs/ are not part of it: they are in the repository's tools/.
"""

from .driver import FMUError, PlateImpactFMU, signal, unzipped
from .scenes import default_base, sine

__all__ = ["FMUError", "PlateImpactFMU", "default_base", "signal", "sine", "unzipped"]
