"""fmpy's FMI 2 logger proxy keeps one process-wide pointer to the last logger registered with
`addLoggerProxy`; `simulate_fmu(logger=f)` registers a callback that is freed when its run returns,
and the pointer is never reset, so the next FMI 2 message of any later run calls freed memory (a
segfault in fmpy's logging.so, or a message lost to whatever took the slot). After every test,
the proxy gets a printing logger that lives as long as the process, as fmpy's default one does."""

from __future__ import annotations

from ctypes import byref

import pytest

try:
    import fmpy
    from fmpy.fmi1 import printLogMessage
    from fmpy.fmi2 import (fmi2CallbackAllocateMemoryTYPE, fmi2CallbackFreeMemoryTYPE, fmi2CallbackFunctions,
                           fmi2CallbackLoggerTYPE)
    from fmpy.logging import addLoggerProxy
except ImportError:  # the tests that need fmpy say so themselves
    addLoggerProxy = None

if addLoggerProxy is not None:
    _PRINT = fmi2CallbackLoggerTYPE(printLogMessage)  # lives as long as the process
    _PRINTING = fmi2CallbackFunctions()
    _PRINTING.allocateMemory = fmi2CallbackAllocateMemoryTYPE(fmpy.calloc)
    _PRINTING.freeMemory = fmi2CallbackFreeMemoryTYPE(fmpy.free)


@pytest.fixture(autouse=True)
def fmi2_logger_restored():
    yield
    if addLoggerProxy is not None:
        # addLoggerProxy swaps the struct's logger for the proxy and skips a struct that already
        # holds it: give it the printing function again each time, so the registration happens.
        _PRINTING.logger = _PRINT
        addLoggerProxy(byref(_PRINTING))


@pytest.fixture(autouse=True)
def log_folder(tmp_path, monkeypatch):
    """The FMU's default log goes to the user's log folder, `$XDG_STATE_HOME/beam-impact/logs`
    (issue 41): every test points XDG_STATE_HOME into its own temporary folder, so no test writes
    to the real home. Returns that log folder."""
    monkeypatch.setenv("XDG_STATE_HOME", str(tmp_path / "state"))
    return tmp_path / "state" / "beam-impact" / "logs"
