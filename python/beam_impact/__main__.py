"""`python -m beam_impact sweep [--scenario FILE | --fmu PATH] --vary KEY=SPEC ... [--scheduler ADDRESS]
--out FILE.csv` and `python -m beam_impact log FILE.mcap`."""

from __future__ import annotations

import argparse
import sys
import time


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m beam_impact", description=__doc__)
    commands = parser.add_subparsers(dest="command", required=True)
    s = commands.add_parser(
        "sweep",
        help="run a grid of scenarios (the Rust solver, or the FMU) as Dask tasks",
        description="Every combination of the --vary values (the last varying fastest), one run per "
        "scenario as a Dask task (the Rust solver itself, or the FMU with --fmu); one CSV row per scenario "
        "in grid order, with the columns of `beam-impact sweep` (with --fmu, those the FMU gives).",
    )
    s.add_argument("--fmu", help="run the FMU file (target/fmu/fmi2/BeamImpact.fmu) instead of the solver itself")
    s.add_argument("--scenario", metavar="FILE",
                   help="the base scenario file (without --fmu; default: the defaults, as the FMU's)")
    s.add_argument("--vary", action="append", default=[], metavar="KEY=SPEC",
                   help="a varied field: start:stop:count (inclusive, linear) or a comma list (repeatable)")
    s.add_argument("--scheduler", metavar="ADDRESS",
                   help="a Dask scheduler (tcp://host:8786); default: threads on this machine")
    s.add_argument("--stop-time", type=float, default=None,
                   help="simulated s per run (default: the scenario's duration, 3 s for the defaults and the FMU)")
    s.add_argument("--workers", type=int, default=None, help="local threads (default: one per core)")
    s.add_argument("--out", required=True, metavar="FILE.csv", help="the rows as CSV")
    s.add_argument("--json", metavar="FILE", help="also write the rows as JSON records")
    s.add_argument("--fatigue", action="store_true",
                   help="each row's fatigue on the scenario's [fatigue] curve (the solver only), as `beam-impact sweep "
                        "--fatigue`")
    lg = commands.add_parser("log", help="print what an MCAP log holds")
    lg.add_argument("file")
    args = parser.parse_args(argv)

    if args.command == "log":
        from .log import main as log_main

        try:
            return log_main(["log", args.file])
        except BrokenPipeError:  # `| head`: the reader went away
            sys.stdout = None
            return 0

    from . import _native
    from .dask_sweep import sweep
    from .grid import parse_vary

    # Every output through the CLI's guard (the native module): no NUL, symbolic link, folder,
    # FIFO, socket or device other than /dev/null; never the FMU or the other output (by device
    # and inode); checked before any run, and again when written (beside, then renamed).
    if args.fmu is not None and args.scenario is not None:
        print("python -m beam_impact: --scenario is for the solver itself; the FMU starts from its own parameters",
              file=sys.stderr)
        return 2
    inputs = [("--fmu", args.fmu)] if args.fmu is not None else []
    if args.scenario is not None:
        inputs.append(("--scenario", args.scenario))
    outputs = [("--out", args.out)] + ([("--json", args.json)] if args.json is not None else [])

    def others(role: str) -> list:
        return [o for o in outputs if o[0] != role]

    try:
        for role, target in outputs:
            _native.check_output(target, role, inputs, others(role), allow_devices=True)
        grid = parse_vary(args.vary)
        started = time.perf_counter()
        from pathlib import Path

        scenario = None if args.scenario is None else Path(args.scenario)
        frame = sweep(grid, client=args.scheduler, fmu=args.fmu, stop_time=args.stop_time,
                      num_workers=args.workers, scenario=scenario, fatigue=args.fatigue)
        wall = time.perf_counter() - started
        render = {"--out": lambda: frame.to_csv(index=False), "--json": lambda: frame.to_json(orient="records", indent=1)}
        for role, target in outputs:
            _native.write_file(target, render[role]().encode(), role, inputs, others(role))
    except (ValueError, FileNotFoundError) as e:
        print(f"python -m beam_impact: {e}", file=sys.stderr)
        return 2
    failed = int((frame["error"] != "").sum())
    if failed:
        print(f"python -m beam_impact: warning: {failed} of {len(frame)} scenarios failed (their rows hold the error)",
              file=sys.stderr)
    print(f"sweep: {len(frame)} scenarios in {wall:.2f} s: {len(frame) - failed} ran, {failed} failed\n"
          f"rows written to {args.out}" + (f" and {args.json}" if args.json else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main())
