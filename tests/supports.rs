//! The struck beam's supports and contact position (issue 45, item 2): each support condition's
//! natural frequencies against Blevins' closed forms, static deflections and reactions against
//! the beam tables, an impact at midspan of a pinned-pinned beam run converged and trusted, a
//! grid of supports, contact positions and drop heights without a panic, and the new fields
//! through `--set` and `--vary`.

use std::process::Command;

use beam_impact::answer::{self, Options};
use beam_impact::model::supports::{Supports, SUPPORTS_NAMES};
use beam_impact::model::Model;
use beam_impact::record::NullRecorder;
use beam_impact::solver::eigen::natural_modes;
use beam_impact::solver::static_contact::static_response;
use beam_impact::{Scenario, Simulation};

const ALL: [Supports; 4] =
    [Supports::ClampedFree, Supports::PinnedPinned, Supports::ClampedClamped, Supports::ClampedPinned];

/// A scenario whose struck beam is uniform without a lumped mass, on `supports`, meshed by
/// `elements` (the bridge on the paper's 7 + 7/7).
fn struck(supports: Supports, elements: u32) -> Scenario {
    let mut s = Scenario::paper_mesh();
    s.lower.supports = supports;
    s.lower.tip_mass = 0.0;
    s.lower.elements = elements;
    s
}

/// Each support condition's first four natural frequencies against Blevins (1979), Table 8-1:
/// omega_i = (lambda_i L)^2 sqrt(E I / (m L^4)), m per length. The Hermite element with
/// consistent mass bounds each frequency from above, with a leading error in omega_i^2 of
/// (lambda_i h)^4 / 720 (h = L / N), (lambda_i h)^4 / 1440 in omega_i: measured 0.69 of
/// (lambda_i h)^4 / 1000 for every mode here (1.1e-5 for the fourth clamped-clamped mode on
/// 40 elements, lambda_4 h = 0.353), so the tolerance (lambda_i h)^4 / 1000 holds each mode to
/// its mesh's own error and fails at a wrong lambda's fifth digit.
#[test]
fn each_support_conditions_frequencies_match_blevins() {
    for supports in ALL {
        let s = struck(supports, 40);
        let model = Model::new(&s).unwrap();
        assert_eq!(model.lower.mesh.rigid_modes(), 0, "{supports:?}");
        let modes = natural_modes(&model.lower.stiffness, &model.lower.mass, 0).unwrap();
        let l = &s.lower;
        let scale = (l.elastic_modulus * l.second_moment / (l.mass / l.length)).sqrt() / (l.length * l.length);
        for (i, lambda) in supports.blevins_lambda().iter().enumerate() {
            let expected = lambda * lambda * scale;
            let ours = modes.omega[i];
            assert!(ours >= expected * (1.0 - 1e-9), "{supports:?} mode {}: {ours} below {expected}", i + 1);
            let h = l.length / 40.0;
            let bound = (lambda / l.length * h).powi(4) / 1000.0;
            assert!((ours / expected - 1.0).abs() < bound, "{supports:?} mode {}: {ours} vs {expected}", i + 1);
        }
    }
}

