"""beam_impact: the beam-impact solver from Python (its Rust code, or its FMU through fmpy), design
sweeps on threads or a Dask cluster, and its MCAP log reader.

    beam_impact.run(drop_height=0.8)                         one run, no FMU: `beam-impact run --json`
    beam_impact.sweep({"drop_height": [...], ...})           a grid as Dask tasks: a DataFrame
    beam_impact.sweep(grid, engine="fmu", fmu=PATH)          the same through the FMU
    beam_impact.campaign("vessel-sea.toml", events=1000)      impacts in a sea state: rows, statistics, table
    beam_impact.simulate(fmu, {"drop_height": 0.8})          one FMU run: the peaks (CLI names)
    beam_impact.load_log("paper.mcap")                       a log as numpy arrays / DataFrame
    python -m beam_impact sweep [--scenario FILE | --fmu PATH] --vary KEY=SPEC ... --out FILE.csv
    beam_impact.fmu_path("fmi3")                             the FMU a wheel carries (or $BEAM_IMPACT_FMU_DIR's)

Heavy imports (fmpy, dask, pandas) happen inside the functions, so `import beam_impact` is quick.
"""

from .campaign import CampaignInterrupted, CampaignResult, campaign
from .dask_sweep import sweep
from .example_files import examples
from .fmu import FmuFile, ScenarioError, SimulationError, fmu_path, simulate
from .grid import expand, linspace, parse_spec, parse_vary
from .log import Log, LogError, load_log
from .native_run import RunResult, run

__all__ = [
    "CampaignInterrupted",
    "CampaignResult",
    "FmuFile",
    "Log",
    "LogError",
    "RunResult",
    "ScenarioError",
    "SimulationError",
    "campaign",
    "examples",
    "expand",
    "fmu_path",
    "linspace",
    "load_log",
    "parse_spec",
    "parse_vary",
    "run",
    "simulate",
    "sweep",
]
__version__ = "0.1.0"
