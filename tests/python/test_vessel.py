"""BeamImpact on a vessel in waves: a second FMU drives the supports (issue 17, item 4).

VesselMotion (`fmu/vessel/vessel_motion.c`, an FMI 2 co-simulation FMU built here with gcc
against its FMI 2 types `fmu/vessel/fmi2_abi.h`; `beam-impact pack --ssp` builds the same source) is the heave and pitch of a walk-to-work
vessel in a regular head-sea wave (linear RAOs, steady state), projected onto the two supports:
the bridge's hinge heaves, the arrestor's clamp heaves and rotates (docs/moving-supports.md has the
conventions). A fixed-step master (fmpy's low-level `FMU2Slave`, FMI 2 co-simulation, h = 1 ms,
3 s from the impact; `tests/python/vessel_master.py`, shared with docs/plot_vessel_phase.py)
couples them both ways:

    VesselMotion -> BeamImpact: the nine support motions (positions, rates, second rates)
    BeamImpact -> VesselMotion: upper.hinge_reaction_force, lower.clamp_reaction_force,
                                lower.clamp_reaction_moment (-> the deck load on the vessel)

At each communication point t_n the master reads the vessel's motion at t_n (a function of time
alone: no input reaches it), sets it on BeamImpact (from t_n on each support moves as
z_n + v_n tau + a_n tau^2 / 2), reads BeamImpact's outputs at t_n, sets the reactions on the
vessel, reads the deck load (direct feedthrough), then steps both to t_n + h. No algebraic loop:
the motion does not depend on the reactions. The motion at t = 0 is also set in BeamImpact's
initialization mode, so its initial state (the bridge falling under g plus the hinge's
acceleration, the beams touching with the supports' offset) is the one of that motion. The
vessel's motion is prescribed, not solved: the gangway and the arrestor (24 t) against a 5 900 t
vessel; the deck load is read back so that a vessel model could use it, and
`deck.heave_acceleration` bounds what leaving it out neglects.

Checks (each can fail):
- VesselMotion compiles without a warning under -Wall -Wextra, `validate_fmu` finds nothing,
  fmpy loads it (all 34 functions), unsupported calls and bad parameters fail with a reason.
- Its outputs are the closed form (an independent numpy transcription), its rates are the
  derivatives of its positions (central differences), the arrestor's end moves with the deck point
  under it, and in the long-wave limit a deck point follows the surface of a head sea.
- BeamImpact takes the motion without a warning. The values sampled at consecutive points leave
  its constant-acceleration prediction by the cosines' Taylor remainders only, measured 5.4e-11 m
  (position), 1.9e-7 m/s (velocity) and 3.7e-4 m/s^2 (acceleration) per 1 ms step; against its
  tolerance (src/model/support_motion.rs: |a_1 - a_0| tau + 5 % of max|a| tau for the velocity,
  |a_1 - a_0| tau^2 / 2 + 5 % of (max|v| tau + max|a| tau^2 / 2) for the position) that is at
  most 1.6e-6 of it for
  positions and 0.48 for velocities (a sampled smooth motion stays near 1/2 there: the
  remainder is a' tau^2 / 2, the tolerance's first term a' tau^2). A master that sends positions
  without rates is warned (fmi2Warning, the input named).
- Relations between BeamImpact's outputs and the motion: each tip's absolute position is its
  support's motion plus its deflection (measured to 5.4e-11 m: BeamImpact's motion at t_n is the
  quadratic from t_{n-1}), and in contact the gap between the bridge's contact point and the
  arrestor's end, both absolute, is F_c / k_c (to 2.9e-11 m; 4e-16 m on fixed supports).
- The energy verdict stays trusted: `quality.trusted`, and the largest |energy.residual|, 23 J,
  within 1 % of the energy that flows (173 kJ with the supports' work).
- A calm sea (zero wave amplitude: all nine inputs exactly 0) reproduces the fixed supports'
  peaks (measured bit for bit).
- A phase sweep over the wave phase at the impact (12 phases over one period) moves the peaks by
  more than the solver's own 1 % discretisation tolerance (measured sigma_a 420-517 MPa, sigma_b
  242-327 MPa, tau_a 61-76 MPa, F_c 7.9-10.4 MN, against 468.9, 316.1, 66.5 MPa and 9.75 MN on
  fixed supports), each rising with the supports' closing speed at the impact.
- docs/plot_vessel_phase.py draws the sweep and prints its table.
- The deck load read back is the reactions', and what prescribing the vessel's motion neglects
  (the load moving a 5 900 t vessel) stays below 3 % of its heave (measured 7.7 mm).

The whole file takes about 20 s on two cores (about 1 s per 3 s master run, 14 runs).
"""

