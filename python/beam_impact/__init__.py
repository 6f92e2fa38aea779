"""beam_impact: design sweeps of the beam-impact FMU (fmpy, Dask) and its MCAP log reader.

    beam_impact.simulate(fmu, {"drop_height": 0.8})          one run: the peaks (CLI names)
    beam_impact.sweep({"drop_height": [...], ...}, fmu=...)  a grid as Dask tasks: a DataFrame
    beam_impact.load_log("paper.mcap")                       a log as numpy arrays / DataFrame
    beam_impact.fmu_path("fmi3")                             the FMU a wheel carries (or $BEAM_IMPACT_FMU_DIR's)
    python -m beam_impact sweep --fmu PATH --vary KEY=SPEC ... --out FILE.csv

Heavy imports (fmpy, dask, pandas) happen inside the functions, so `import beam_impact` is quick.
"""

from .dask_sweep import sweep
from .fmu import FmuFile, SimulationError, fmu_path, simulate
from .grid import expand, linspace, parse_spec, parse_vary
from .log import Log, LogError, load_log

__all__ = [
    "FmuFile",
    "Log",
    "LogError",
    "SimulationError",
    "expand",
    "fmu_path",
    "linspace",
    "load_log",
    "parse_spec",
    "parse_vary",
    "simulate",
    "sweep",
]
__version__ = "0.1.0"
