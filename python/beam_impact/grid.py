"""Grids of scenarios, with the semantics of `beam-impact sweep` (src/sweep.rs).

A grid is a dict {field: [values]}; its scenarios are the product of the lists in the dict's
order, the last field varying fastest (`itertools.product`). A `--vary` SPEC is
`start:stop:count` (inclusive, linear: value i is `start + (stop - start) * i / (count - 1)` to 15
significant digits, the last exactly `stop`; count 1 is `start`) or a comma list. Integer fields
are rounded (half away from zero) and their duplicates dropped, the first kept. The arithmetic is
the CLI's, so both give the same bits.

Values are read per field: numbers; "auto" (0 in the FMU) for the time steps, the element counts
and `modal_cutoff`; "mean", "left", "right" (0, 1, 2 in the FMU) for `stress_recovery`;
"converged", "paper" (0, 1) for `method`. In results they are shown as the CLI writes them: "auto"
for a zero, the names, whole numbers for integer fields.
"""

from __future__ import annotations

import itertools
import math
from typing import Any, Iterable

#: Integer fields of the scenario (the FMU's Integer parameters).
INTEGER_FIELDS = frozenset(
    {"upper.elements_to_contact", "upper.elements_beyond_contact", "lower.elements", "stress_recovery", "method"}
)
#: Time steps: "auto" is 0.
TIME_STEP_FIELDS = frozenset({"step_free", "step_contact"})
#: Fields whose 0 is "auto": the time steps, the element counts and the modal cut-off.
AUTO_FIELDS = TIME_STEP_FIELDS | {"upper.elements_to_contact", "upper.elements_beyond_contact", "lower.elements",
                                  "modal_cutoff"}
#: stress_recovery's names in index order.
RECOVERY_NAMES = ("mean", "left", "right")
#: method's names in index order (0 converged, 1 paper).
METHOD_NAMES = ("converged", "paper")
#: Fields with named values.
SYMBOLIC = {"stress_recovery": RECOVERY_NAMES, "method": METHOD_NAMES}

#: The five peaks, as in the CLI's `summary.peaks` and sweep columns.
PEAKS = (
    "lower_tip_deflection",
    "lower_clamp_bending_stress",
    "lower_clamp_shear_stress",
    "upper_contact_bending_stress",
    "contact_force",
)


def parse_value(field: str, text: Any) -> float:
    """One value of `field` in the FMU's parameter form."""
    if isinstance(text, bool):
        raise ValueError(f"{field} takes a number, got {text!r}")
    if isinstance(text, (int, float)):
        return float(text)
    t = str(text).strip()
    if field in AUTO_FIELDS and t == "auto":
        return 0.0
    if field in SYMBOLIC and t in SYMBOLIC[field]:
        return float(SYMBOLIC[field].index(t))
    try:
        return float(t)
    except ValueError:
        raise ValueError(f"{field} takes {_expected(field)}, got `{t}`") from None


def _expected(field: str) -> str:
    if field in TIME_STEP_FIELDS:
        return 'a time step in s or "auto"'
    if field in AUTO_FIELDS:
        return f'{"a whole number" if field in INTEGER_FIELDS else "a number"} or "auto"'
    if field in SYMBOLIC:
        *rest, last = SYMBOLIC[field]
        return f"{', '.join(rest)} or {last}"
    if field in INTEGER_FIELDS:
        return "a whole number"
    return "a number"


def display(field: str, value: float) -> Any:
    """A value as the CLI's CSV shows it: "auto", a recovery's or method's name, an int, or the float."""
    if field in AUTO_FIELDS and value == 0.0:
        return "auto"
    if field in SYMBOLIC and float(value).is_integer() and 0 <= value < len(SYMBOLIC[field]):
        return SYMBOLIC[field][int(value)]
    if field in INTEGER_FIELDS and float(value).is_integer():
        return int(value)
    return value


def round_half_away(x: float) -> float:
    """Rust's f64::round: halves away from zero (Python's round() goes to even)."""
    a = abs(x)
    r = math.floor(a)
    if a - r >= 0.5:
        r += 1
    return math.copysign(float(r), x)


def linspace(start: float, stop: float, count: int) -> list[float]:
    """`count` values from start to stop inclusive, as the CLI computes them."""
    out = []
    for i in range(count):
        if i == 0:
            out.append(start)
        elif i == count - 1:
            out.append(stop)
        else:
            out.append(float(f"{start + (stop - start) * i / (count - 1):.14e}"))
    return out


#: Largest grid a sweep runs, checked before any value is built (the CLI's limit).
MAX_SCENARIOS = 1_000_000


def quoted(text: Any) -> str:
    """At most 200 characters of user text for a one-line message."""
    t = str(text)
    return t if len(t) <= 200 else t[:200] + "..."


def normalize(field: str, values: Iterable[Any]) -> list[float]:
    """Values in parameter form; integer fields rounded and deduplicated (first kept)."""
    parsed = []
    for v in values:
        parsed.append(parse_value(field, v))
        if len(parsed) > MAX_SCENARIOS:
            raise ValueError(f"{field} has more than {MAX_SCENARIOS} values (the sweep's limit): split the sweep")
    if field not in INTEGER_FIELDS:
        return parsed
    bad = next((v for v in parsed if not math.isfinite(v)), None)
    if bad is not None:
        raise ValueError(f"{field} takes a whole number, got {bad}")
    out: list[float] = []
    seen: set[float] = set()
    for v in map(round_half_away, parsed):
        if v + 0.0 not in seen:  # -0.0 and 0.0 are one value
            seen.add(v + 0.0)
            out.append(v)
    return out


def parse_spec(field: str, spec: str) -> list[float]:
    """A SPEC, `start:stop:count` or a comma list, as the CLI reads it."""
    if ":" in spec:
        parts = spec.split(":")
        if len(parts) != 3:
            raise ValueError(f"SPEC is start:stop:count (inclusive, linear) or a comma list, got `{spec}`")
        try:
            count = int(parts[2].strip())
        except ValueError:
            count = 0
        if not 1 <= count <= MAX_SCENARIOS:
            raise ValueError(f"the count of start:stop:count must be a whole number from 1 to {MAX_SCENARIOS}, "
                             f"got `{quoted(parts[2])}`")
        return normalize(field, linspace(parse_value(field, parts[0]), parse_value(field, parts[1]), count))
    return normalize(field, spec.split(","))


def parse_vary(texts: Iterable[str]) -> dict[str, list[float]]:
    """`--vary KEY=SPEC` options into a grid dict (a field given twice is an error)."""
    grid: dict[str, list[float]] = {}
    for text in texts:
        key, sep, spec = text.partition("=")
        key = key.strip()
        if not sep or not key:
            raise ValueError(f"--vary expects KEY=SPEC, got `{text}`")
        if key in grid:
            raise ValueError(f"--vary {key} is given twice")
        try:
            grid[key] = parse_spec(key, spec)
        except ValueError as e:
            raise ValueError(f"--vary {text}: {e}") from None
    return grid


def expand(grid: dict[str, Iterable[Any]]) -> list[dict[str, float]]:
    """Every scenario of the grid in order (the last field fastest), values in parameter form."""
    fields = list(grid)
    values = [normalize(f, grid[f]) for f in fields]
    if math.prod(len(v) for v in values) > MAX_SCENARIOS:
        raise ValueError(f"the grid has more than {MAX_SCENARIOS} scenarios: split the sweep")
    return [dict(zip(fields, point)) for point in itertools.product(*values)]