/// A unit load at the contact node, solved by the struck beam's own stiffness: Hermite elements
/// give the exact nodal deflections of point loads at nodes, so every condition's deflection
/// under the load matches Roark's closed form ([`Supports::point_load`]) to round-off (1e-9),
/// at midspan (P L^3 / 48 EI pinned-pinned, P L^3 / 192 EI clamped-clamped, 7 P L^3 / 768 EI
/// clamped-pinned) and off-centre (0.3 L), and the first support's moment and shear too.
#[test]
fn static_point_load_deflections_and_first_support_reactions_match_the_tables() {
    for supports in ALL {
        for fraction in [0.5, 0.3] {
            let mut s = struck(supports, 20);
            let length = s.lower.length;
            s.lower.contact_position = fraction * length;
            s.gravity = 0.0;
            s.impact_angular_velocity = Some(0.1);
            s.drop_height = 0.0;
            let model = Model::new(&s).unwrap();
            let node = model.lower_contact_node;
            assert!((model.lower.mesh.nodes[node].x - fraction * length).abs() < 1e-12);
            let load = model.lower.deflection_functional(node) * -1.0; // 1 N down
            let u = model.lower.stiffness.clone().cholesky().unwrap().solve(&load);
            let ei = s.lower.elastic_modulus * s.lower.second_moment;
            let expected = supports.point_load(ei, length, fraction * length);
            let w = -u[model.lower.mesh.nodes[node].w.unwrap()];
            assert!((w / expected.flexibility - 1.0).abs() < 1e-9, "{supports:?} at {fraction} L: {w}");
            if fraction == 0.5 {
                let closed = match supports {
                    Supports::ClampedFree => (length / 2.0).powi(3) / (3.0 * ei),
                    Supports::PinnedPinned => length.powi(3) / (48.0 * ei),
                    Supports::ClampedClamped => length.powi(3) / (192.0 * ei),
                    Supports::ClampedPinned => 7.0 * length.powi(3) / (768.0 * ei),
                };
                assert!((w / closed - 1.0).abs() < 1e-9, "{supports:?}: {w} vs {closed}");
            }
            // The reactions of both supports, from the model's functionals (no inertia at rest).
            let global = model.stack(&u, &nalgebra::DVector::zeros(model.upper.dofs()));
            let [force, moment, _] = model.reactions().map(|r| r.stiffness.dot(&global));
            let [far_force, far_moment] = model.far_reactions().map(|r| r.stiffness.dot(&global));
            assert!((force + far_force - 1.0).abs() < 1e-9, "{supports:?}: {force} + {far_force} != 1 N");
            assert!((force - expected.first_shear).abs() < 1e-9, "{supports:?}: {force} vs {expected:?}");
            assert!((moment.abs() - expected.first_moment).abs() < 1e-9 * length, "{supports:?}: {moment}");
            // Moment balance about the first support: M_1 + M_2 + R_2 L - P a = 0 (counter-clockwise).
            let balance = moment + far_moment + far_force * length - fraction * length;
            assert!(balance.abs() < 1e-9 * length, "{supports:?}: moment balance {balance}");
            if !supports.far_is_clamped() {
                assert_eq!(far_moment, 0.0, "{supports:?}");
            }
        }
    }
}

/// The bridge resting on a deck beam (the static contact solution): the midspan deflection is the
/// contact force's P L^3 / 48 EI (pinned-pinned) or P L^3 / 192 EI (clamped-clamped) plus the
/// self-weight's 5 q L^4 / 384 EI or q L^4 / 384 EI (exact at the nodes for the consistent
/// loads), the two supports' forces sum to the contact force plus the beam's weight and share
/// them equally, and the clamps' moments are P L / 8 + q L^2 / 12. Tolerance 1e-7: the static
/// solve holds P to about 1e-8 (static_contact.rs's tests).
#[test]
fn the_bridge_resting_at_midspan_deflects_the_beam_as_the_tables_say() {
    for supports in [Supports::PinnedPinned, Supports::ClampedClamped] {
        let s = struck(supports, 20);
        let r = static_response(&s).unwrap().expect("the bridge rests on the beam");
        let l = &s.lower;
        let (length, ei) = (l.length, l.elastic_modulus * l.second_moment);
        let p = -r.signed.contact_force;
        let q = l.mass / length * s.gravity;
        let expected = match supports {
            Supports::PinnedPinned => p * length.powi(3) / (48.0 * ei) + 5.0 * q * length.powi(4) / (384.0 * ei),
            _ => p * length.powi(3) / (192.0 * ei) + q * length.powi(4) / (384.0 * ei),
        };
        let w = -r.signed.lower_tip_deflection;
        assert!((w / expected - 1.0).abs() < 1e-7, "{supports:?}: {w} vs {expected}");
        let total = p + l.mass * s.gravity;
        let (first, far) = (r.reactions[0], r.far_reactions[0]);
        assert!(((first + far) / total - 1.0).abs() < 1e-7, "{supports:?}: {first} + {far} vs {total}");
        assert!((first / far - 1.0).abs() < 1e-7, "{supports:?}: symmetric {first} vs {far}");
        if supports == Supports::ClampedClamped {
            let m = p * length / 8.0 + q * length * length / 12.0;
            assert!((r.reactions[1].abs() / m - 1.0).abs() < 1e-7, "{}: {m}", r.reactions[1]);
            assert!((r.far_reactions[1].abs() / m - 1.0).abs() < 1e-7, "{}: {m}", r.far_reactions[1]);
        } else {
            assert_eq!(r.reactions[1], 0.0);
        }
    }
}