from __future__ import annotations

import math
import os
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from fmpy.fmi2 import fmi2OK, fmi2Warning
from fmpy.validation import validate_fmu

import vessel_master as vm

ROOT = Path(__file__).resolve().parents[2]
PHASES = 12  # wave phases at the impact, over one period
H = vm.STEP


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    """(VesselMotion.fmu, gcc's stderr), built with gcc -Wall -Wextra."""
    try:
        return vm.build_vessel_fmu(tmp_path_factory.mktemp("vessel"))
    except RuntimeError as e:
        if "gcc not found" in str(e):
            pytest.skip(str(e))
        raise


@pytest.fixture(scope="module")
def vessel_fmu(built):
    return built[0]


@pytest.fixture(autouse=True)
def in_tmp(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)


def closed_form(p: dict, booleans: dict, t: np.ndarray) -> dict[str, np.ndarray]:
    """The vessel's outputs from docs/moving-supports.md's formulas, written again here (numpy)."""
    omega = 2 * math.pi / p["wave.period"]
    k = omega**2 / p["gravity"]
    psi = omega * t + p["wave.phase"]
    za = p["wave.amplitude"]

    def rates(amplitude, phase):
        return (amplitude * np.cos(psi + phase), -amplitude * omega * np.sin(psi + phase),
                -amplitude * omega**2 * np.cos(psi + phase))

    z = rates(p["heave.rao"] * za, p["heave.phase"])
    theta = rates(p["pitch.rao"] * k * za, p["pitch.phase"])
    gh = 1.0 if booleans.get("hinge.on_vessel", True) else 0.0
    gc = 1.0 if booleans.get("clamp.on_vessel", True) else 0.0
    out = {"wave.elevation": za * np.cos(psi), "vessel.heave": z[0], "vessel.pitch": theta[0]}
    for j, suffix in enumerate(("", "_velocity", "_acceleration")):
        out["upper.hinge_heave" + suffix] = gh * (z[j] - p["hinge.x"] * theta[j])
        out["lower.clamp_heave" + suffix] = gc * (z[j] - p["clamp.x"] * theta[j])
        out["lower.clamp_rotation" + suffix] = gc * -p["clamp.direction"] * theta[j]
    return out


def amplitudes(p: dict) -> dict[str, float]:
    """An upper bound of each support coordinate's amplitude (m or rad) and the wave frequency."""
    omega = 2 * math.pi / p["wave.period"]
    theta = p["pitch.rao"] * omega**2 / p["gravity"] * p["wave.amplitude"]
    z = p["heave.rao"] * p["wave.amplitude"]
    return {"upper.hinge_heave": z + abs(p["hinge.x"]) * theta, "lower.clamp_heave": z + abs(p["clamp.x"]) * theta,
            "lower.clamp_rotation": abs(p["clamp.direction"]) * theta, "omega": omega}


def vessel_alone(vessel_fmu: Path, tmp_path: Path, parameters: dict, steps: int, step: float):
    """Steps VesselMotion alone; returns (parameters read back, {output: array over t_n})."""
    vm.listen()
    vessel = vm.Slave(vessel_fmu, "alone", tmp_path / "unzip")
    vessel.fmu.setupExperiment(startTime=0.0)
    vessel.fmu.enterInitializationMode()
    vessel.set_values(parameters)
    vessel.fmu.exitInitializationMode()
    rows = []
    for n in range(steps + 1):
        rows.append(vessel.get(*vm.VESSEL_OUTPUTS))
        if n < steps:
            assert vessel.do_step(n * step, step) == fmi2OK
    names = [v.name for v in vessel.md.modelVariables if v.causality == "parameter" and v.type == "Real"]
    read = dict(zip(names, vessel.get(*names)))
    assert not vessel.messages, vessel.messages
    vessel.close()
    return read, {k: np.array(v) for k, v in zip(vm.VESSEL_OUTPUTS, np.array(rows).T)}


