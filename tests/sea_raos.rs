//! Issue 42: RAO tables from our CSV and from VERES `.re1`, their axes, phases and headings, and
//! their interpolation.
//!
//! The real file is the Marine Systems Simulator's supply vessel (VERES 4.02.3, Lpp 82.8 m, MIT
//! licence), read where the project keeps it, `../shared/data/mss-supply-vessel/supply.re1` (or
//! beside a folder above the checkout, or `/work/shared/data/...`, see [`supply_path`];
//! `BEAM_IMPACT_SUPPLY_RE1` points elsewhere); it is never copied into the repository.
//!
//! The long-wave limits that prove the axes, the phase convention and the heading (a body that
//! follows a long wave's surface; Faltinsen, *Sea Loads on Ships and Offshore Structures*, 1990,
//! ch. 7): for waves travelling at beta from the bow towards port, zeta = zeta_a cos(w t - k (x
//! cos beta + y sin beta)), k = w^2 / g, the deck w(x, y) = heave - x theta + y phi follows
//! zeta_a cos(w t) + zeta_a k (x cos beta + y sin beta) sin(w t): heave 1 at phase 0, pitch
//! theta = -zeta_a k cos beta sin(w t), so H_pitch = i k cos beta (-90 deg in head seas: the
//! bow goes down a quarter period after the crest passes the reference point), roll H_roll =
//! -i k sin beta, and the horizontal excursions H_surge = -i cos beta, H_sway = -i sin beta.

use beam_impact::model::sea::raos::{RaoSource, RaoTable, MAX_ROWS};
use nalgebra::Complex;

/// Where the MSS supply vessel's `.re1` is: `BEAM_IMPACT_SUPPLY_RE1`, else `shared/data/...` beside
/// the checkout or beside any folder above it (a clone elsewhere on this machine, as CI's), else
/// the workplace's `/work/shared/data/...`; the first that exists (the first candidate when none
/// does, for the message).
pub fn supply_path() -> std::path::PathBuf {
    if let Some(path) = std::env::var_os("BEAM_IMPACT_SUPPLY_RE1") {
        return path.into();
    }
    let tail = "shared/data/mss-supply-vessel/supply.re1";
    let manifest = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut candidates: Vec<std::path::PathBuf> = manifest.ancestors().skip(1).map(|a| a.join(tail)).collect();
    candidates.push(std::path::Path::new("/work").join(tail));
    candidates.iter().find(|p| p.is_file()).unwrap_or(&candidates[0]).clone()
}

fn supply() -> RaoTable {
    let path = supply_path();
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| {
        panic!("{}: {e} (the MSS supply vessel's .re1; set BEAM_IMPACT_SUPPLY_RE1 to its path)", path.display())
    });
    RaoTable::parse_re1(&text).unwrap()
}

fn fixture() -> RaoTable {
    RaoTable::parse_csv(include_str!("fixtures/sea-raos.csv")).unwrap()
}

const G: f64 = 9.81;

/// The supply vessel's highest frequency as VERES prints it (pi to 7 digits).
#[allow(clippy::approx_constant)]
const SUPPLY_TOP: f64 = 3.141593;

