"""Load a beam-impact MCAP log into numpy arrays: moved to the `beam_impact` package
(python/beam_impact/log.py, `from beam_impact import load_log`); this file re-exports it so
that `from load_log import load_log` and `python load_log.py paper.mcap` keep working.
"""

from __future__ import annotations

import sys
from pathlib import Path

try:
    from beam_impact.log import CONTACT_TOPIC, MODEL_TOPIC, STEP_TOPIC, Log, load_log, main
except ImportError:  # the package is not installed (`pip install ./python`): use the source tree's
    sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "python"))
    from beam_impact.log import CONTACT_TOPIC, MODEL_TOPIC, STEP_TOPIC, Log, load_log, main

__all__ = ["CONTACT_TOPIC", "MODEL_TOPIC", "STEP_TOPIC", "Log", "load_log", "main"]

if __name__ == "__main__":
    sys.exit(main(sys.argv))