# ---- VesselMotion alone ---------------------------------------------------------------------------

def test_vessel_fmu_compiles_clean_validates_and_loads(built, tmp_path):
    fmu, gcc_stderr = built
    assert gcc_stderr == "", f"gcc warnings:\n{gcc_stderr}"
    assert validate_fmu(str(fmu)) == []
    vm.listen()
    # fmpy looks up all 34 functions when it loads the library: loading proves they exist.
    vessel = vm.Slave(fmu, "probe", tmp_path / "unzip")
    vessel.fmu.setupExperiment(startTime=0.0)
    vessel.fmu.enterInitializationMode()
    vessel.set_values({"wave.period": 0.0})
    # In initialization mode the outputs at the start time need valid parameters: read fails.
    with pytest.raises(Exception, match="status 3"):
        vessel.get("upper.hinge_heave")
    with pytest.raises(Exception, match="status 3"):
        vessel.fmu.exitInitializationMode()
    assert any(status == 3 and "wave.period (s) must be in (0, 10000], got 0" in message
               for status, _, message in vessel.messages), vessel.messages
    vessel.fmu.freeInstance()

    vessel = vm.Slave(fmu, "probe2", tmp_path / "unzip2")
    vessel.fmu.setupExperiment(startTime=0.0)
    vessel.fmu.enterInitializationMode()
    vessel.fmu.exitInitializationMode()
    # Parameters are fixed after initialization; outputs are not inputs.
    for bad in ({"wave.amplitude": 2.0}, {"hinge.on_vessel": False}, {"deck.force": 1.0}):
        with pytest.raises(Exception, match="status 3"):
            vessel.set_values(bad)
    with pytest.raises(Exception, match="status 3"):
        vessel.fmu.getFMUstate()
    messages = [m for _, _, m in vessel.messages]
    assert any("fmi2GetFMUstate: not supported" in m for m in messages), messages
    assert any("parameter 0 is fixed" in m for m in messages), messages
    assert any("Boolean parameters are fixed" in m for m in messages), messages
    assert any("value reference 28 is not a Real input or parameter" in m for m in messages), messages
    vessel.close()


# Parameters away from the defaults, every one changed, and the hinge on a fixed platform.
OTHER = {"wave.amplitude": 1.7, "wave.period": 6.5, "wave.phase": 2.1, "gravity": 9.80665, "heave.rao": 0.6,
         "heave.phase": -0.8, "pitch.rao": 1.3, "pitch.phase": -2.4, "hinge.x": 22.0, "clamp.x": -31.0,
         "clamp.direction": 0.6, "vessel.mass": 4.0e6, "vessel.pitch_inertia": 1.1e9, "hinge.on_vessel": False}


@pytest.mark.parametrize("parameters", [{}, OTHER], ids=["defaults", "other"])
def test_vessel_outputs_are_the_closed_form_with_exact_rates(vessel_fmu, tmp_path, parameters):
    step = 0.01
    p, got = vessel_alone(vessel_fmu, tmp_path, parameters, steps=1000, step=step)
    t = np.arange(1001) * step
    want = closed_form(p, parameters, t)
    if parameters:
        assert not got["upper.hinge_heave"].any()  # off the vessel: at rest
    for name, values in want.items():
        # The same formulas in C and numpy: both round cos of arguments below 30 rad, whose
        # absolute error is a few 1e-15; 1e-12 of the largest value leaves a margin of 100.
        scale = max(np.abs(values).max(), 1e-300)
        assert np.abs(got[name] - values).max() <= 1e-12 * scale, name
    # The rates are the derivatives of the positions: central differences over 2 steps, whose
    # truncation error is A omega^3 step^2 / 6 (A the coordinate's amplitude).
    a = amplitudes(p)
    for base in ("upper.hinge_heave", "lower.clamp_heave", "lower.clamp_rotation"):
        for lower, higher in (("", "_velocity"), ("_velocity", "_acceleration")):
            x, v = got[base + lower], got[base + higher]
            order = len(lower) and 1  # 0: position -> velocity, 1: velocity -> acceleration
            bound = a[base] * a["omega"] ** (3 + order) * step**2 / 6 + 1e-12
            difference = (x[2:] - x[:-2]) / (2 * step)
            assert np.abs(difference - v[1:-1]).max() <= bound, base + higher