/// The example deck beam (pinned-pinned, struck at midspan by the paper's bridge on a pad) runs
/// converged and trusted, its worst arrestor bending stress at midspan and none at the pins, its
/// contact force well above the resting one (the static contact solution).
#[test]
fn an_impact_at_midspan_of_a_pinned_pinned_beam_runs_converged_and_trusted() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/deck-beam-supports.toml");
    let s = Scenario::from_toml(&std::fs::read_to_string(path).unwrap(), path).unwrap();
    let a = answer::run(&s, &mut NullRecorder, Options::default()).unwrap();
    assert!(a.quality.trusted, "{:?}", a.quality.reasons);
    assert_eq!(a.converged_peaks.lower_clamp_bending_stress, 0.0, "a pin carries no moment");
    let worst = a.envelope_peaks[2].expect("the arrestor's bending envelope");
    assert!((worst.position - 6.0).abs() < 1e-9, "{worst:?}");
    // The dropped bridge strikes harder than it rests: the peak above the static contact force.
    let resting = static_response(&s).unwrap().expect("the bridge rests on the beam");
    assert!(a.converged_peaks.contact_force > 2.0 * resting.peaks.contact_force, "{:?}", a.converged_peaks);
}

/// Every support with the contact near each end and at midspan, dropped from rest and from
/// 0.5 m, on the paper's method (fast): each runs or fails with one line, never a panic.
#[test]
fn a_grid_of_supports_positions_and_drops_never_panics() {
    for supports in ALL {
        for fraction in [0.05, 0.5, 0.95, 1.0] {
            for drop_height in [0.0, 0.5] {
                let mut s = struck(supports, 10);
                s.lower.contact_position = fraction * s.lower.length;
                s.drop_height = drop_height;
                s.duration = 0.05;
                let outcome = std::panic::catch_unwind(|| {
                    Simulation::new(&s).and_then(|mut sim| sim.run(&mut NullRecorder).map(|_| ()))
                });
                let context = format!("{supports:?} at {fraction} L from {drop_height} m");
                match outcome.unwrap_or_else(|_| panic!("{context}: panicked")) {
                    Ok(()) => assert!(fraction < 1.0 || supports == Supports::ClampedFree, "{context}: ran"),
                    Err(e) => {
                        let text = e.to_string();
                        assert!(!text.contains('\n') && text.contains("lower.contact_position"), "{context}: {text}");
                    }
                }
            }
        }
    }
}

/// Out-of-range contact positions are refused with one line naming the field and the rule.
#[test]
fn contact_positions_off_the_beam_are_refused_naming_the_rule() {
    for (supports, x, rule) in [
        (Supports::ClampedFree, 12.5, "0 < x <= lower.length = 12 m"),
        (Supports::PinnedPinned, 12.0, "0 < x < lower.length = 12 m with lower.supports = \"pinned-pinned\""),
        (Supports::ClampedClamped, -1.0, "0 < x < lower.length"),
        (Supports::ClampedPinned, f64::NAN, "0 < x < lower.length"),
    ] {
        let mut s = Scenario::default();
        s.lower.supports = supports;
        s.lower.contact_position = x;
        let e = s.validate().unwrap_err().to_string();
        assert!(e.contains("lower.contact_position") && e.contains(rule), "{supports:?} {x}: {e}");
    }
    let text = "[lower]\nsupports = \"fixed-fixed\"\n";
    let e = Scenario::from_toml(text, "bad.toml").unwrap_err().to_string();
    assert!(e.contains("clamped-clamped") && !e.contains('\n'), "{e}");
}

fn beam_impact_cli() -> Command {
    Command::new(env!("CARGO_BIN_EXE_beam-impact"))
}

