"""The Linux wheel works without Rust (issue 31, item 2).

Goal: the wheel scripts/build-wheels.sh makes (tests/run_all.sh builds it once, from the FMUs it
packed, into target/wheels/) installs into a fresh venv whose PATH has no cargo or rustc, and
there runs docs/tutorial.md as test_tutorial.py does, except that `python` is the fresh venv's,
no BEAM_IMPACT_FMU_DIR is set and the working folder has no target/fmu: `beam_impact.fmu_path()`
must find the FMUs the wheel carries, and the native module must be the wheel's. The CLI blocks
run the `beam-impact` the wheel installed into the venv's bin/ (issue 41: the wheel carries the
command, as ruff's and uv's do), found on PATH as in an activated venv.

The wheel is BEAM_IMPACT_WHEEL, or the one manylinux wheel in target/wheels/. Without one the test
is skipped, except where BEAM_IMPACT_REQUIRE_WHEEL=1 (tests/run_all.sh), where it fails.
"""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

from test_doc_snippets import SNIPPETS, make_inputs
from test_glibc import HIGHEST, glibc_versions
from test_python_doc import PAGE as PYTHON_PAGE
from test_python_doc import blocks
from test_tutorial import TIMEOUT, TUTORIAL, runnable

ROOT = Path(__file__).resolve().parents[2]
REQUIRED = os.environ.get("BEAM_IMPACT_REQUIRE_WHEEL") == "1"
#: Variables that would point the fresh venv at the repository's FMUs or package, or at Rust.
DROPPED = ("BEAM_IMPACT_FMU_DIR", "BEAM_IMPACT_FMU", "PYTHONPATH", "VIRTUAL_ENV", "CARGO", "CARGO_HOME",
           "CARGO_TARGET_DIR", "RUSTC", "RUSTUP_HOME", "RUSTUP_TOOLCHAIN")


def the_wheel() -> Path:
    given = os.environ.get("BEAM_IMPACT_WHEEL")
    if given:
        assert Path(given).is_file(), f"BEAM_IMPACT_WHEEL={given}: no such file"
        return Path(given)
    found = sorted((ROOT / "target" / "wheels").glob("beam_impact-*-cp39-abi3-*manylinux*_x86_64*.whl"))
    if not found:
        message = "no Linux wheel in target/wheels: run scripts/build-wheels.sh target/wheels (or set BEAM_IMPACT_WHEEL)"
        if REQUIRED:
            pytest.fail(message, pytrace=False)
        pytest.skip(message)
    assert len(found) == 1, f"more than one Linux wheel in target/wheels: {[p.name for p in found]}"
    return found[0]


def pin(name: str) -> str:
    """The requirement of tests/python/requirements.txt (the same fmpy and matplotlib as the suite;
    pinned or not, as the suite has it)."""
    for line in (ROOT / "tests" / "python" / "requirements.txt").read_text().splitlines():
        if line.split("#")[0].strip() == name or line.startswith(f"{name}=="):
            return line.split()[0]
    raise AssertionError(f"tests/python/requirements.txt has no {name}")


def without_rust(path: str) -> str:
    """PATH less every folder that holds cargo or rustc."""
    return os.pathsep.join(d for d in path.split(os.pathsep)
                           if d and not any(os.path.exists(os.path.join(d, tool)) for tool in ("cargo", "rustc")))