def test_arrestor_end_moves_with_the_deck_point_under_it(vessel_fmu, tmp_path):
    """The clamp's heave and rotation carry the arrestor's end (length L, along clamp.direction)
    as the deck carries the point at clamp.x + direction L; with the defaults that point is the
    bridge's contact point, 13 m forward of the hinge (the geometry docs/moving-supports.md describes)."""
    p, got = vessel_alone(vessel_fmu, tmp_path, {}, steps=900, step=0.01)
    length, contact = 12.0, 13.0  # BeamImpact's lower.length and contact_position
    assert p["hinge.x"] + contact == p["clamp.x"] + p["clamp.direction"] * length
    end = got["lower.clamp_heave"] + length * got["lower.clamp_rotation"]
    deck = got["vessel.heave"] - (p["clamp.x"] + p["clamp.direction"] * length) * got["vessel.pitch"]
    # Round-off of sums of terms below 2 m.
    assert np.abs(end - deck).max() <= 1e-14 * 16
    # The bridge, hinged, does not follow the pitch: the supports open the gap by contact * pitch.
    gap = got["upper.hinge_heave"] - end
    assert np.abs(gap - contact * got["vessel.pitch"]).max() <= 1e-14 * 16
    assert np.abs(gap).max() > 0.4  # 13 m x 0.040 rad: a motion that matters against a 0.567 m drop


def test_long_wave_limit_follows_a_head_sea_surface(vessel_fmu, tmp_path):
    """The sign conventions: with the long-wave RAOs (|H_z| = 1, eps_z = 0, |H_theta| = 1,
    eps_theta = -pi/2) the deck point at x moves with the surface of a wave travelling towards -x
    (from ahead), zeta(x, t) = zeta_a cos(omega t + k x + phase), up to the curvature term
    zeta_a (k x)^2 / 2 that a straight deck cannot follow."""
    x = 4.0
    long_wave = {"heave.rao": 1.0, "heave.phase": 0.0, "pitch.rao": 1.0, "pitch.phase": -math.pi / 2,
                 "hinge.x": x, "wave.phase": 0.3}
    p, got = vessel_alone(vessel_fmu, tmp_path, long_wave, steps=900, step=0.01)
    omega = 2 * math.pi / p["wave.period"]
    k = omega**2 / p["gravity"]
    t = np.arange(901) * 0.01
    surface = p["wave.amplitude"] * np.cos(omega * t + k * x + p["wave.phase"])
    curvature = p["wave.amplitude"] * (k * x) ** 2 / 2  # 0.020 m at x = 4 m
    assert np.abs(got["upper.hinge_heave"] - surface).max() <= curvature
    # With the other sign of pitch (or a wave from astern) the error would be 2 k x zeta_a = 0.40 m.
    mirrored = p["wave.amplitude"] * np.cos(omega * t - k * x + p["wave.phase"])
    assert np.abs(got["upper.hinge_heave"] - mirrored).max() > 10 * curvature


# ---- the coupled runs -----------------------------------------------------------------------------

@pytest.fixture(scope="module")
def coupled(vessel_fmu, tmp_path_factory):
    """The default vessel (wave phase 0 at the impact) driving BeamImpact."""
    return vm.run(vm.beam_fmu(), tmp_path_factory.mktemp("coupled"), "coupled", vessel_fmu)


@pytest.fixture(scope="module")
def fixed(tmp_path_factory):
    """BeamImpact on fixed supports (its motion inputs never set)."""
    return vm.run(vm.beam_fmu(), tmp_path_factory.mktemp("fixed"), "fixed")


@pytest.fixture(scope="module")
def sweep(vessel_fmu, coupled, tmp_path_factory):
    """The wave phase at the impact over one period; phase 0 is `coupled`."""
    work = tmp_path_factory.mktemp("sweep")
    phases = 2 * math.pi * np.arange(PHASES) / PHASES
    return [coupled] + vm.phase_sweep(vm.beam_fmu(), vessel_fmu, phases[1:], work)


