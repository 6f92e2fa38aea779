//! The paper's published values (Čatipović, Vladimir, Reljić 2008, Tables 1-3, Figure 6) for
//! the reconstructed scenario of SCENARIO.md. Tolerances are those the reconstruction
//! supports (SCENARIO.md, last paragraph): Tables 2-3 within 1 %, the energy column to its
//! printed digits (±0.5 %), the FEM column within 10 %, contact windows within 0.05 s.

use beam_impact::compare::merged_windows;
use beam_impact::paper;
use beam_impact::record::NullRecorder;
use beam_impact::results::Summary;
use beam_impact::solver::initial::Pitching;
use beam_impact::solver::EnergyMethod;
use beam_impact::{Scenario, Simulation};

fn paper_run() -> Summary {
    Simulation::new(&Scenario::paper()).unwrap().run(&mut NullRecorder).unwrap()
}

fn within(value: f64, reference: f64, tolerance: f64, what: &str) {
    let rel = value / reference - 1.0;
    assert!(rel.abs() <= tolerance, "{what}: {value} vs paper {reference} ({:+.2} %)", rel * 100.0);
}

/// Table 2, every printed value within 1 % (the bridge's rigid mode exactly 0).
#[test]
fn table2_natural_frequencies_within_one_percent() {
    let simulation = Simulation::new(&Scenario::paper()).unwrap();
    let modes = simulation.mode_table(5);
    for (c, column) in [&modes.lower, &modes.upper, &modes.coupled].iter().enumerate() {
        for n in 0..5 {
            let printed = paper::TABLE2[c][n];
            if printed == 0.0 {
                assert_eq!(column[n], 0.0);
            } else {
                within(column[n], printed, 0.01, &format!("Table 2 column {} mode {}", c + 1, n + 1));
            }
        }
    }
}

/// Table 3, periods 2 pi / omega. The paper prints three decimals, so its own 2 pi / 546.1 =
/// 0.0115 s prints as 0.012: a printed value p stands for [p - 0.0005, p + 0.0005]. Ours must
/// lie within 1 % of p from that interval.
#[test]
fn table3_natural_periods_within_one_percent_at_printed_precision() {
    let simulation = Simulation::new(&Scenario::paper()).unwrap();
    let modes = simulation.mode_table(5);
    for (c, column) in [&modes.lower, &modes.upper, &modes.coupled].iter().enumerate() {
        for n in 0..5 {
            let printed = paper::TABLE3[c][n];
            if printed.is_nan() {
                continue; // the bridge's rigid mode has no period ("/")
            }
            let period = 2.0 * std::f64::consts::PI / column[n];
            let outside = ((period - printed).abs() - 0.0005).max(0.0);
            assert!(
                outside <= 0.01 * printed,
                "Table 3 column {} mode {}: {period:.5} s vs printed {printed}",
                c + 1,
                n + 1
            );
        }
    }
}

/// Table 1, energy column and E_def,a (Eqs. 29, 33, 35), to the printed digits.
#[test]
fn table1_energy_approach_column() {
    let e = EnergyMethod::new(&Scenario::paper());
    within(e.tip_deflection, 0.628, 0.005, "w_din");
    within(e.clamp_bending_stress, 412e6, 0.005, "sigma_din,a");
    within(e.clamp_shear_stress, 40e6, 0.012, "tau_din,a (paper prints 40 for 39.6)");
    within(e.strain_energy, 149.2e3, 0.001, "E_def,a");
}

/// Eqs. (20)-(22) for h = 0.567 m: alpha_u0 = 2.24 deg, t0 = 0.392 s, omega_u0 = 0.199 rad/s
/// (SCENARIO.md), to the digits given there.
#[test]
fn rigid_pitching_before_impact_matches_scenario() {
    let p = Pitching::new(0.567, 29.0, 9.81);
    assert!((p.initial_angle.to_degrees() - 2.24).abs() < 0.005, "{}", p.initial_angle.to_degrees());
    assert!((p.fall_time - 0.392).abs() < 0.0005, "{}", p.fall_time);
    assert!((p.angular_velocity - 0.199).abs() < 0.0005, "{}", p.angular_velocity);
}

