"""Grids of scenarios, with the semantics of `beam-impact sweep` (src/studies/sweep.rs).

A grid is a dict {field: [values]}; its scenarios are the product of the lists in the dict's
order, the last field varying fastest (`itertools.product`). A `--vary` SPEC is
`start:stop:count` (inclusive, linear: value i is `start + (stop - start) * i / (count - 1)` to 15
significant digits, the last exactly `stop`; count 1 is `start`) or a comma list. Integer fields
are rounded (half away from zero) and their duplicates dropped, the first kept.

Text is read by the CLI's own parser (the native module: `parse_vary` and `parse_spec` are
`beam-impact sweep --vary`'s, `parse_value` its `--set` value's), so Python accepts exactly what
the CLI accepts (numbers in Rust's grammar: no `1_0`, ASCII digits only) and gives the same bits.
Values are read per field: numbers; "auto" (0 in the FMU) for the time steps, the element counts
and `modal_cutoff`; "mean", "left", "right" (0, 1, 2 in the FMU) for `stress_recovery`;
"converged", "paper" (0, 1) for `method`. In results they are shown as the CLI writes them: "auto"
for a zero, the names, whole numbers for integer fields.
"""

from __future__ import annotations

import itertools
import math
import operator
from typing import Any, Iterable

#: Integer fields of the scenario (the FMU's Integer parameters).
INTEGER_FIELDS = frozenset(
    {"upper.elements_to_contact", "upper.elements_beyond_contact", "lower.elements", "stress_recovery", "method",
     "lower.kind", "contact.law"}
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
    """One value of `field` in the FMU's parameter form: a Python number as it is, text read by the
    CLI's parser (a name the CLI does not know, an FMU-only variable, takes a number)."""
    from . import _native

    if isinstance(text, bool):
        raise ValueError(f"{field} takes a number, got {text!r}")
    if isinstance(text, (int, float)):
        return float(text)
    return _native.parse_value(str(field), str(text))


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
    """`count` values from start to stop inclusive, as the CLI computes them. `count` is bounded as
    `--vary start:stop:count`'s is: a whole number from 1 to MAX_SCENARIOS (ValueError in one
    line otherwise, before any value is built)."""
    try:
        n = None if isinstance(count, bool) else operator.index(count)
    except TypeError:  # 2.5, "10", None
        n = None
    if n is None or not 1 <= n <= MAX_SCENARIOS:
        shown = f"a whole number of {count.bit_length()} bits" if isinstance(count, int) and count.bit_length() > 128 \
            else repr(count)[:100]
        raise ValueError(
            f"linspace: the count must be a whole number from 1 to {MAX_SCENARIOS} (the limit of a sweep and of "
            f"--vary start:stop:count), got {shown}")
    count = n
    ends = [_finite(v) for v in (start, stop)]
    if None in ends:
        bad = (start, stop)[ends.index(None)]
        raise ValueError(f"linspace: start and stop must be finite numbers, got {repr(bad)[:100]}")
    start, stop = ends
    span = stop - start
    out = []
    for i in range(count):
        if i == 0:
            out.append(start)
        elif i == count - 1:
            out.append(stop)
        else:
            # As the CLI: where stop - start overflows, the same point as start (1 - t) + stop t.
            t = i / (count - 1)
            x = start + span * i / (count - 1) if math.isfinite(span) else start * (1.0 - t) + stop * t
            out.append(float(f"{x:.14e}"))
    return out


def _finite(value: Any) -> float | None:
    """`value` as a finite float, or None (a bool, text, NaN, an infinity, an overflowing int)."""
    if isinstance(value, (bool, str, bytes)):
        return None
    try:
        x = float(value)
    except (TypeError, ValueError, OverflowError):
        return None
    return x if math.isfinite(x) else None


#: Largest grid a sweep runs, checked before any value is built (the CLI's limit).
MAX_SCENARIOS = 1_000_000


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
    """A SPEC, `start:stop:count` or a comma list, read by the CLI's parser (`--vary field=SPEC`)."""
    (values,) = parse_vary([f"{field}={spec}"]).values()
    return values


def parse_vary(texts: Iterable[str]) -> dict[str, list[float]]:
    """`--vary KEY=SPEC` options into a grid dict, read by the CLI's parser (`beam-impact sweep
    --vary`, through the native module): what the CLI refuses (an unknown field, a field given
    twice, `1_0`, non-ASCII digits) raises ValueError with the CLI's one-line message."""
    from . import _native

    return dict(_native.parse_vary(list(texts)))


def expand(grid: dict[str, Iterable[Any]]) -> list[dict[str, float]]:
    """Every scenario of the grid in order (the last field fastest), values in parameter form."""
    fields = list(grid)
    values = [normalize(f, grid[f]) for f in fields]
    if math.prod(len(v) for v in values) > MAX_SCENARIOS:
        raise ValueError(f"the grid has more than {MAX_SCENARIOS} scenarios: split the sweep")
    return [dict(zip(fields, point)) for point in itertools.product(*values)]