def test_the_vessel_outputs_in_the_coupled_run_are_the_closed_form(coupled):
    want = closed_form(coupled.parameters, {}, coupled.time)
    for name, values in want.items():
        assert np.abs(coupled.vessel[name] - values).max() <= 1e-12 * np.abs(values).max(), name
    # What the master sent is what the vessel gave.
    for name in vm.MOTION:
        assert np.array_equal(coupled.sent[name], coupled.vessel[name]), name


def test_the_deck_load_is_the_reactions_read_back(coupled):
    p, beam, vessel = coupled.parameters, coupled.beam, coupled.vessel
    r_h, r_c, m_c = (beam[vm.REACTIONS[k]] for k in ("hinge_force", "clamp_force", "clamp_moment"))
    assert np.abs(r_c).max() > 1e5, "the arrestor's clamp should carry the impact"
    force = -(r_h + r_c)
    moment = p["hinge.x"] * r_h + p["clamp.x"] * r_c + p["clamp.direction"] * m_c
    # Sums of three products: round-off of a few ulp of the largest term.
    assert np.abs(vessel["deck.force"] - force).max() <= 1e-14 * np.abs(force).max() * 8
    assert np.abs(vessel["deck.pitch_moment"] - moment).max() <= 1e-14 * (
        np.abs(p["clamp.x"] * r_c).max() + np.abs(p["hinge.x"] * r_h).max() + np.abs(m_c).max()) * 8
    assert np.allclose(vessel["deck.heave_acceleration"], vessel["deck.force"] / p["vessel.mass"], rtol=1e-15, atol=0)
    assert np.allclose(vessel["deck.pitch_acceleration"], vessel["deck.pitch_moment"] / p["vessel.pitch_inertia"],
                       rtol=1e-15, atol=0)
    # Why the vessel's motion may stay prescribed: the load's dynamic part (less the structures'
    # weight, which the vessel's displacement already carries), integrated twice, is how far it
    # would move the vessel alone (no added mass, no hydrostatics) over the run. Two parts: the
    # structures' mass m_s riding the vessel's motion, m_s / M of it, and the momentum the bridge
    # brings to the impact, m_u v_cg (v_cg = omega_pitch l_u / 2), spread over M for the run.
    s = coupled.scenario
    m_s = s["upper.mass"] + s["lower.mass"] + s["lower.tip_mass"]
    dynamic = (vessel["deck.force"] + m_s * s["gravity"]) / p["vessel.mass"]
    velocity = np.concatenate([[0.0], np.cumsum((dynamic[1:] + dynamic[:-1]) / 2 * H)])
    drift = np.abs(np.concatenate([[0.0], np.cumsum((velocity[1:] + velocity[:-1]) / 2 * H)])).max()
    motion = max(amplitudes(p)["upper.hinge_heave"], amplitudes(p)["lower.clamp_heave"])
    v_cg = math.sqrt(6 * s["gravity"] * s["drop_height"]) / 2  # rigid pitching from the drop height
    bound = (m_s * motion + s["upper.mass"] * v_cg * coupled.time[-1]) / p["vessel.mass"]
    assert drift <= bound, (drift, bound)  # measured 7.7 mm against 21 mm
    assert bound < 0.03 * np.abs(vessel["vessel.heave"]).max()  # the neglected motion: < 3 % of the heave


def quadratic_mismatch(run: vm.Run) -> dict[str, tuple[float, float, float]]:
    """Per support coordinate, the largest departure of the values sent at t_{n+1} from the
    constant-acceleration motion of the values sent at t_n: (position, rate, second rate)."""
    out = {}
    for k in range(0, 9, 3):
        z, v, a = (run.sent[vm.MOTION[k + j]] for j in range(3))
        out[vm.MOTION[k]] = (np.abs(z[1:] - (z[:-1] + v[:-1] * H + a[:-1] * H * H / 2)).max(),
                             np.abs(v[1:] - (v[:-1] + a[:-1] * H)).max(), np.abs(a[1:] - a[:-1]).max())
    return out


