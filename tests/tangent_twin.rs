//! The twin's sensitivity from the printed run's tangent (issue 43, `src/simulation/tangent.rs`)
//! against the real twin (drop height x (1 + 1e-9)) over a grid of drop heights, damping ratios,
//! contact positions and sea instants: the same trust verdict on every case, and linearised
//! spreads of the real twin's order wherever the real twin's are above its own round-off floor.

use beam_impact::answer::{self, twin_scenario};
use beam_impact::record::NullRecorder;
use beam_impact::solver::ModalCache;
use beam_impact::{Scenario, Simulation};

/// The linearised spreads, their bound and the real twin's spreads, each [whole 5, first 5, env 4].
struct Pair {
    linearised: [f64; 14],
    real: [f64; 14],
    bound: f64,
    graze: f64,
}

fn rel(a: f64, b: f64) -> f64 {
    if a == b {
        0.0
    } else {
        (a - b).abs() / b.abs()
    }
}

fn pair(s: &Scenario) -> Pair {
    let cache = answer::own_cache();
    let twin = twin_scenario(s);
    let mut printed = Simulation::new_cached(s, &cache).unwrap();
    assert!(printed.follow_tangent(&twin, &cache).unwrap(), "the tangent follows");
    let summary = printed.run(&mut NullRecorder).unwrap();
    let l = printed.linearised(&summary).expect("followed to the end");
    let mut t = Simulation::new_cached(&twin, &cache).unwrap();
    let ts = t.run(&mut NullRecorder).unwrap();
    let mut linearised = [0.0; 14];
    let mut real = [0.0; 14];
    let (pw, pf, tw, tf) = (
        summary.peaks.as_array(),
        summary.first_contact_peaks.as_array(),
        ts.peaks.as_array(),
        ts.first_contact_peaks.as_array(),
    );
    for k in 0..5 {
        linearised[k] = l.whole.as_array()[k];
        linearised[5 + k] = l.first_contact.as_array()[k];
        real[k] = rel(tw[k], pw[k]);
        real[5 + k] = rel(tf[k], pf[k]);
    }
    let (pe, te) = (summary.envelope.peak_values(), ts.envelope.peak_values());
    for k in 0..4 {
        linearised[10 + k] = l.envelope[k].unwrap_or(0.0);
        real[10 + k] = match (te[k], pe[k]) {
            (Some(a), Some(b)) => rel(a, b),
            _ => 0.0,
        };
    }
    Pair { linearised, real, bound: l.bound, graze: l.graze }
}

fn grid() -> Vec<(String, Scenario)> {
    let mut cases = Vec::new();
    for &drop in &[0.1, 0.5, 2.0] {
        for &damping in &[0.0, 0.01, 0.05] {
            for &contact in &[4.0, 13.0, 29.0] {
                let s = Scenario {
                    drop_height: drop,
                    damping_ratio: damping,
                    contact_position: contact,
                    duration: 1.0,
                    ..Scenario::default()
                };
                cases.push((format!("drop {drop} damping {damping} contact {contact}"), s));
            }
        }
    }
    cases
}

#[test]
#[ignore]
fn print_the_grid() {
    for (name, s) in grid() {
        let Ok(_) = s.validate() else { continue };
        let p = pair(&s);
        let lw = p.linearised.iter().cloned().fold(0.0, f64::max);
        let rw = p.real.iter().cloned().fold(0.0, f64::max);
        println!("{name}: bound {:.2e} graze {:.2e} lin max {lw:.2e} real max {rw:.2e}", p.bound, p.graze);
        println!("   lin  {:?}", p.linearised.map(|v| format!("{v:.1e}")));
        println!("   real {:?}", p.real.map(|v| format!("{v:.1e}")));
    }
}

fn sea(shift: f64, seed: u64) -> Scenario {
    let mut s =
        beam_impact::scenario_file::read_file(std::path::Path::new("examples/vessel-sea.toml"), &mut Vec::new())
            .unwrap();
    let sea = s.sea.as_mut().unwrap();
    sea.time_shift = shift;
    sea.seed = seed;
    s
}

/// The answer as a campaign's event takes it, with the tangent (true) or the real twin (false).
fn event(s: &Scenario, linearised_twin: bool) -> answer::Answer {
    let options =
        answer::Options { observed_order: false, station_envelope: false, linearised_twin, ..Default::default() };
    answer::run(s, &mut NullRecorder, options).unwrap()
}

#[test]
#[ignore]
fn print_the_sea() {
    let mut linearised = 0;
    let mut total = 0;
    for i in 0..40 {
        let s = sea(i as f64 * 13.7, 1 + (i % 4) as u64);
        let a = event(&s, true);
        let b = event(&s, false);
        let twin = a.runs.iter().find(|r| r.role == "twin").unwrap();
        total += 1;
        linearised += usize::from(twin.linearised);
        let (sa, sb) = (a.quality.checks.sensitivity.unwrap(), b.quality.checks.sensitivity.unwrap());
        println!(
            "{i}: linearised {} sens {:.2e} vs real {:.2e} pass {} {} trusted {} {}",
            twin.linearised, sa.value, sb.value, sa.pass, sb.pass, a.quality.trusted, b.quality.trusted
        );
    }
    println!("{linearised} of {total} linearised");
}
