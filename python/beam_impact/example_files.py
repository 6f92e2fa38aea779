"""`beam_impact.examples()`: the repository's example scenarios, from a wheel or a checkout.

A wheel carries them in the package (`beam_impact/examples/`, put there by
scripts/build-wheels.sh with the motion file one of them names); an install from source or a
checkout reads the repository's `examples/` folder. The docs' Python runs from either.
"""

from __future__ import annotations

from pathlib import Path


def examples() -> dict[str, str]:
    """The example scenarios by file name (`"arrestor.toml"`, ...): their paths, to pass to
    `beam_impact.run` or `beam-impact run`. FileNotFoundError where neither the package nor a
    checkout holds them."""
    here = Path(__file__).resolve().parent
    for folder in (here / "examples", here.parent.parent / "examples"):
        found = sorted(folder.glob("*.toml"))
        if found:
            return {p.name: str(p) for p in found}
    raise FileNotFoundError(f"no example scenarios: looked in {here / 'examples'} (a wheel's) and "
                            f"{here.parent.parent / 'examples'} (a checkout's)")