def test_beam_takes_the_vessel_motion_without_a_warning(coupled):
    assert set(coupled.beam_statuses) == {fmi2OK}, "a doStep returned fmi2Warning"
    assert not [m for m in coupled.beam_messages if m[0] != fmi2OK], coupled.beam_messages
    assert not coupled.vessel_messages and set(coupled.vessel_statuses) == {fmi2OK}, coupled.vessel_messages
    # The sampled cosines leave the constant-acceleration motion by their Taylor remainders:
    # A omega^3 h^3 / 6, A omega^3 h^2 / 2 and A omega^3 h (plus round-off of the position).
    a = amplitudes(coupled.parameters)
    for name, (dz, dv, da) in quadratic_mismatch(coupled).items():
        jerk = a[name] * a["omega"] ** 3
        assert dz <= jerk * H**3 / 6 + 1e-15 * 4 and dv <= jerk * H**2 / 2 * 1.001 and da <= jerk * H * 1.001, name


def test_positions_without_rates_are_warned(vessel_fmu, tmp_path):
    """The check above can fail: a master that sends the positions with their rates left at 0
    describes no motion, and BeamImpact says so (fmi2Warning and a message naming the input)."""
    run = vm.run(vm.beam_fmu(), tmp_path, "no_rates", vessel_fmu, stop=0.05, positions_only=True)
    assert fmi2Warning in run.beam_statuses, run.beam_statuses
    warned = [m for status, _, m in run.beam_messages if status == fmi2Warning]
    assert any(name in m for m in warned for name in vm.MOTION), run.beam_messages


def test_tip_positions_are_the_supports_plus_the_deflections(coupled):
    beam, sent, s = coupled.beam, coupled.sent, coupled.scenario
    a = amplitudes(coupled.parameters)
    # BeamImpact's own motion at t_n is the quadratic from t_{n-1} or the value set at t_n: they
    # differ by A omega^3 h^3 / 6 at most (0.04 nm here); round-off of metre-sized positions.
    bound = max(a["upper.hinge_heave"], a["lower.clamp_heave"] + s["lower.length"] * a["lower.clamp_rotation"]) \
        * a["omega"] ** 3 * H**3 / 6 + 1e-13
    upper = sent["upper.hinge_heave"] + beam["upper.tip_deflection"]
    assert np.abs(beam["upper.tip_position"] - upper).max() <= bound
    lower = sent["lower.clamp_heave"] + s["lower.length"] * sent["lower.clamp_rotation"] + beam["lower.tip_deflection"]
    assert np.abs(beam["lower.tip_position"] - lower).max() <= bound
    # The supports move the tips by more than the bound by far.
    assert np.abs(beam["upper.tip_position"] - beam["upper.tip_deflection"]).max() > 0.1


def test_contact_gap_is_the_bar_compression_with_the_supports_offset(coupled):
    """In contact, F_c = k_c (y_u - y_l) with y the absolute vertical positions of the bridge's
    contact point (hinge heave + its deflection: the hinged bridge does not turn with the
    supports) and of the arrestor's end (clamp heave + L theta + its deflection)."""
    beam, sent, s = coupled.beam, coupled.sent, coupled.scenario
    k_c = s["contact.elastic_modulus"] * s["contact.area"] / s["contact.length"]
    y_u = sent["upper.hinge_heave"] + beam["upper.contact_deflection"]
    y_l = sent["lower.clamp_heave"] + s["lower.length"] * sent["lower.clamp_rotation"] + beam["lower.tip_deflection"]
    touching = beam["contact.force"] < 0
    assert touching.sum() > 100, "the run should stay in contact for a while"
    gap = (y_u - y_l)[touching]
    force = beam["contact.force"][touching]
    # The bar compresses by |F_c| / k_c (up to 0.08 mm here). BeamImpact's own offset at t_n is
    # the quadratic from t_{n-1}, which differs from the values sent at t_n by the cosines'
    # remainder A omega^3 h^3 / 6 of the three supports (measured 3e-11 m; on fixed supports the
    # relation holds to 4e-16 m); round-off of metre-sized positions.
    a = amplitudes(coupled.parameters)
    bound = (a["upper.hinge_heave"] + a["lower.clamp_heave"] + s["lower.length"] * a["lower.clamp_rotation"]) \
        * a["omega"] ** 3 * H**3 / 6 + 1e-13
    assert np.abs(gap - force / k_c).max() <= bound
    # Without the supports' offset the relation would miss by the offset itself.
    offset = (sent["upper.hinge_heave"] - sent["lower.clamp_heave"] - s["lower.length"] * sent["lower.clamp_rotation"])
    assert np.abs(offset[touching]).max() > 100 * np.abs(force).max() / k_c