/// Table 1 FEM column within 10 %, about 90 000 steps (±5 %), and Figure 6's long separation.
#[test]
fn table1_fem_column_steps_and_figure6_separation() {
    let s = paper_run();
    let p = &s.peaks;
    within(p.lower_tip_deflection, 0.691, 0.10, "w_din,a");
    within(p.lower_clamp_bending_stress, 492e6, 0.10, "sigma_din,a");
    within(p.lower_clamp_shear_stress, 59e6, 0.10, "tau_din,a");
    within(p.upper_contact_bending_stress, 295e6, 0.10, "sigma_din,b");
    within(s.steps as f64, 90_000.0, 0.05, "steps");

    // Figure 6: the first long contact ends at 0.77 s and sustained contact resumes at 1.44 s.
    // "Sustained" = windows of 0.1 s or more after merging bounces closer than 10 ms: the
    // reconstructed arrestor grazes the falling bridge for two ~10 ms windows near 1.30-1.35 s,
    // which the paper's figure does not show (reported in the run output, not hidden here).
    let sustained: Vec<_> =
        merged_windows(&s.contact_windows, 0.01).into_iter().filter(|w| w.end - w.start >= 0.1).collect();
    assert!(sustained.len() >= 2, "{sustained:?}");
    assert!((sustained[0].end - paper::SEPARATION.0).abs() <= 0.05, "separation starts {}", sustained[0].end);
    assert!((sustained[1].start - paper::SEPARATION.1).abs() <= 0.05, "contact resumes {}", sustained[1].start);
}

/// Appendix A: deflections barely change with damping (all within 5 % of gamma = 0.03), the
/// bridge's stress is much higher without damping (gamma = 0: over 1.5x), and from gamma = 0.02
/// on it levels off: 0.02-0.04 within 15 % of each other ("approximately equal" in the paper,
/// against a 2x jump at gamma = 0). Measured: w 0.674/0.657 m and sigma_b 580/292 MPa at
/// gamma 0/0.03; sigma_b 299, 292, 271 MPa at gamma 0.02, 0.03, 0.04.
#[test]
fn appendix_a_damping_study_shapes() {
    let rows = beam_impact::studies::damping::run(&Scenario::paper(), &beam_impact::studies::damping::RATIOS).unwrap();
    let peaks = |gamma: f64| rows.iter().find(|(g, _)| *g == gamma).unwrap().1.peaks;
    let reference = peaks(0.03);
    for (gamma, summary) in &rows {
        let w = summary.peaks.lower_tip_deflection;
        assert!((w / reference.lower_tip_deflection - 1.0).abs() < 0.05, "gamma {gamma}: w {w}");
    }
    assert!(peaks(0.0).upper_contact_bending_stress > 1.5 * reference.upper_contact_bending_stress);
    let levelled: Vec<f64> = [0.02, 0.03, 0.04].iter().map(|&g| peaks(g).upper_contact_bending_stress).collect();
    let (lo, hi) = levelled.iter().fold((f64::MAX, 0.0f64), |(lo, hi), &x| (lo.min(x), hi.max(x)));
    assert!(hi / lo < 1.15, "{levelled:?}");
}

/// Stress recovery at the bridge's contact node (issue 7): the mean of the two adjacent elements
/// gives 292.1 MPa over the whole run, the hinge-side element alone 296.0 MPa (both to 0.05 MPa,
/// measured 292.148 and 296.026), the free-end side 291.2 MPa; the first sustained contact
/// (until 0.7495 s) peaks at 280.1 MPa with the mean. The arrestor's values do not depend on it.
#[test]
fn bridge_stress_recovery_is_selectable_and_the_first_contact_is_reported() {
    use beam_impact::model::StressRecovery;
    let run = |recovery: StressRecovery| {
        let scenario = Scenario { stress_recovery: recovery, ..Scenario::paper() };
        Simulation::new(&scenario).unwrap().run(&mut NullRecorder).unwrap()
    };
    let (mean, left, right) = (run(StressRecovery::Mean), run(StressRecovery::Left), run(StressRecovery::Right));
    let mpa = |s: &beam_impact::results::Summary| s.peaks.upper_contact_bending_stress / 1e6;
    assert!((mpa(&mean) - 292.1).abs() < 0.05, "{}", mpa(&mean));
    assert!((mpa(&left) - 296.0).abs() < 0.05, "{}", mpa(&left));
    assert!((mpa(&right) - 291.2).abs() < 0.05, "{}", mpa(&right));
    assert_eq!(mean.peaks.lower_clamp_bending_stress, left.peaks.lower_clamp_bending_stress);
    assert!((mean.first_contact_end.unwrap() - 0.7495).abs() < 1e-3, "{:?}", mean.first_contact_end);
    let first = mean.first_contact_peaks.upper_contact_bending_stress / 1e6;
    assert!((first - 280.1).abs() < 0.05, "{first}");
    assert_eq!(mean.first_contact_peaks.lower_tip_deflection, mean.peaks.lower_tip_deflection);
}
