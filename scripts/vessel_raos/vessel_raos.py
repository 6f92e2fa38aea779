#!/usr/bin/env python3
"""The example vessel's motion RAOs (issue 42): examples/vessel-sea-raos.csv, computed with Capytaine.

A parametric walk-to-work / supply hull of the main dimensions of the MSS supply vessel (Lpp 82.8 m,
B 19.2 m, T 6.0 m, so its VERES RAOs in ../shared/data/mss-supply-vessel/supply.re1 are a peer to
compare with: `--compare`), free floating at zero speed in deep water. First-order radiation and
diffraction by Capytaine's BEM (the Delhommeau Green function, a lid against irregular
frequencies), hydrostatics from the mesh, rigid-body inertia from stated radii of gyration, an
added linear roll damping, the 6x6 equations of motion solved per frequency and heading.

    python scripts/vessel_raos/vessel_raos.py                       # writes examples/vessel-sea-raos.csv
    python scripts/vessel_raos/vessel_raos.py --convergence         # the same frequencies on a finer mesh: a few rows
    python scripts/vessel_raos/vessel_raos.py --compare ../shared/data/mss-supply-vessel/supply.re1

Conventions of the CSV (docs/sea-states.md; the spec of issue 42): vessel axes x forward, y to
port, z up, origin (the motion reference point) midships (Lpp/2) on the centreline at the
waterline; surge, sway, heave of that point in m per m of wave amplitude; roll (positive starboard
down), pitch (positive bow down), yaw (positive bow to port) in deg per m of wave amplitude; phases
in deg, a lead over the wave elevation at the reference point: the motion is |H| cos(w t + eps)
when the elevation there is cos(w t). Heading: the direction the waves travel towards, from the
bow towards port: 180 = head seas (waves from ahead), 0 = following, 90 = waves travelling to port
(coming from starboard). The hull is symmetric port/starboard, so a heading 360 - beta has the
RAOs of beta with sway, roll and yaw of opposite sign (their phases + 180 deg), the others equal.

Capytaine's conventions (its user manual, "Conventions"): phasors x(t) = Re(X exp(-i w t)); the
incident potential Phi_0 = -i g/w exp(k z) exp(i k (x cos beta + y sin beta)), whose elevation
-(1/g) dPhi/dt at z = 0 is Re(exp(i k (x cos beta + y sin beta) - i w t)): unit amplitude, crest at
the origin at t = 0, travelling towards beta (radians, from +x towards +y). So the wave at the
origin is cos(w t), our heading is beta in degrees, and eps = -arg(X); rotations about the origin
with Capytaine's right-handed dofs (rotation about +x, +y, +z) are our roll, pitch, yaw signs with
y to port. The long-wave limits checked at the end prove it: heave -> 1 at 0 deg, pitch in head
seas -> the wave slope k (rad/m) at -90 deg, roll in beam seas -> k at -90 deg (and pitch in
following seas at +90 deg). Those limits are quasi-static: a time convention and a heading both
taken the wrong way round would pass them too. The damping tells them apart: the roll at 0.1 rad/s
lags its quasi-static phase (-91 deg), as a damped response does, and --compare finds VERES's
head-sea pitch phases within 8 deg of ours.

Cost (2026-11-29, a 2-core x86-64 VM shared with other builds): 2442 hull panels and 736 lid
panels, 37 frequencies x 13 headings in 2.5-3.5 minutes, 0.5 GB; --convergence (9780 + 3124
panels at 6 frequencies x 3 headings) 10 minutes, 5.4 GB.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np

RHO = 1025.0  # sea water, kg/m^3
G = 9.81  # m/s^2

# --- The hull -------------------------------------------------------------------------------
LPP = 82.8  # m, waterline length (stem to transom at the waterline)
BEAM = 19.2  # m
DRAFT = 6.0  # m
X_AFT_SHOULDER = -0.15 * LPP  # the parallel midbody from here ...
X_FWD_SHOULDER = 0.05 * LPP  # ... to here (m from midships)
TRANSOM_HALF_BEAM = 0.8  # transom's waterline breadth / B
TRANSOM_DRAFT = 0.2  # transom's immersion / T (a flat run rising aft)
MID_EXPONENT = 8.0  # superellipse exponent of the midship section: C_M = 0.978, a bilge radius of about 2.5 m
BOW_EXPONENT = 2.0  # ... at the stem (elliptic, V-ish sections forward)
STERN_EXPONENT = 4.0  # ... at the transom

# --- Mass distribution (stated, not a particular vessel's) -----------------------------------
KG = 6.5  # m above the keel: a loaded supply / W2W vessel (gangway and tower on deck)
ROLL_GYRADIUS = 0.35  # k_xx / B (DNV-RP-C205 / typical monohulls: 0.30-0.40 B)
PITCH_GYRADIUS = 0.25  # k_yy / Lpp (typical 0.24-0.26 Lpp)
YAW_GYRADIUS = 0.25  # k_zz / Lpp
ROLL_DAMPING_RATIO = 0.05  # added linear roll damping, fraction of critical (viscous + bilge keels)

# --- Frequencies and headings ----------------------------------------------------------------
HEADINGS_DEG = np.arange(0.0, 180.0 + 1e-9, 15.0)
BASE_FREQUENCIES = [
    0.10, 0.15, 0.20, 0.25, 0.30, 0.35, 0.40, 0.45, 0.50, 0.70, 0.75, 0.80, 0.85, 0.90, 0.95,
    1.00, 1.05, 1.10, 1.15, 1.20, 1.30, 1.40, 1.50, 1.60, 1.80, 2.00, 2.20, 2.40, 2.60, 2.80, 3.00,
]  # rad/s; the roll resonance gets a cluster of its own (roll_cluster)

DOFS = ["Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw"]


def section(x: float) -> tuple[float, float, float]:
    """The section at x (m from midships, forward +): half-breadth at the waterline (m), draft (m),
    superellipse exponent n of |y/b|^n + |z/t|^n = 1."""
    b0, t0 = BEAM / 2, DRAFT
    if x > X_FWD_SHOULDER:  # forebody: waterline (1 - xi^2), a half-entrance angle of 30 deg, vertical stem
        xi = min((x - X_FWD_SHOULDER) / (LPP / 2 - X_FWD_SHOULDER), 1.0)
        return b0 * (1 - xi**2), t0, MID_EXPONENT + (BOW_EXPONENT - MID_EXPONENT) * xi
    if x < X_AFT_SHOULDER:  # afterbody: the run rises and narrows to an immersed transom
        eta = min((X_AFT_SHOULDER - x) / (X_AFT_SHOULDER + LPP / 2), 1.0)
        return (
            b0 * (1 - (1 - TRANSOM_HALF_BEAM) * eta**2),
            t0 * (1 - (1 - TRANSOM_DRAFT) * eta**2),
            MID_EXPONENT + (STERN_EXPONENT - MID_EXPONENT) * eta,
        )
    return b0, t0, MID_EXPONENT


def girth_points(b: float, t: float, n: float, count: int) -> np.ndarray:
    """count + 1 points (y, z) along a half section from the waterline's edge (b, 0) to the keel
    (0, -t), equally spaced in arc length (a stem section of b = 0 is the segment to the keel)."""
    s = np.linspace(0.0, np.pi / 2, 2001)
    y = b * np.cos(s) ** (2 / n)
    z = -t * np.sin(s) ** (2 / n)
    arc = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(y), np.diff(z)))])
    target = np.linspace(0.0, arc[-1], count + 1)
    return np.column_stack([np.interp(target, arc, y), np.interp(target, arc, z)])


def half_hull(nx: int, ngirth: int, ntransom: int):
    """Vertices and triangular faces of the port half (y >= 0) of
    the wetted hull and its transom, normals out of the hull. Stations cosine-clustered towards
    the ends, where the sections change fastest."""
    u = np.linspace(0.0, 1.0, nx + 1)
    xs = -LPP / 2 + LPP * (0.5 - 0.5 * np.cos(np.pi * u)) * 0.5 + LPP * u * 0.5  # half cosine, half uniform
    rings = np.array([[(x, y, z) for y, z in girth_points(*section(x), ngirth)] for x in xs])  # (nx+1, ng+1, 3)
    vertices = [p for ring in rings for p in ring]
    index = lambda i, j: i * (ngirth + 1) + j  # noqa: E731
    faces = []
    for i in range(nx):
        for j in range(ngirth):
            faces.append([index(i, j), index(i + 1, j), index(i + 1, j + 1), index(i, j + 1)])
    # The transom (x = -L/2): strips from the girth points at the same z to the centreline.
    offset = len(vertices)
    stern = rings[0]
    for m in range(1, ntransom + 1):
        for y, z in stern[:, 1:]:
            vertices.append((-LPP / 2, y * (1 - m / ntransom), z))
    tindex = lambda m, j: index(0, j) if m == 0 else offset + (m - 1) * (ngirth + 1) + j  # noqa: E731
    for m in range(ntransom):
        for j in range(ngirth):
            faces.append([tindex(m, j), tindex(m, j + 1), tindex(m + 1, j + 1), tindex(m + 1, j)])
    vertices = np.array(vertices, dtype=float)
    # Collapse repeated vertices (the stem line, the keel point of the transom) and drop the faces
    # with fewer than three distinct corners.
    key = np.round(vertices, 9)
    _, first, inverse = np.unique(key, axis=0, return_index=True, return_inverse=True)
    inverse = inverse.ravel()
    # Each quad is split into two triangles along its shorter diagonal: a curved hull's quads are
    # not planar, and Capytaine integrates a quad as two triangles split along the diagonal from its
    # first corner, which its mirroring (the corners reversed) moves to the other diagonal, so the
    # starboard half would not be the port half's mirror image (roll forces in head seas of 3e-4 of
    # the beam-sea ones). Triangles are planar and mirror exactly.
    vertices = vertices[first]
    clean = []
    for f in faces:
        g = []
        for v in (int(inverse[k]) for k in f):
            if v not in g:
                g.append(v)
        if len(g) == 3:
            clean.append(g)
        elif len(g) == 4:
            a, b, c, d = (vertices[k] for k in g)
            if np.linalg.norm(c - a) <= np.linalg.norm(d - b):
                clean += [[g[0], g[1], g[2]], [g[0], g[2], g[3]]]
            else:
                clean += [[g[0], g[1], g[3]], [g[1], g[2], g[3]]]
    return vertices, np.array(clean)


def make_body(nx: int, ngirth: int, ntransom: int, omega_max: float):
    """The Capytaine body: the symmetric hull mesh, a lid, six rigid dofs about the origin, the
    mass and centre of gravity that float it level."""
    import capytaine as cpt

    vertices, faces = half_hull(nx, ngirth, ntransom)
    half = cpt.Mesh(vertices=vertices, faces=faces, name="half hull")
    # Orient the normals outwards: the enclosed volume of the full hull must come out positive.
    mesh = cpt.ReflectionSymmetricMesh(half=half, plane="xOz", name="hull")
    if mesh.volume < 0:
        half = cpt.Mesh(vertices=vertices, faces=faces[:, ::-1], name="half hull")
        mesh = cpt.ReflectionSymmetricMesh(half=half, plane="xOz", name="hull")
    z_lid = mesh.lowest_lid_position(omega_max=omega_max)
    lid = mesh.generate_lid(z=z_lid)
    body = cpt.FloatingBody(mesh=mesh, lid_mesh=lid, dofs=cpt.rigid_body_dofs(rotation_center=(0.0, 0.0, 0.0)),
                            name="w2w_vessel")
    volume = body.disp_volume
    cob = body.center_of_buoyancy
    body.mass = RHO * volume
    body.center_of_mass = np.array([cob[0], 0.0, KG - DRAFT])  # level trim: the centre of gravity above the centre of buoyancy
    return body, z_lid


def rigid_body_inertia(mass: float, cog: np.ndarray) -> np.ndarray:
    """6x6 mass matrix about the origin (Fossen 2011, eq. 3.44): [[m I, -m S(r)], [m S(r), I_O]],
    S(r) b = r x b, I_O = I_G + m (|r|^2 I - r r^T), I_G = m diag(k_xx^2, k_yy^2, k_zz^2)."""
    s = np.array([[0, -cog[2], cog[1]], [cog[2], 0, -cog[0]], [-cog[1], cog[0], 0]])
    i_g = mass * np.diag([(ROLL_GYRADIUS * BEAM) ** 2, (PITCH_GYRADIUS * LPP) ** 2, (YAW_GYRADIUS * LPP) ** 2])
    i_o = i_g + mass * (cog @ cog * np.eye(3) - np.outer(cog, cog))
    m = np.zeros((6, 6))
    m[:3, :3] = mass * np.eye(3)
    m[:3, 3:] = -mass * s
    m[3:, :3] = mass * s
    m[3:, 3:] = i_o
    return m


def solve(body, omegas, headings_deg, n_jobs=1):
    """Capytaine's added mass, radiation damping and excitation force (6 dofs, complex, per unit
    wave amplitude) at the given frequencies and headings."""
    import capytaine as cpt
    import xarray as xr

    solver = cpt.BEMSolver()
    grid = xr.Dataset(coords={
        "omega": np.asarray(omegas, dtype=float),
        "wave_direction": np.radians(np.asarray(headings_deg, dtype=float)),
        "radiating_dof": list(body.dofs),
        "water_depth": [np.inf],
        "rho": [RHO],
        "g": [G],
    })
    ds = solver.fill_dataset(grid, body, n_jobs=n_jobs, progress_bar=False, _check_wavelength=False)
    return ds.squeeze(drop=True)


def motions(ds, inertia, stiffness, roll_damping):
    """The complex RAOs X[omega, heading, dof] in Capytaine's phasors (x = Re(X exp(-i w t)), per m
    of wave amplitude, m and rad): (-w^2 (M + A) - i w (B + B_ext) + C) X = F."""
    omegas = ds.omega.values
    a = ds.added_mass.transpose("omega", "influenced_dof", "radiating_dof").sel(influenced_dof=DOFS, radiating_dof=DOFS).values
    b = ds.radiation_damping.transpose("omega", "influenced_dof", "radiating_dof").sel(influenced_dof=DOFS, radiating_dof=DOFS).values
    f = ds.excitation_force.transpose("omega", "wave_direction", "influenced_dof").sel(influenced_dof=DOFS).values
    b_ext = np.zeros((6, 6))
    b_ext[3, 3] = roll_damping
    x = np.empty(f.shape, dtype=complex)
    for i, w in enumerate(omegas):
        h = -w**2 * (inertia + a[i]) - 1j * w * (b[i] + b_ext) + stiffness
        x[i] = np.linalg.solve(h, f[i].T).T
    return x


def to_csv_units(x):
    """Our CSV's amplitudes (m/m; deg/m for rotations) and phase leads (deg) from Capytaine's phasors."""
    amp = np.abs(x).copy()
    amp[..., 3:] = np.degrees(amp[..., 3:])
    phase = -np.degrees(np.angle(x))
    return amp, phase


def natural_frequency(mass, added, stiffness):
    return math.sqrt(stiffness / (mass + added)) if stiffness > 0 else float("nan")


def write_csv(path: Path, omegas, headings, amp, phase, header_lines):
    names = ["surge", "sway", "heave", "roll", "pitch", "yaw"]
    with open(path, "w", newline="\n") as out:
        for line in header_lines:
            out.write(f"# {line}\n" if line else "#\n")
        out.write("frequency,heading," + ",".join(f"{n},{n}_phase" for n in names) + "\n")
        for j, beta in enumerate(headings):
            for i, w in enumerate(omegas):
                cells = [f"{w:.4f}", f"{beta:.1f}"]
                for d in range(6):
                    a = amp[i, j, d]
                    p = phase[i, j, d]
                    if a < 1e-9:  # a motion the heading cannot excite (sway, roll, yaw in head seas): exactly 0
                        a, p = 0.0, 0.0
                    p = round((p + 180.0) % 360.0 - 180.0, 2) + 0.0  # in [-180, 180), no "-0.00"
                    cells += [f"{a:.6g}", f"{p:.2f}"]
                out.write(",".join(cells) + "\n")


def read_re1(path: Path):
    """A VERES .re1's motion transfer functions, for --compare only: ({(heading, omega): [6 complex]},
    the motion reference point (x from Lpp/2 positive aft, z from the baseline)). VERES's numbers
    are x(t) = Re(H exp(+i w t)) in its axes x aft, y to starboard, z up, rotations in rad/m, its
    headings from the bow (0 head seas), as MSS's read_veres_TF reads them."""
    lines = Path(path).read_text().splitlines()
    nv, nbeta, nfreq, ndof = (int(v) for v in lines[9].split())
    k = 10
    out = {}
    reference = None
    for _ in range(nv):
        speed = [float(v) for v in lines[k].split()]
        reference = (speed[3], speed[4])
        k += 1
        for _ in range(nbeta):
            beta = float(lines[k].split()[0])
            k += 1
            for _ in range(nfreq):
                w = float(lines[k].split()[0])
                k += 1
                row = []
                for _ in range(ndof):
                    _, re, im = lines[k].split()
                    row.append(complex(float(re), float(im)))
                    k += 1
                out[(beta, w)] = row
    return out, reference


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    root = Path(__file__).resolve().parents[2]
    parser.add_argument("--out", type=Path, default=root / "examples" / "vessel-sea-raos.csv")
    parser.add_argument("--mesh", type=int, nargs=3, default=[48, 12, 3], metavar=("NX", "NGIRTH", "NTRANSOM"),
                        help="panels along the half hull: stations, girth, transom strips (default 48 12 3)")
    parser.add_argument("--convergence", action="store_true",
                        help="solve a few frequencies on this mesh and one twice as fine in each direction, print the differences")
    parser.add_argument("--compare", type=Path, help="a VERES .re1 of a similar vessel to print beside ours (not copied)")
    parser.add_argument("--jobs", type=int, default=1, help="Capytaine's joblib workers (default 1; threads: OMP_NUM_THREADS)")
    args = parser.parse_args(argv)

    import capytaine as cpt

    t0 = time.perf_counter()
    omega_max = max(BASE_FREQUENCIES)
    body, z_lid = make_body(*args.mesh, omega_max=omega_max)
    mass = body.mass
    cog = body.center_of_mass
    hydro = body.compute_hydrostatics(rho=RHO, g=G)
    stiffness = body.compute_hydrostatic_stiffness(rho=RHO, g=G).sel(influenced_dof=DOFS, radiating_dof=DOFS).values
    inertia = rigid_body_inertia(mass, cog)
    volume = body.disp_volume
    gm_t = hydro["transversal_metacentric_height"]
    gm_l = hydro["longitudinal_metacentric_height"]
    awp = hydro["waterplane_area"]
    print(f"Capytaine {cpt.__version__}, numpy {np.__version__}")
    print(f"hull: Lpp {LPP} m, B {BEAM} m, T {DRAFT} m; panels {body.mesh.nb_faces} hull + "
          f"{body.lid_mesh.nb_faces} lid at z = {z_lid:.2f} m (mesh {args.mesh})")
    print(f"displacement {mass / 1e3:.0f} t ({volume:.0f} m^3), C_B {volume / (LPP * BEAM * DRAFT):.3f}, "
          f"C_WP {awp / (LPP * BEAM):.3f}, LCB {body.center_of_buoyancy[0]:+.2f} m, KB {DRAFT + body.center_of_buoyancy[2]:.2f} m")
    print(f"KG {KG} m, GM_T {gm_t:.2f} m, GM_L {gm_l:.1f} m; gyradii {ROLL_GYRADIUS} B, {PITCH_GYRADIUS} L, {YAW_GYRADIUS} L")

    if args.convergence:
        return convergence(args, omega_max)

    # The roll resonance: A_44 from one radiation solve at a first guess, then a cluster of
    # frequencies around it (the roll peak is the narrowest one: its half-power width is about
    # 2 zeta w_n = 0.06 rad/s).
    c44 = stiffness[3, 3]
    guess = solve(body, [0.6], [180.0], n_jobs=args.jobs)
    a44 = float(guess.added_mass.sel(radiating_dof="Roll", influenced_dof="Roll"))
    w_roll = natural_frequency(inertia[3, 3], a44, c44)
    b44 = ROLL_DAMPING_RATIO * 2 * math.sqrt((inertia[3, 3] + a44) * c44)
    cluster = [round(w_roll * f, 3) for f in (0.85, 0.92, 0.96, 1.0, 1.04, 1.08, 1.16)]
    omegas = np.array(sorted(set(BASE_FREQUENCIES) | set(cluster)))
    omegas = omegas[~np.array([any(abs(w - c) < 0.012 for c in cluster) and w not in cluster for w in omegas])]
    print(f"roll: C44 {c44 / 1e6:.1f} MN m/rad, A44(0.6) {a44 / 1e6:.1f} t m^2 x1e3, w_n {w_roll:.3f} rad/s "
          f"(T {2 * math.pi / w_roll:.1f} s), added damping {b44 / 1e6:.2f} MN m s/rad ({ROLL_DAMPING_RATIO:.0%} of critical)")
    print(f"{len(omegas)} frequencies {omegas.min()}-{omegas.max()} rad/s x {len(HEADINGS_DEG)} headings")

    t1 = time.perf_counter()
    ds = solve(body, omegas, HEADINGS_DEG, n_jobs=args.jobs)
    t2 = time.perf_counter()
    x = motions(ds, inertia, stiffness, b44)
    amp, phase = to_csv_units(x)
    for name, d, c in (("heave", 2, stiffness[2, 2]), ("pitch", 4, stiffness[4, 4])):
        i = int(np.argmin(abs(omegas - 1.0)))
        a = float(ds.added_mass.sel(radiating_dof=DOFS[d], influenced_dof=DOFS[d]).isel(omega=i))
        wn = natural_frequency(inertia[d, d], a, c)
        print(f"{name}: w_n {wn:.3f} rad/s (T {2 * math.pi / wn:.1f} s, with A at {omegas[i]} rad/s)")

    long_wave_checks(omegas, amp, phase)

    header = [
        "Motion RAOs of the beam-impact example vessel (issue 42), made by scripts/vessel_raos/vessel_raos.py",
        f"with Capytaine {cpt.__version__} (numpy {np.__version__}): first-order radiation/diffraction at zero speed, deep water,",
        f"a lid at z = {z_lid:.2f} m against irregular frequencies; {body.mesh.nb_faces} hull panels (mesh {' '.join(map(str, args.mesh))}).",
        f"Hull: parametric supply / walk-to-work monohull, Lpp {LPP} m, B {BEAM} m, T {DRAFT} m (the MSS supply vessel's main",
        f"dimensions), parallel midbody {X_AFT_SHOULDER:.1f} to {X_FWD_SHOULDER:.1f} m, fine bow with vertical stem, immersed transom;",
        f"displacement {mass / 1e3:.0f} t (rho {RHO:.0f} kg/m^3), C_B {volume / (LPP * BEAM * DRAFT):.3f}, LCG = LCB {cog[0]:+.2f} m.",
        f"Mass: KG {KG} m (GM_T {gm_t:.2f} m, GM_L {gm_l:.0f} m), radii of gyration {ROLL_GYRADIUS} B (roll), {PITCH_GYRADIUS} Lpp (pitch, yaw).",
        f"Added linear roll damping {b44:.4g} N m s/rad = {ROLL_DAMPING_RATIO:.0%} of critical at the roll resonance",
        f"({w_roll:.3f} rad/s, T {2 * math.pi / w_roll:.1f} s); no other damping than the waves' radiation; free floating (no mooring, no DP).",
        "Axes: x forward, y to port, z up; reference point midships on the centreline at the waterline (the rotations' centre",
        "and the elevation's). Roll + starboard down, pitch + bow down, yaw + bow to port. Heading: the direction the waves",
        "travel towards from the bow towards port: 180 head seas, 0 following, 90 waves from starboard; 180-360 deg mirror",
        "0-180: H(360 - b) = H(b) for surge, heave, pitch and -H(b) (phase + 180 deg) for sway, roll, yaw.",
        "Units: frequency rad/s, heading deg, surge/sway/heave m/m, roll/pitch/yaw deg/m; phase deg, a lead over the",
        "elevation at the reference point: motion = |H| cos(w t + phase) when the elevation is cos(w t).",
        f"The panels meet Capytaine's rule (a wavelength of at least 8 panel radii) up to {math.sqrt(2 * math.pi * G / body.minimal_computable_wavelength):.1f} rad/s; above, the",
        "motions are small (from 2 rad/s: heave < 0.012 m/m, roll and pitch < 0.09 deg/m, yaw < 0.2 deg/m) and less accurate.",
    ]
    write_csv(args.out, omegas, HEADINGS_DEG, amp, phase, header)
    t3 = time.perf_counter()
    print(f"wrote {args.out} ({len(omegas) * len(HEADINGS_DEG)} rows); set-up {t1 - t0:.1f} s, BEM {t2 - t1:.1f} s, total {t3 - t0:.1f} s")

    if args.compare:
        compare(args.compare, omegas, x)
    return 0