def test_energy_verdict_stays_trusted(coupled):
    assert coupled.trusted is True
    beam = coupled.beam
    potential = coupled.scenario["upper.mass"] * coupled.scenario["gravity"] * coupled.scenario["drop_height"]
    flow = max(potential + np.abs(beam["energy.external_work"]).max(), np.abs(beam["energy.strain"]).max())
    # The FMU's default energy_tolerance, 1 % of the energy that flows.
    assert np.abs(beam["energy.residual"]).max() <= 0.01 * flow


def test_calm_sea_reproduces_the_fixed_supports(vessel_fmu, fixed, tmp_path):
    calm = vm.run(vm.beam_fmu(), tmp_path, "calm", vessel_fmu, {"wave.amplitude": 0.0})
    assert not any(np.any(calm.sent[n]) for n in vm.MOTION)  # every motion input exactly 0
    for name in vm.PEAKS:
        # Zero motion is the fixed supports: the same arithmetic, up to round-off (1e-9 leaves
        # room for a summation order that differs with the motion terms present).
        assert calm.peaks[name] == pytest.approx(fixed.peaks[name], rel=1e-9, abs=0), name
    assert set(fixed.beam_statuses) == {fmi2OK} and fixed.trusted is True


def test_peaks_vary_with_the_wave_phase_at_impact(sweep, fixed):
    for run in sweep:
        assert set(run.beam_statuses) == {fmi2OK}, run.parameters["wave.phase"]
        assert run.trusted is True, run.parameters["wave.phase"]
    for name in vm.PEAKS:
        values = np.array([run.peaks[name] for run in sweep])
        spread = (values.max() - values.min()) / values.mean()
        # The solver's peaks are trusted to its discretisation_tolerance, 1 %: a spread of more
        # than twice that is the waves, not the numerics.
        assert spread > 0.02, (name, values)
        # The fixed supports' peak lies inside the band the phases span: some phases lessen the
        # impact, others add to it.
        assert values.min() < fixed.peaks[name] < values.max(), (name, values, fixed.peaks[name])
        # And it is the supports' closing speed at the impact that does it (the vessel adds up to
        # 0.35 m/s to the bridge's 2.6 m/s, or takes it away): every peak rises with it. Measured
        # correlation 0.96-0.999 over the 12 phases; a wrong sign in the motion would make it
        # negative, a motion that did not matter would leave it near 0.
        closing = [vm.closing_speed(run) for run in sweep]
        assert np.corrcoef(closing, values)[0, 1] > 0.9, (name, closing, values)


def test_the_plot_script_draws_the_sweep_and_prints_its_table(tmp_path):
    figure = tmp_path / "vessel-phase.png"
    run = subprocess.run([sys.executable, str(ROOT / "docs" / "plot_vessel_phase.py"), "--phases", "3",
                          "--duration", "0.3", "--out", str(figure)], capture_output=True, text=True, timeout=300,
                         env={**os.environ, "BEAM_IMPACT_FMU_DIR": str(vm.FMU_DIR)})
    assert run.returncode == 0, run.stderr
    assert figure.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    rows = [line.split() for line in run.stdout.splitlines() if re.match(r"^\s*(fixed|\d+(\.\d+)?)\s", line)]
    assert [r[0] for r in rows] == ["fixed", "0", "120", "240"], run.stdout
    assert all(len(r) >= 5 and all(float(x) > 0 for x in r[1:5]) for r in rows), run.stdout


def test_master_runs_in_modest_time(coupled, fixed):
    # 3000 communication steps of BeamImpact (about 44 internal steps each, and its check rungs)
    # and of the vessel: 0.3-1 s measured on two cores; 20 s leaves room for a loaded machine.
    assert coupled.wall < 20.0 and fixed.wall < 20.0, (coupled.wall, fixed.wall)