@pytest.fixture(scope="module")
def installed(tmp_path_factory):
    """A fresh venv with the wheel (and matplotlib for the tutorial's plot): (its python, env)."""
    wheel = the_wheel()
    venv = tmp_path_factory.mktemp("wheel-venv")
    subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True, timeout=TIMEOUT)
    python = venv / "bin" / "python"
    # matplotlib for the plots; mcap and mcap-protobuf-support for docs/logs.md's reader without
    # beam_impact (the page names them to install).
    done = subprocess.run([str(python), "-m", "pip", "install", "--quiet", "--disable-pip-version-check", str(wheel),
                           pin("fmpy"), pin("matplotlib"), pin("mcap"), pin("mcap-protobuf-support")],
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, f"pip install {wheel.name} failed:\n{done.stdout}{done.stderr}"
    env = {k: v for k, v in os.environ.items() if k not in DROPPED}
    # The venv's bin/ first, as an activated venv has it: its python and the wheel's `beam-impact`.
    env.update(PATH=os.pathsep.join([str(venv / "bin"), without_rust(os.environ.get("PATH", ""))]),
               MPLBACKEND="Agg")
    for tool in ("cargo", "rustc"):
        assert shutil.which(tool, path=env["PATH"]) is None, f"{tool} is still on the test's PATH"
    return python, venv, env, wheel


#: Where the Linux wheel keeps its command (maturin's data folder, installed into bin/ by pip).
COMMAND = "beam_impact-{version}.data/scripts/beam-impact"


def wheel_version(wheel: Path) -> str:
    return wheel.name.split("-")[1]


def test_the_wheel_carries_the_command_linked_for_glibc_2_17(tmp_path):
    """Issue 41: the wheel's `beam-impact` is an executable (mode 755 in the archive, which pip
    keeps) in the wheel's scripts, and, as the FMUs' library and the native module, needs no
    glibc symbol newer than GLIBC_2.17 (`objdump -T`, the check of test_glibc.py)."""
    wheel = the_wheel()
    name = COMMAND.format(version=wheel_version(wheel))
    with zipfile.ZipFile(wheel) as archive:
        assert name in archive.namelist(), f"{wheel.name} has no {name}"
        assert archive.getinfo(name).external_attr >> 16 & 0o777 == 0o755
        command = Path(archive.extract(name, tmp_path))
    assert command.read_bytes()[:4] == b"\x7fELF"
    versions = glibc_versions(command)
    assert versions, "no GLIBC symbol versions found: not a glibc-linked executable?"
    highest = max(versions)
    assert highest <= HIGHEST, f"the wheel's beam-impact needs GLIBC_{'.'.join(map(str, highest))}, newer than 2.17"


def test_beam_impact_run_from_the_venv_s_path_equals_the_package_s_run(installed, tmp_path):
    """`pip install WHEEL` puts `beam-impact` into the venv's bin/: found there on PATH (no other
    on it), `beam-impact run` works, and its `--json` document gives the peaks `beam_impact.run`
    gives in the same venv (one solver, two doors)."""
    python, venv, env, _ = installed
    found = shutil.which("beam-impact", path=env["PATH"])
    assert found == str(venv / "bin" / "beam-impact"), found
    done = subprocess.run(["beam-impact", "run", "--set", "duration=0.05", "--json", "run.json", "--no-mcap"],
                          cwd=tmp_path, env=env, capture_output=True, text=True, timeout=TIMEOUT)
    assert done.returncode == 0, done.stderr
    assert "quality:" in done.stdout, done.stdout
    probe = ("import json, beam_impact\n"
             "r = beam_impact.run(duration=0.05)\n"
             "print(json.dumps(r.peaks))\n")
    ran = subprocess.run([str(python), "-c", probe], cwd=tmp_path, env=env, capture_output=True, text=True,
                         timeout=TIMEOUT)
    assert ran.returncode == 0, ran.stderr
    by_command = json.loads((tmp_path / "run.json").read_text())["summary"]["peaks"]
    by_package = json.loads(ran.stdout.splitlines()[-1])
    assert by_package and all(by_command[k] == v for k, v in by_package.items()), (by_command, by_package)


def test_the_wheel_carries_the_module_and_both_fmus(installed, tmp_path):
    """Imported from the fresh venv: the package, its native module and the FMUs fmu_path() finds all
    lie inside the venv's site-packages, and the FMUs are the wheel's bytes."""
    python, venv, env, wheel = installed
    probe = ("import beam_impact, beam_impact._native as n\n"
             "print(beam_impact.__file__); print(n.__file__)\n"
             "print(beam_impact.fmu_path('fmi2')); print(beam_impact.fmu_path('fmi3'))\n")
    done = subprocess.run([str(python), "-c", probe], cwd=tmp_path, env=env, capture_output=True, text=True,
                          timeout=TIMEOUT)
    assert done.returncode == 0, done.stderr
    package, module, fmi2, fmi3 = done.stdout.split()
    site = str(venv.resolve())
    for path in (package, module, fmi2, fmi3):
        assert str(Path(path).resolve()).startswith(site), f"{path} is not inside the fresh venv {site}"
    assert module.endswith("_native.abi3.so")
    with zipfile.ZipFile(wheel) as archive:
        for fmi, path in (("fmi2", fmi2), ("fmi3", fmi3)):
            assert Path(path).read_bytes() == archive.read(f"beam_impact/fmus/{fmi}/BeamImpact.fmu")


def test_fmu_path_refuses_an_unknown_version(installed, tmp_path):
    python, _, env, _ = installed
    done = subprocess.run([str(python), "-c", "import beam_impact; beam_impact.fmu_path('fmi1')"], cwd=tmp_path,
                          env=env, capture_output=True, text=True, timeout=TIMEOUT)
    assert done.returncode != 0
    assert "version must be one of fmi2, fmi3, got 'fmi1'" in done.stderr


def test_beam_impact_fmu_dir_wins_over_the_wheels_fmus(installed, tmp_path):
    """fmu_path()'s order: BEAM_IMPACT_FMU_DIR's FMU when it holds one, else the wheel's."""
    python, venv, env, _ = installed
    (tmp_path / "packed" / "fmi3").mkdir(parents=True)
    (tmp_path / "packed" / "fmi3" / "BeamImpact.fmu").write_bytes(b"not read by fmu_path")
    probe = "import beam_impact; print(beam_impact.fmu_path('fmi3')); print(beam_impact.fmu_path('fmi2'))"
    done = subprocess.run([str(python), "-c", probe], cwd=tmp_path, env=dict(env, BEAM_IMPACT_FMU_DIR=str(tmp_path / "packed")),
                          capture_output=True, text=True, timeout=TIMEOUT)
    assert done.returncode == 0, done.stderr
    fmi3, fmi2 = done.stdout.split()
    assert fmi3 == str(tmp_path / "packed" / "fmi3" / "BeamImpact.fmu")
    assert str(Path(fmi2).resolve()).startswith(str(venv.resolve())), fmi2  # no fmi2 there: the wheel's


def test_the_tutorial_runs_from_the_wheel(installed, tmp_path):
    """Every ```sh and ```python block of the tutorial, in order, in a folder without target/fmu;
    the FMU's peaks are the CLI's (the FMU block prints both)."""
    python, _, env, _ = installed
    shutil.copytree(ROOT / "examples", tmp_path / "examples")
    shutil.copytree(ROOT / "docs", tmp_path / "docs")
    outputs = []
    for n, (info, body) in enumerate(runnable(TUTORIAL.read_text()), 1):
        args = ["bash", "-euo", "pipefail", "-c", body] if info == "sh" else [str(python), "-c", body]
        done = subprocess.run(args, cwd=tmp_path, env=env, capture_output=True, text=True, timeout=TIMEOUT)
        output = done.stdout + done.stderr
        assert done.returncode == 0, f"tutorial block {n} (```{info}) failed from the wheel:\n{body}\n--- output:\n{output}"
        outputs.append((info, body, output))
    assert not (tmp_path / "target").exists(), "the tutorial made a target/ folder: an FMU may have come from it"
    fmu = [out for info, body, out in outputs if info == "python" and "fmpy.simulate_fmu" in body]
    assert fmu, "the tutorial has no fmpy block"
    pairs = re.findall(r"FMU\s+(\S+)\s+CLI\s+(\S+)", fmu[0])
    assert len(pairs) >= 3, fmu[0]
    for got, want in pairs:
        # Both print 4 decimals of MPa of the same internal steps (the FMU takes the CLI's steps).
        assert float(got) == pytest.approx(float(want), rel=1e-6), fmu[0]
    wrapped = [out for info, body, out in outputs if info == "python" and "beam_impact.simulate(" in body]
    assert wrapped and "design.pass False" in wrapped[0], wrapped
    assert (tmp_path / "sweep-stresses.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def wheel_check(wheel: Path, platform: str = "linux", fmus: str = "linux") -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, str(ROOT / "scripts" / "wheel_check.py"), str(wheel), platform, fmus],
                          capture_output=True, text=True, timeout=TIMEOUT)


def test_wheel_check_passes_the_wheel_and_refuses_altered_copies(tmp_path):
    """scripts/wheel_check.py (run by build-wheels.sh on every wheel) passes the built wheel and
    refuses: a copy without its FMI 3 FMU (RECORD still lists it), one renamed to another
    platform's tag, and the same wheel checked as carrying every platform's FMU binaries."""
    wheel = the_wheel()
    done = wheel_check(wheel)
    assert done.returncode == 0, done.stderr
    assert "needs GLIBC_2.17 at most" in done.stdout and "exports PyInit__native" in done.stdout

    without = tmp_path / wheel.name
    with zipfile.ZipFile(wheel) as source, zipfile.ZipFile(without, "w") as copy:
        for item in source.infolist():
            if item.filename != "beam_impact/fmus/fmi3/BeamImpact.fmu":
                copy.writestr(item, source.read(item.filename))
    done = wheel_check(without)
    assert done.returncode == 1
    assert "no beam_impact/fmus/fmi3/BeamImpact.fmu" in done.stderr

    renamed = tmp_path / "beam_impact-0.1.0-cp39-abi3-manylinux_2_28_x86_64.whl"
    shutil.copy(wheel, renamed)
    done = wheel_check(renamed)
    assert done.returncode == 1 and "is not beam_impact-V-cp39-abi3-" in done.stderr

    done = wheel_check(wheel, fmus="all")
    assert done.returncode == 1 and "binaries/win64/BeamImpact.dll" in done.stderr


def test_the_wheel_is_typed():
    """Issue 41: the package says it carries inline types (PEP 561), so mypy and pyright read them."""
    with zipfile.ZipFile(the_wheel()) as archive:
        assert "beam_impact/py.typed" in archive.namelist()


def test_the_wheel_carries_the_example_scenarios(installed, tmp_path):
    """Issue 41: `beam_impact.examples()` from a wheel install gives the repository's example
    scenarios from inside the fresh venv, and one that names a motion file runs from there."""
    python, venv, env, wheel = installed
    probe = ("import beam_impact\n"
             "e = beam_impact.examples()\n"
             "print(e['arrestor.toml']); print(sorted(e))\n"
             "r = beam_impact.run(e['vessel.toml'], duration=0.01, check_sensitivity=False)\n"
             "print(r['summary']['time'])\n")
    done = subprocess.run([str(python), "-c", probe], cwd=tmp_path, env=env, capture_output=True, text=True,
                          timeout=TIMEOUT)
    assert done.returncode == 0, done.stderr
    arrestor, names, time = done.stdout.splitlines()
    assert str(Path(arrestor).resolve()).startswith(str(venv.resolve())), arrestor
    assert names == repr(sorted(p.name for p in (ROOT / "examples").glob("*.toml")))
    assert float(time) == pytest.approx(0.01)


# Every page's Python from the wheel (issue 41: "every page of the docs runs from a wheel install"):
# the fresh venv's python, in an empty temporary folder (no examples/, no target/fmu, nothing of
# the repository on sys.path), with the wheel's FMUs, examples and command.

#: Pages whose marked snippets read a checkout's packed FMUs (`target/fmu/...`, which
#: `beam-impact pack --out target/fmu` makes) rather than `beam_impact.fmu_path()`: from the wheel
#: they run in a folder whose target/fmu is the wheel's own FMUs. No other page may (the list
#: can only shrink: each of these would read `beam_impact.fmu_path()` instead).
CHECKOUT_FMU_PAGES = {"README.md", "docs/fmu.md"}


def run_python(python: Path, env: dict, cwd: Path, body: str) -> tuple[int | str, str]:
    try:
        done = subprocess.run([str(python), "-c", body], cwd=cwd, env=env, capture_output=True, text=True,
                              timeout=TIMEOUT)
        return done.returncode, done.stdout + done.stderr
    except subprocess.TimeoutExpired as e:
        return "timeout", f"{e.stdout or ''}{e.stderr or ''}\n(timed out after {TIMEOUT} s)"


def wheel_fmus(python: Path, env: dict, cwd: Path) -> Path:
    """The installed package's FMU folder (`fmus/fmi2/BeamImpact.fmu`, `fmus/fmi3/...`)."""
    code, out = run_python(python, env, cwd, "import beam_impact; print(beam_impact.fmu_path())")
    assert code == 0, out
    return Path(out.strip()).parents[1]


def test_the_fresh_venv_s_python_has_nothing_of_the_repository_on_its_path(installed, tmp_path):
    python, venv, env, _ = installed
    code, out = run_python(python, env, tmp_path, "import sys, beam_impact\nprint(beam_impact.__file__)\n"
                                                  "print('\\n'.join(p for p in sys.path if p))")
    assert code == 0, out
    package, *path = out.splitlines()
    assert str(Path(package).resolve()).startswith(str(venv.resolve())), package
    assert not [p for p in path if str(Path(p).resolve()).startswith(str(ROOT))], path


def test_python_md_runs_from_the_wheel_in_an_empty_folder(installed, tmp_path):
    """docs/python.md's ```python blocks, in order, as test_python_doc.py runs them but from the
    wheel: the example scenario is `beam_impact.examples()`'s, the FMU `beam_impact.fmu_path()`'s
    (no BEAM_IMPACT_FMU_DIR, no target/fmu); the sweep's table has the CLI's columns and the
    FMU route gives the native numbers (the page prints True)."""
    python, _, env, _ = installed
    outputs = []
    for n, (info, body) in enumerate(blocks(PYTHON_PAGE.read_text()), 1):
        if info != "python":
            continue
        code, output = run_python(python, env, tmp_path, body)
        assert code == 0, f"docs/python.md block {n} failed from the wheel ({code}):\n{body}\n--- output:\n{output}"
        outputs.append(output)
    assert not (tmp_path / "target").exists() and not (tmp_path / "examples").exists()
    assert outputs[-1].rstrip().endswith("True"), outputs[-1]
    header = (tmp_path / "sweep.csv").read_text().splitlines()[0].split(",")
    assert header[:2] == ["drop_height", "damping_ratio"] and "peak_time.contact.force" in header
    assert len(header) == 63 + 1  # the CLI sweep's columns for two varied fields
    assert (tmp_path / "sweep.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


@pytest.fixture(scope="module")
def made_by_the_command(installed, tmp_path_factory):
    """paper.mcap and steps.csv, as test_doc_snippets.py makes them, by the wheel's `beam-impact`."""
    _, _, env, _ = installed
    folder = tmp_path_factory.mktemp("wheel-snippet-inputs")
    make_inputs(folder, "beam-impact", env)
    return folder


@pytest.mark.parametrize("page,line,body", SNIPPETS, ids=[f"{p}:{n}" for p, n, _ in SNIPPETS])
def test_every_marked_snippet_runs_from_the_wheel(installed, made_by_the_command, tmp_path, page, line, body):
    """Each snippet test_doc_snippets.py runs (README, docs/fmu.md, docs/logs.md,
    docs/python-reference.md, ...), in an empty folder with the command's paper.mcap and
    steps.csv; a checkout's target/fmu only for the pages that still read it (CHECKOUT_FMU_PAGES),
    there the wheel's FMUs."""
    python, _, env, _ = installed
    for name in ("paper.mcap", "steps.csv"):
        shutil.copy(made_by_the_command / name, tmp_path / name)
    if "target/fmu" in body:
        assert page in CHECKOUT_FMU_PAGES, f"{page}:{line} reads target/fmu: use beam_impact.fmu_path() instead"
        (tmp_path / "target").mkdir()
        (tmp_path / "target" / "fmu").symlink_to(wheel_fmus(python, env, tmp_path), target_is_directory=True)
    code, output = run_python(python, env, tmp_path, body)
    assert code == 0, f"{page}:{line} failed from the wheel ({code}):\n{body}\n--- its output:\n{output[-3000:]}"


def test_wheels_md_and_the_reference_s_cluster_script_run_from_the_wheel(installed, tmp_path):
    """docs/wheels.md's marked block, and docs/python-reference.md's LocalCluster script saved as a
    script (as test_package.py runs it, with no path replaced), from the fresh venv."""
    python, _, env, _ = installed
    page = (ROOT / "docs" / "wheels.md").read_text()
    marker = "<!-- run by tests/python/test_wheel.py"
    start = page.index("```python\n", page.index(marker)) + len("```python\n")
    code, output = run_python(python, env, tmp_path, page[start:page.index("```", start)])
    assert code == 0, output
    reference = (ROOT / "docs" / "python-reference.md").read_text()
    at = reference.index('  if __name__ == "__main__":')
    begin = reference.rindex("```python\n", 0, at) + len("```python\n")
    script = "\n".join(line[2:] for line in reference[begin:reference.index("```", begin)].splitlines())
    assert "LocalCluster" in script and "beam_impact.fmu_path()" in script, script
    (tmp_path / "study.py").write_text(script)
    done = subprocess.run([str(python), "study.py"], cwd=tmp_path, env=env, capture_output=True, text=True,
                          timeout=300)
    assert done.returncode == 0, done.stderr[-2000:]
    table = (tmp_path / "sweep.csv").read_text().splitlines()
    assert len(table) == 4 and table[0].startswith("drop_height,peak.lower.tip_deflection"), table[:2]