def long_wave_checks(omegas, amp, phase):
    """The long-wave limits that prove the conventions: at the lowest frequency the vessel rides the
    wave: heave 1 at 0 deg; pitch the wave slope k (deg/m) at -90 deg in head seas and +90 deg in
    following seas; roll the slope at -90 deg in beam seas (waves travelling to port)."""
    i = 0
    w = omegas[i]
    k_deg = math.degrees(w**2 / G)
    j = {b: int(np.argmin(abs(HEADINGS_DEG - b))) for b in (0.0, 90.0, 180.0)}
    print(f"long-wave limits at w = {w} rad/s (k = {w**2 / G:.5f} rad/m = {k_deg:.4f} deg/m):")
    for label, b, d, expect_amp, expect_phase in (
        ("heave, head seas", 180.0, 2, 1.0, 0.0),
        ("heave, beam seas", 90.0, 2, 1.0, 0.0),
        ("pitch, head seas", 180.0, 4, k_deg, -90.0),
        ("pitch, following seas", 0.0, 4, k_deg, 90.0),
        ("roll, beam seas", 90.0, 3, k_deg, -90.0),
        ("surge, head seas", 180.0, 0, 1.0, 90.0),
    ):
        a, p = amp[i, j[b], d], phase[i, j[b], d]
        print(f"  {label:24s} |H| {a:.4f} (limit {expect_amp:.4f}, ratio {a / expect_amp:.3f}), phase {p:+7.2f} deg (limit {expect_phase:+.0f})")