#[test]
fn veres_supply_vessel_reads_19_headings_by_36_frequencies_completed_by_symmetry() {
    let t = supply();
    assert_eq!(t.frequencies.len(), 36);
    assert_eq!(t.given_headings, 19);
    // VERES's 0..180 are our 180..360; mirrored, 0 and 180 map onto themselves: 36 headings.
    assert_eq!(t.headings.len(), 36);
    assert_eq!((t.headings[0], t.headings[35]), (0.0, 350.0));
    let (lo, hi) = t.frequency_range();
    assert!((lo - 0.1047198).abs() < 1e-9 && (hi - SUPPLY_TOP).abs() < 1e-9);
    match &t.source {
        RaoSource::Veres { ship, speed, reference_x, reference_z } => {
            assert_eq!(ship, "Supply");
            assert_eq!(*speed, 0.0);
            assert!((reference_x - 5.38592).abs() < 1e-6 && (reference_z - 6.0).abs() < 1e-9);
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn veres_supply_vessel_heaves_with_long_waves_at_phase_zero_in_every_heading() {
    let t = supply();
    let w = t.frequencies[0];
    for beta in (0..360).step_by(10) {
        let h = t.at_frequency(&t.at_heading(f64::from(beta)).unwrap(), w).unwrap();
        // At w = 0.105 rad/s (a 5.6 km wave on an 83 m hull) heave is the elevation within 0.1 %
        // (VERES prints 0.99983 to 1.00000) and its phase within 0.1 deg.
        assert!((h[2].norm() - 1.0).abs() < 1e-3, "beta {beta}: |heave| {}", h[2].norm());
        assert!(h[2].arg().to_degrees().abs() < 0.1, "beta {beta}: heave phase {}", h[2].arg().to_degrees());
    }
}

#[test]
fn veres_supply_vessel_pitches_with_the_wave_slope_bow_down_after_the_crest_in_head_seas() {
    let t = supply();
    for (beta, sign) in [(180.0, -1.0), (0.0, 1.0)] {
        let column = t.at_heading(beta).unwrap();
        for k in 0..2 {
            let w = t.frequencies[k];
            let h = t.at_frequency(&column, w).unwrap();
            let slope = Complex::new(0.0, sign * w * w / G); // i k cos(beta)
            let ratio = h[4] / slope;
            // The hull follows the slope up to O((k Lpp)^2) (k Lpp = 0.09 and 0.37 here): VERES
            // gives 1.023 and 1.031 of it; 5 % and 3 deg.
            assert!((ratio.norm() - 1.0).abs() < 0.05, "beta {beta}, w {w}: pitch / slope = {ratio}");
            assert!(ratio.arg().to_degrees().abs() < 3.0, "beta {beta}, w {w}: phase {}", ratio.arg().to_degrees());
            // Surge: the particles' excursion -i cos(beta) (+90 deg in head seas).
            let surge = h[0] / Complex::new(0.0, -beta.to_radians().cos());
            assert!((surge.norm() - 1.0).abs() < 0.02 && surge.arg().abs() < 0.05, "beta {beta}: surge {surge}");
        }
    }
}

#[test]
fn veres_supply_vessel_sways_and_rolls_towards_where_beam_waves_travel() {
    let t = supply();
    let w = t.frequencies[0];
    for beta in [90.0f64, 270.0] {
        let h = t.at_frequency(&t.at_heading(beta).unwrap(), w).unwrap();
        let s = beta.to_radians().sin();
        // Sway -i sin(beta) within 1 %; roll -i k sin(beta) in sign and phase (its amplitude is
        // 1.6 k: the roll resonance already lifts it).
        let sway = h[1] / Complex::new(0.0, -s);
        assert!((sway.norm() - 1.0).abs() < 0.01 && sway.arg().abs() < 0.02, "beta {beta}: sway {sway}");
        let roll = h[3] / Complex::new(0.0, -s * w * w / G);
        assert!(roll.re > 0.0 && roll.arg().abs() < 0.1, "beta {beta}: roll / slope {roll}");
    }
}

#[test]
fn interpolation_is_linear_on_the_complex_value_between_frequencies_and_headings() {
    let t = fixture();
    let nf = t.frequencies.len();
    // At grid points: the file's values (the fixture's headings 180..360 by 15 deg, mirrored).
    let column = t.at_heading(195.0).unwrap();
    let k = t.headings.iter().position(|h| *h == 195.0).unwrap();
    assert_eq!(column, t.values[k * nf..(k + 1) * nf].to_vec());
    let w0 = t.frequencies[3];
    assert_eq!(t.at_frequency(&column, w0).unwrap(), column[3]);
    // Half way between two frequencies: the mean of the complex neighbours (to round-off).
    let mid = t.at_frequency(&column, 0.5 * (t.frequencies[3] + t.frequencies[4])).unwrap();
    for j in 0..6 {
        let mean = (column[3][j] + column[4][j]) * 0.5;
        assert!((mid[j] - mean).norm() <= 1e-14 * (1.0 + mean.norm()), "dof {j}");
    }
    // A third of the way between two headings.
    let (a, b) = (t.at_heading(180.0).unwrap(), t.at_heading(195.0).unwrap());
    let c = t.at_heading(185.0).unwrap();
    for f in [0, 10, 39] {
        for j in 0..6 {
            let expected = a[f][j] + (b[f][j] - a[f][j]) / 3.0;
            assert!((c[f][j] - expected).norm() <= 1e-14 * (1.0 + expected.norm()));
        }
    }
    // Across 360: between 345 and 0 (the file's 360).
    let (a, b, c) = (t.at_heading(345.0).unwrap(), t.at_heading(0.0).unwrap(), t.at_heading(352.5).unwrap());
    assert!((c[5][2] - (a[5][2] + b[5][2]) * 0.5).norm() < 1e-14);
    // Outside the frequencies: none (the sea keeps its components inside).
    assert!(t.at_frequency(&column, 0.05).is_none() && t.at_frequency(&column, 4.5).is_none());
}

#[test]
fn the_fixtures_mirror_keeps_the_long_wave_signs() {
    // The fixture gives 180..360 (waves from port and ahead); the mirror gives beam seas from
    // starboard: sway -i sin(90) = -i, roll -i k.
    let t = fixture();
    let h = t.at_frequency(&t.at_heading(90.0).unwrap(), t.frequencies[0]).unwrap();
    assert!((h[1] - Complex::new(0.0, -1.0)).norm() < 1e-8, "{}", h[1]);
    assert!(h[3].im < 0.0 && h[3].re.abs() < 0.1 * h[3].im.abs(), "{}", h[3]);
}

#[test]
fn a_heading_between_sparse_headings_is_refused_naming_both() {
    let header = include_str!("fixtures/sea-raos.csv").lines().nth(1).unwrap();
    let mut text = format!("{header}\n");
    for heading in [0, 90] {
        for w in [0.5, 1.0] {
            text += &format!("{w},{heading},0,0,0,0,1,0,0,0,0,0,0,0\n");
        }
    }
    let t = RaoTable::parse_csv(&text).unwrap();
    // 0 and 90 mirror to 0 and 270: 45 deg lies between 0 and 90, 90 deg apart.
    let e = t.at_heading(45.0).unwrap_err();
    assert!(e.contains("between the RAO file's headings 0 and 90 deg, 90 deg apart"), "{e}");
}

#[test]
fn hostile_rao_files_are_one_line_errors() {
    let header = include_str!("fixtures/sea-raos.csv").lines().nth(1).unwrap();
    let row = |w: &str, h: &str| format!("{w},{h},0,0,0,0,1,0,0,0,0,0,0,0\n");
    let cases: Vec<(String, &str)> = vec![
        (String::new(), "no header"),
        ("root:x:0:0:root:/root:/bin/bash\n".into(), "is not an RAO CSV header"),
        (format!("{header}\n{}{}", row("0.5", "180"), row("nan", "180")), "`frequency` = NaN is not finite"),
        (format!("{header}\n{}{}", row("0.5", "180"), row("0.5", "180")), "is given twice (lines 2 and 3)"),
        (
            format!("{header}\n{}{}{}", row("0.5", "180"), row("1", "180"), row("0.5", "195")),
            "heading 195 deg has no row at frequency 1 rad/s",
        ),
        (format!("{header}\n{}", row("0.5", "180")), "at least 2"),
        (format!("{header}\n{}", row("-1", "180")), "frequency = -1 rad/s is not > 0"),
        (format!("{header}\n0.5,180,0,0,0,0,-1,0,0,0,0,0,0,0\n"), "heave = -1 m/m is not an amplitude"),
        (format!("{header}\n0.5,180,0,0,0,0,1,0,0,0,0,0,0\n"), "13 fields, the header has 14 columns"),
        (format!("{header},extra\n"), "unknown column `extra`"),
        (
            " MOTION TRANSFER FUNCTIONS\n\n\n\n\n\n1025 9.81\n80 20 6\n5 7\n1 2 3 6\n0 0 0 0 0\n0\n0.5\n1 0 0\n2 0 0\n3 1 0\n4 0 0\n5 0 0\n6 0 0\n0.4\n"
                .into(),
            "frequency 0.4 rad/s does not follow 0.5 rad/s",
        ),
        (" MOTION TRANSFER FUNCTIONS\n\n\n\n\n\n1025 9.81\n80 20 6\n5 7\n1 2000000 3 6\n".into(), "headings, expected 1 to 180"),
        (" MOTION TRANSFER FUNCTIONS\n\n\n\n\n\n1025 9.81\n80 20 6\n5 7\n1 1 2 6\n0 0 0 0 0\n0\n0.5\n1 0 0\n".into(), "the file ends before"),
    ];
    for (text, expected) in cases {
        let e = RaoTable::parse(&text).unwrap_err();
        assert!(e.contains(expected), "{expected:?}: {e}");
        assert!(!e.contains('\n') && e.len() < 600, "{e}");
        assert!(!e.contains("root"), "{e}");
    }
}

#[test]
fn a_million_rows_are_refused_at_the_limit_within_a_second() {
    let header = include_str!("fixtures/sea-raos.csv").lines().nth(1).unwrap();
    let mut text = format!("{header}\n");
    for k in 0..1_000_000 {
        text += &format!("{},{},0,0,0,0,1,0,0,0,0,0,0,0\n", 0.001 + k as f64 * 1e-5, 180);
    }
    let started = std::time::Instant::now();
    let e = RaoTable::parse_csv(&text).unwrap_err();
    assert!(e.contains(&format!("more than {MAX_ROWS} rows")), "{e}");
    // Refused when the limit is reached, before the rest is read (a few tens of ms in release).
    assert!(started.elapsed().as_secs_f64() < 1.0, "{:?}", started.elapsed());
}
