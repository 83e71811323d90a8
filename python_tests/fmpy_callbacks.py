"""FMI 2.0 callbacks a test keeps alive itself. fmpy formats FMI 2.0 log messages in a native proxy
that keeps one global pointer to the last Python logger registered (fmpy.logging.addLoggerProxy);
a `simulate_fmu(..., logger=f)` registers f's ctypes callback and drops it when it returns, so the
next FMU that logs through fmpy's default callbacks in the same process calls freed memory (a
segfault of an xdist worker at the first message)."""

from __future__ import annotations

from fmpy.fmi2 import (
    calloc,
    fmi2CallbackAllocateMemoryTYPE,
    fmi2CallbackFreeMemoryTYPE,
    fmi2CallbackFunctions,
    fmi2CallbackLoggerTYPE,
    free,
)


def callbacks(logger) -> fmi2CallbackFunctions:
    """Callbacks with `logger` (a Python function of fmpy's logger signature); keep the result alive
    as long as any instance or proxy uses it."""
    c = fmi2CallbackFunctions()
    c.logger = fmi2CallbackLoggerTYPE(logger)
    c.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
    c.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
    return c