def convergence(args, omega_max):
    """The RAOs at a few frequencies and headings on the default mesh and on one twice as fine
    along the hull and its girth (four times the panels)."""
    omegas = [0.4, 0.55, 0.8, 1.0, 1.3, 2.0]
    headings = [90.0, 135.0, 180.0]
    results = []
    for mesh in (args.mesh, [2 * args.mesh[0], 2 * args.mesh[1], 2 * args.mesh[2]]):
        body, _ = make_body(*mesh, omega_max=omega_max)
        stiffness = body.compute_hydrostatic_stiffness(rho=RHO, g=G).sel(influenced_dof=DOFS, radiating_dof=DOFS).values
        inertia = rigid_body_inertia(body.mass, body.center_of_mass)
        t = time.perf_counter()
        ds = solve(body, omegas, headings, n_jobs=args.jobs)
        # the same added roll damping on both meshes (the coarse mesh's value), so only the BEM differs
        b44 = 0.05 * 2 * math.sqrt((inertia[3, 3] + float(ds.added_mass.sel(radiating_dof="Roll", influenced_dof="Roll").isel(omega=1))) * stiffness[3, 3])
        if not results:
            b44_coarse = b44
        x = motions(ds, inertia, stiffness, b44_coarse)
        print(f"mesh {mesh}: {body.mesh.nb_faces} hull panels, {body.lid_mesh.nb_faces} lid; {len(omegas)} x {len(headings)} in {time.perf_counter() - t:.1f} s")
        results.append(to_csv_units(x))
    (a0, p0), (a1, p1) = results
    print("w [rad/s] heading  dof    coarse |H|   fine |H|   diff     phase diff [deg]")
    for i, w in enumerate(omegas):
        for j, b in enumerate(headings):
            for d, name in ((2, "heave"), (3, "roll"), (4, "pitch")):
                if a1[i, j, d] < 1e-6:
                    continue
                print(f"{w:8.2f} {b:7.0f}  {name:5s} {a0[i, j, d]:11.4f} {a1[i, j, d]:10.4f} {100 * (a0[i, j, d] / a1[i, j, d] - 1):+6.1f} %"
                      f" {((p0[i, j, d] - p1[i, j, d] + 180) % 360 - 180):+8.2f}")
    return 0