/// `--set lower.supports=pinned-pinned` and `--vary lower.supports=...` take the names, and
/// `--vary lower.contact_position` moves the contact along the beam; the sweep's CSV names them.
#[test]
fn set_and_vary_take_the_supports_and_the_contact_position() {
    let dir = std::env::temp_dir().join(format!("beam-impact-supports-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let json = dir.join("run.json");
    let out = beam_impact_cli()
        .args(["run", "--no-mcap", "--set", "duration=0.02", "--set", "lower.supports=clamped-clamped"])
        .args(["--set", "lower.tip_mass=0", "--set", "lower.contact_position=4", "--json"])
        .arg(&json)
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let doc: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let text = doc.to_string();
    assert!(text.contains("\"supports\":\"clamped-clamped\""), "{text:.400}");
    let bad = beam_impact_cli().args(["run", "--no-mcap", "--set", "lower.supports=simply"]).output().unwrap();
    assert_eq!(bad.status.code(), Some(2));
    let err = String::from_utf8_lossy(&bad.stderr);
    assert!(err.contains("lower.supports") && SUPPORTS_NAMES.iter().all(|n| err.contains(n)), "{err}");
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    let csv = dir.join("sweep.csv");
    let out = beam_impact_cli()
        .args(["sweep", "--set", "duration=0.02", "--set", "method=paper", "--set", "lower.tip_mass=0"])
        .args(["--vary", "lower.supports=pinned-pinned,clamped-pinned", "--vary", "lower.contact_position=3,6"])
        .arg("--out")
        .arg(&csv)
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let table = std::fs::read_to_string(&csv).unwrap();
    assert_eq!(table.lines().count(), 5, "{table}");
    assert!(table.contains("pinned-pinned") && table.contains("clamped-pinned"), "{table}");
    std::fs::remove_dir_all(&dir).ok();
}

/// A log of the deck beam replays through `report`: the scenario with its supports and contact
/// position, the first support's bending 0 (a pin), and the arrestor's bending envelope at its
/// midspan, the contact node, as the run printed it.
#[test]
fn a_deck_beam_log_replays_through_report() {
    let dir = std::env::temp_dir().join(format!("beam-impact-supports-log-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let log = dir.join("deck.mcap");
    let example = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/deck-beam-supports.toml");
    let run = beam_impact_cli().args(["run", example, "--mcap"]).arg(&log).output().unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let printed = String::from_utf8_lossy(&run.stdout).to_string();
    let report = beam_impact_cli().arg("report").arg(&log).arg("--out").arg(dir.join("figures")).output().unwrap();
    assert!(report.status.success(), "{}", String::from_utf8_lossy(&report.stderr));
    let text = String::from_utf8_lossy(&report.stdout);
    assert!(text.contains("supports = \"pinned-pinned\"") && text.contains("contact_position = 6.0"), "{text}");
    assert!(text.contains("pin bending stress       s_din,a     0.0000 MPa"), "{text}");
    // On two supports w_din,a is the contact point's deflection: the labels say so.
    assert!(text.contains("contact-point deflection w_din,a") && !text.contains("arrestor end deflection"), "{text}");
    assert!(printed.contains("w_din,a arrestor at contact [m]") && !printed.contains("end deflection"), "{printed}");
    let envelope = text.lines().find(|l| l.trim_start().starts_with("arrestor bending")).unwrap();
    assert!(envelope.contains("at x =   6.000 m"), "{envelope}");
    // The envelope's value is the run's own (its table prints it to 4 decimals).
    let value = envelope.split_whitespace().nth(2).unwrap();
    let row = printed.lines().find(|l| l.starts_with("sigma arrestor [MPa]")).unwrap();
    assert!(row.contains(value), "{row} vs {envelope}");
    std::fs::remove_dir_all(&dir).ok();
}

/// The far support's reactions during a run (issue 45): the bridge settling on a clamped-clamped
/// deck beam at midspan (drop height 0, damping ratio 0.9, 6 s, as `tests/reactions.rs` lets the
/// paper's pair settle): the two supports' forces each carry half of the contact force and the
/// beam's weight, and the clamps' moments are P L / 8 + q L^2 / 12, within 1 % of them (what is
/// left of the motion is far below it), and the run's values at t = 0 (the beam resting under its
/// own weight before the bridge's force) are its weight's halves and q L^2 / 12 to round-off.
#[test]
fn the_far_supports_reactions_carry_their_share_during_a_run() {
    let mut s = struck(Supports::ClampedClamped, 20);
    s.method = beam_impact::model::Method::Converged;
    s.drop_height = 0.0;
    s.damping_ratio = 0.9;
    s.duration = 6.0;
    let mut simulation = Simulation::new(&s).unwrap();
    let start = *simulation.result();
    let l = &s.lower;
    let (weight, q) = (l.mass * s.gravity, l.mass / l.length * s.gravity);
    assert!((start.lower_far_reaction_force / (weight / 2.0) - 1.0).abs() < 1e-9, "{start:?}");
    assert!((start.lower_clamp_reaction_force / (weight / 2.0) - 1.0).abs() < 1e-9, "{start:?}");
    let m0 = q * l.length * l.length / 12.0;
    assert!((start.lower_far_reaction_moment.abs() / m0 - 1.0).abs() < 1e-9, "{start:?}");
    assert!((start.lower_clamp_reaction_moment.abs() / m0 - 1.0).abs() < 1e-9, "{start:?}");
    simulation.run(&mut NullRecorder).unwrap();
    let r = simulation.output();
    let p = -r.contact_force;
    let share = (p + weight) / 2.0;
    assert!((r.lower_far_reaction_force / share - 1.0).abs() < 0.01, "{r:?}");
    assert!((r.lower_clamp_reaction_force / share - 1.0).abs() < 0.01, "{r:?}");
    let m = p * l.length / 8.0 + m0;
    assert!((r.lower_far_reaction_moment.abs() / m - 1.0).abs() < 0.01, "{r:?}");
    assert!((r.lower_clamp_reaction_moment.abs() / m - 1.0).abs() < 0.01, "{r:?}");
}

/// The far support's reactions replay from the log (issue 45): the deck beam's run (0.35 s, past
/// the bridge's first touch at about 0.25 s) logged, then `report --csv`: the far support's
/// columns are in the CSV by their FMU names, the first row (the beam resting under its own
/// weight) carries half the weight at the far pin to 1e-9 (the static share, as in
/// [`the_far_supports_reactions_carry_their_share_during_a_run`]), every moment is 0 (a pin), and
/// the last row is the run's own final value to the bit (the CSV round-trips f64).
#[test]
fn a_deck_beam_logs_far_reactions_replay_through_report_csv() {
    let dir = std::env::temp_dir().join(format!("beam-impact-supports-far-log-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (log, csv) = (dir.join("deck.mcap"), dir.join("deck.csv"));
    let example = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/deck-beam-supports.toml");
    let run = beam_impact_cli().args(["run", example, "--set", "duration=0.35", "--mcap"]).arg(&log).output().unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let report =
        beam_impact_cli().arg("report").arg(&log).arg("--csv").arg(&csv).arg("--out").arg(dir.join("f")).output();
    let report = report.unwrap();
    assert!(report.status.success(), "{}", String::from_utf8_lossy(&report.stderr));
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let rows: Vec<Vec<f64>> =
        lines.map(|l| l.split(',').map(|c| c.parse::<f64>().unwrap_or(f64::NAN)).collect()).collect();
    let column = |name: &str| {
        let k = header.iter().position(|h| *h == name).unwrap_or_else(|| panic!("no column {name}: {header:?}"));
        rows.iter().map(|r| r[k]).collect::<Vec<f64>>()
    };
    let (force, moment) = (column("lower.far_reaction_force"), column("lower.far_reaction_moment"));

    let mut s = Scenario::from_toml(&std::fs::read_to_string(example).unwrap(), "deck-beam-supports").unwrap();
    s.duration = 0.35;
    let mut simulation = Simulation::new(&s).unwrap();
    let weight = s.lower.mass * s.gravity;
    assert!((force[0] / (weight / 2.0) - 1.0).abs() < 1e-9, "{} vs {}", force[0], weight / 2.0);
    assert!(moment.iter().all(|&m| m == 0.0), "a pin carries no moment");
    simulation.run(&mut NullRecorder).unwrap();
    let r = simulation.output();
    assert!(r.contact_force != 0.0 || force.iter().any(|&f| f != force[0]), "the bridge has touched");
    assert_eq!(force.last().unwrap().to_bits(), r.lower_far_reaction_force.to_bits(), "{r:?}");
    std::fs::remove_dir_all(&dir).ok();
}
