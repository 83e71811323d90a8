"""Independent FMU runs as Dask tasks (the response map, the sizing): the package shipped to the
workers, the FMU's bytes sent once and written once per worker process, the results in the order of
the calls, a progress bar."""

from __future__ import annotations

import atexit
import hashlib
import shutil
import tempfile
from pathlib import Path

PACKAGE = Path(__file__).resolve().parent

_written = {}  # sha256 of an FMU's bytes -> the file this process wrote them to (local_fmu)


def local_fmu(fmu):
    """A path as it is; the FMU's bytes as a file, written once per process: every run then loads
    the same extraction, whose discretization cache the runs share (driver.unzipped)."""
    if not isinstance(fmu, (bytes, bytearray)):
        return fmu
    digest = hashlib.sha256(fmu).hexdigest()
    if digest not in _written:
        folder = tempfile.mkdtemp(prefix="plateimpact-task-")
        atexit.register(shutil.rmtree, folder, ignore_errors=True)
        path = Path(folder) / "PlateImpact.fmu"
        path.write_bytes(fmu)
        _written[digest] = path
    return _written[digest]


def on_dask(client, func, fmu, calls, progress=True, desc="runs", unit="run"):
    """func(fmu, *args, **kwargs) for each (args, kwargs) of `calls` as Dask tasks; the results in
    the order of `calls`. `fmu`: a path the workers can read, or the FMU file's bytes."""
    from distributed import as_completed

    # the workers need this package (a remote cluster may have no copy of it): ship it as a
    # zip. load=False: a LocalCluster's scheduler lives in this process and would otherwise
    # re-import it here, replacing the module objects the caller holds
    with tempfile.TemporaryDirectory(prefix="plateimpact-upload-") as tmp:
        archive = shutil.make_archive(str(Path(tmp) / "plateimpact"), "zip", str(PACKAGE.parent), PACKAGE.name)
        client.upload_file(archive, load=False)
    if isinstance(fmu, (bytes, bytearray)):
        fmu = client.scatter(fmu, broadcast=True)  # sent once to every worker
    futures = [client.submit(func, fmu, *args, pure=False, **kwargs) for args, kwargs in calls]
    index = {fut.key: i for i, fut in enumerate(futures)}
    results = [None] * len(futures)
    bar = None
    if progress:
        from tqdm import tqdm

        bar = tqdm(total=len(futures), unit=unit, desc=desc)
    try:
        for fut in as_completed(futures):
            results[index[fut.key]] = fut.result()
            if bar is not None:
                bar.update(1)
    finally:
        if bar is not None:
            bar.close()
    return results