def compare(path, omegas, x):
    """Ours beside a VERES .re1 of a similar vessel, in our axes: VERES's heading h is our 180 + h
    (mirrored: the magnitudes of h and 360 - h agree), its surge, sway, roll and pitch change sign
    (x aft, y to starboard), its phasors are conjugate to Capytaine's (exp(+i w t)). The heave is
    compared at VERES's motion reference point (ours moved there: heave - x pitch); the phases of
    pitch, which does not depend on the point, as leads over the elevation."""
    re1, (x_aft, z_base) = read_re1(path)
    x_p = -x_aft
    ws = sorted({w for (_, w) in re1})
    print(f"beside {path} (VERES strip theory; its motions at x = {x_p:+.2f} m, z = {z_base - DRAFT:+.2f} m):")
    print("heading    w    heave ours / VERES   pitch [deg/m] ours / VERES   pitch lead [deg] ours / VERES   roll [deg/m] ours / VERES")
    for ours_heading, h in ((180.0, 0.0), (150.0, 30.0), (90.0, 90.0)):
        j = int(np.argmin(abs(HEADINGS_DEG - ours_heading)))
        for w in (0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0, 1.1, 1.2, 1.4):
            wv = min(ws, key=lambda v: abs(v - w))
            hv = re1[(h if ours_heading != 90.0 else 90.0, wv)]
            xi = np.array([np.interp(wv, omegas, x[:, j, d].real) + 1j * np.interp(wv, omegas, x[:, j, d].imag) for d in range(6)])
            heave_p = abs(xi[2] - x_p * xi[4])
            pitch_lead = -math.degrees(np.angle(xi[4]))
            veres_pitch_lead = math.degrees(np.angle(-hv[4]))
            print(f"{ours_heading:5.0f} {wv:7.3f}   {heave_p:6.3f} / {abs(hv[2]):6.3f}     "
                  f"{math.degrees(abs(xi[4])):6.3f} / {math.degrees(abs(hv[4])):6.3f}          "
                  f"{pitch_lead:7.1f} / {(veres_pitch_lead + 180) % 360 - 180:7.1f}            "
                  f"{math.degrees(abs(xi[3])):6.3f} / {math.degrees(abs(hv[3])):6.3f}")


if __name__ == "__main__":
    sys.exit(main())
