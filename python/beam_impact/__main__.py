"""`python -m beam_impact sweep --fmu PATH --vary KEY=SPEC ... [--scheduler ADDRESS] --out FILE.csv`
and `python -m beam_impact log FILE.mcap`."""

from __future__ import annotations

import argparse
import sys
import time


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m beam_impact", description=__doc__)
    commands = parser.add_subparsers(dest="command", required=True)
    s = commands.add_parser(
        "sweep",
        help="run a grid of scenarios through the FMU as Dask tasks",
        description="Every combination of the --vary values (the last varying fastest), one FMU run per "
        "scenario as a Dask task; one CSV row per scenario in grid order, with the columns of "
        "`beam-impact sweep` that the FMU gives.",
    )
    s.add_argument("--fmu", required=True, help="the FMU file (target/fmu/fmi2/BeamImpact.fmu)")
    s.add_argument("--vary", action="append", default=[], metavar="KEY=SPEC",
                   help="a varied field: start:stop:count (inclusive, linear) or a comma list (repeatable)")
    s.add_argument("--scheduler", metavar="ADDRESS",
                   help="a Dask scheduler (tcp://host:8786); default: threads on this machine")
    s.add_argument("--stop-time", type=float, default=3.0, help="simulated s per run (default 3)")
    s.add_argument("--workers", type=int, default=None, help="local threads (default: one per core)")
    s.add_argument("--out", required=True, metavar="FILE.csv", help="the rows as CSV")
    s.add_argument("--json", metavar="FILE", help="also write the rows as JSON records")
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

    from .dask_sweep import sweep
    from .grid import parse_vary

    try:
        for target in [args.out, args.json]:
            _check_output(target)
        grid = parse_vary(args.vary)
        started = time.perf_counter()
        frame = sweep(grid, client=args.scheduler, fmu=args.fmu, stop_time=args.stop_time,
                      num_workers=args.workers)
    except (ValueError, FileNotFoundError) as e:
        print(f"python -m beam_impact: {e}", file=sys.stderr)
        return 2
    wall = time.perf_counter() - started
    # Written beside and renamed into place, as the CLI's outputs are.
    _write(args.out, lambda path: frame.to_csv(path, index=False))
    if args.json:
        _write(args.json, lambda path: frame.to_json(path, orient="records", indent=1))
    failed = int((frame["error"] != "").sum())
    if failed:
        print(f"python -m beam_impact: warning: {failed} of {len(frame)} scenarios failed (their rows hold the error)",
              file=sys.stderr)
    print(f"sweep: {len(frame)} scenarios in {wall:.2f} s: {len(frame) - failed} ran, {failed} failed\n"
          f"rows written to {args.out}" + (f" and {args.json}" if args.json else ""))
    return 0


def _check_output(path) -> None:
    """An output must not be a symbolic link, a FIFO, a socket or a folder (the CLI's guard)."""
    import os
    import stat

    if path is None or path == os.devnull:
        return
    try:
        mode = os.lstat(path).st_mode
    except FileNotFoundError:
        return
    if not stat.S_ISREG(mode):
        raise ValueError(f"{path}: not a regular file (a symbolic link, FIFO, socket or folder is refused as output)")


def _write(path, write) -> None:
    import os

    if path == os.devnull:
        write(path)
        return
    partial = f"{path}.partial"
    if os.path.lexists(partial):
        os.remove(partial)
    try:
        write(partial)
        os.replace(partial, path)
    finally:
        if os.path.lexists(partial):
            os.remove(partial)


if __name__ == "__main__":
    sys.exit(main())
