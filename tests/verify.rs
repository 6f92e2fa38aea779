//! `beam-impact verify`: the convergence verdict on the four Table 1 peaks (issue 7) and F_c, the
//! refined meshes with refined modal cut-offs (issue 29).
//!
//! Source: the verdict the issue expects on the paper scenario (Čatipović, Vladimir, Reljić 2008,
//! Table 1, reconstructed in `../shared/paper/SCENARIO.md`): the arrestor's deflection w_din,a and
//! clamp bending stress sigma_din,a converge on the paper's 7 + 7/7 element mesh, while the clamp
//! shear stress tau_din,a and the whole-run bridge stress sigma_din,b do not: their peaks sit in
//! impact transients that 22 elements cannot resolve.
//! Measured (release, this solver): 2x -> 4x elements moves w by 0.003 %, sigma_a by 0.03 %,
//! tau_a by 10.5 % (its peak moves from the big swing at 0.36 s to the first impact at 4 ms) and
//! sigma_b by 1.4 %; sigma_b on the paper mesh is 7.6 % below the 4x mesh's.
//! The contact force F_c (issue 29) is judged too: 4.9 % from the 4x mesh's on the paper mesh.
//! Tolerance: the command's default, 1 % on each change; the converged peaks are 30x inside it and
//! the shear 10x outside it, so the verdicts do not hang on round-off. The other tests compare the
//! verdicts with separately run simulations exactly (the same deterministic runs, the same formula).

use std::process::Command;

use beam_impact::model::TimeStep;
use beam_impact::record::NullRecorder;
use beam_impact::results::seconds;
use beam_impact::studies::verify::{self, Verification, DEFAULT_TOLERANCE, PEAK_NAMES, RUN_NAMES};
use beam_impact::{Scenario, Simulation};

/// The JSON shape the issue documents: five named peaks (Table 1's and F_c), each with value, step_change,
/// mesh_change, estimate (number or null) and converged; plus the documented extras.
fn assert_documented_shape(doc: &serde_json::Value) {
    let peaks = doc["peaks"].as_object().expect("peaks is an object");
    let mut names: Vec<&str> = peaks.keys().map(String::as_str).collect();
    names.sort_unstable();
    let mut expected = PEAK_NAMES.to_vec();
    expected.sort_unstable();
    assert_eq!(names, expected);
    for name in PEAK_NAMES {
        let p = &doc["peaks"][name];
        for key in ["value", "step_change", "mesh_change"] {
            assert!(p[key].as_f64().is_some_and(f64::is_finite), "{name}.{key} = {}", p[key]);
        }
        assert!(p["estimate"].is_null() || p["estimate"].is_f64(), "{name}.estimate = {}", p["estimate"]);
        assert!(p["converged"].is_boolean(), "{name}.converged = {}", p["converged"]);
    }
    assert!(doc["tolerance"].is_f64());
    assert!(doc.get("mesh_capped").is_some(), "mesh_capped is always present (null when not capped)");
    for run in RUN_NAMES {
        assert!(doc["meshes"][run]["lower"].is_u64(), "meshes.{run}");
        assert!(doc["time_steps"][run]["free"].is_f64(), "time_steps.{run}");
        assert!(doc["trusted"][run].is_boolean(), "trusted.{run}");
        assert!(doc["modal_cutoffs"].get(run).is_some(), "modal_cutoffs.{run} (null: the full basis)");
    }
}

/// Paper scenario, default tolerance: w and sigma_a converged, tau_a and sigma_b not (issue 7).
#[test]
fn paper_scenario_flags_shear_and_bridge_stress_as_mesh_dependent() {
    let v = verify::verify(&Scenario::paper(), DEFAULT_TOLERANCE).unwrap();
    let p = &v.peaks;
    assert!(p.lower_tip_deflection.converged, "{p:#?}");
    assert!(p.lower_clamp_bending_stress.converged, "{p:#?}");
    assert!(!p.lower_clamp_shear_stress.converged, "{p:#?}");
    assert!(!p.upper_contact_bending_stress.converged, "{p:#?}");
    // F_c too (issue 29): the paper mesh's contact force is 4.9 % from the 4x mesh's (measured).
    assert!(!p.contact_force.converged && p.contact_force.base_mesh_change > 0.02, "{p:#?}");
    assert!(!v.converged);
    // The not-converged peaks fail on the mesh, not on the step: halving the steps moves every
    // peak by less than 0.2 % (F_c the most, 0.11 %).
    for peak in p.as_array() {
        assert!(peak.step_change < 2e-3, "{peak:?}");
    }
    assert!(p.lower_clamp_shear_stress.mesh_change > 0.05, "{p:#?}");
    // The paper mesh's sigma_b is well below the fine meshes', whatever the 2x-4x margin.
    assert!(p.upper_contact_bending_stress.base_mesh_change > 0.05, "{p:#?}");
    // The runs themselves are sound: every energy balance trusted, the paper mesh uncapped.
    assert!(v.trusted.as_array().iter().all(|t| **t), "{:?}", v.trusted);
    assert_eq!(v.mesh_capped, None);
    assert_eq!((v.meshes.mesh_2x.lower, v.meshes.mesh_4x.upper_beyond_contact), (14, 28));
    assert!((p.lower_tip_deflection.value - 0.657).abs() < 1e-3, "Table 1's FEM w_din,a: {p:#?}");
}

/// Another scenario (1 m drop at 15 m, 2 % damping, 1 s): every number in the JSON is the one
/// its own run gives, run separately with the documented steps and meshes.
#[test]
fn other_scenario_json_has_the_documented_shape_and_the_runs_own_peaks() {
    let scenario =
        Scenario { drop_height: 1.0, contact_position: 15.0, damping_ratio: 0.02, duration: 1.0, ..Scenario::paper() };
    let v: Verification = verify::verify(&scenario, 0.02).unwrap();
    let doc = serde_json::to_value(&v).unwrap();
    assert_documented_shape(&doc);
    assert_eq!(doc["tolerance"].as_f64(), Some(0.02));
    assert!(doc["mesh_capped"].is_null());

    let run = |s: &Scenario| Simulation::new(s).unwrap().run(&mut NullRecorder).unwrap();
    let base_sim = Simulation::new(&scenario).unwrap();
    let plan = *base_sim.step_plan();
    let base = run(&scenario);
    let half = run(&Scenario {
        step_free: TimeStep::Fixed(seconds(plan.free_ns / 2)),
        step_contact: TimeStep::Fixed(seconds(plan.contact_ns / 2)),
        ..scenario.clone()
    });
    let refined = |factor: u32| {
        let mut s = scenario.clone();
        s.lower.elements *= factor;
        s.upper.elements_to_contact *= factor;
        s.upper.elements_beyond_contact *= factor;
        s.step_free = TimeStep::Auto;
        s.step_contact = TimeStep::Auto;
        run(&s)
    };
    let (mesh_2x, mesh_4x) = (refined(2), refined(4));
    let (b, h, m2, m4) =
        (base.peaks.as_array(), half.peaks.as_array(), mesh_2x.peaks.as_array(), mesh_4x.peaks.as_array());
    for (k, name) in PEAK_NAMES.iter().enumerate() {
        let p = &doc["peaks"][name];
        assert_eq!(p["value"].as_f64(), Some(b[k]), "{name}: value is the base run's peak");
        let step_change = (h[k] - b[k]).abs() / b[k].abs();
        let mesh_change = (m4[k] - m2[k]).abs() / m4[k].abs();
        assert_eq!(p["step_change"].as_f64(), Some(step_change), "{name}");
        assert_eq!(p["mesh_change"].as_f64(), Some(mesh_change), "{name}");
        // The verdict is about the printed (base) value: against the half step and the finest mesh.
        let converged = step_change <= 0.02 && (b[k] - m4[k]).abs() / m4[k].abs() <= 0.02;
        assert_eq!(p["converged"].as_bool(), Some(converged), "{name}");
        let estimate = verify::richardson(b[k], m2[k], m4[k]).map(|r| r.estimate);
        assert_eq!(p["estimate"].as_f64(), estimate, "{name}");
    }
    assert_eq!(v.steps.as_array().map(|s| *s), [base.steps, half.steps, mesh_2x.steps, mesh_4x.steps]);
    assert_eq!(v.time_steps.half_step.free, seconds(plan.free_ns / 2));
    assert_eq!(v.time_steps.mesh_4x, mesh_4x.time_steps);
    let trusted = [&base, &half, &mesh_2x, &mesh_4x].map(|s| s.quality.trusted);
    assert_eq!(v.trusted.as_array().map(|t| *t), trusted);
}

/// Issue 29 item 2: `verify` varies the modal cut-off with the mesh, as the converged method's
/// ladder does (a refined mesh at the base cut-off keeps the same modes and cannot see the
/// truncation error), and judges the contact force F_c. A converged run on 7 + 7/7 elements cut at
/// 20 000 rad/s (below the mesh's highest frequency, 43 700 rad/s: truncated): its 2x and 4x runs
/// are cut at 40 000 and 80 000 rad/s, and every number is the one its own run gives, run
/// separately with those settings (the same deterministic runs: exact).
#[test]
fn verify_refines_the_cutoff_with_the_mesh_and_judges_the_contact_force() {
    let mut scenario = Scenario { drop_height: 1.0, duration: 0.3, modal_cutoff: 2e4, ..Scenario::default() };
    scenario.lower.elements = 7;
    scenario.upper.elements_to_contact = 7;
    scenario.upper.elements_beyond_contact = 7;
    let v = verify::verify(&scenario, DEFAULT_TOLERANCE).unwrap();
    let c = &v.modal_cutoffs;
    assert_eq!([c.base, c.half_step, c.mesh_2x, c.mesh_4x], [Some(2e4), Some(2e4), Some(4e4), Some(8e4)]);
    let mut fine = scenario.clone();
    fine.lower.elements = 28;
    fine.upper.elements_to_contact = 28;
    fine.upper.elements_beyond_contact = 28;
    fine.modal_cutoff = 8e4;
    let run = |s: &Scenario| Simulation::new(s).unwrap().run(&mut NullRecorder).unwrap();
    let (base, mesh_4x) = (run(&scenario), run(&fine));
    assert_eq!(v.run_peaks.mesh_4x, mesh_4x.peaks.as_array());
    let f = &v.peaks.contact_force;
    let (b, m4) = (base.peaks.contact_force, mesh_4x.peaks.contact_force);
    assert_eq!(f.value, b);
    assert_eq!(f.base_mesh_change, (b - m4).abs() / m4.abs());
    assert_eq!(f.converged, f.step_change <= DEFAULT_TOLERANCE && f.base_mesh_change <= DEFAULT_TOLERANCE);
    let text = verify::table(&v);
    for needle in ["contact_force [kN]", "80000", "cut-off [rad/s]", "multiply its cut-off by 2 and 4"] {
        assert!(text.contains(needle), "missing {needle:?} in\n{text}");
    }
}

fn beam_impact() -> Command {
    Command::new(env!("CARGO_BIN_EXE_beam-impact"))
}

/// `beam-impact verify --json F` on the paper scenario: the table on stdout, the documented shape
/// in F, the paper verdicts in both.
#[test]
fn cli_verify_writes_the_documented_json() {
    let dir = tempfile::tempdir().unwrap();
    let json = dir.path().join("verify.json");
    let out = beam_impact().args(["verify", "--json"]).arg(&json).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8(out.stdout).unwrap();
    for needle in ["paper scenario", "step_change", "mesh_change", "NOT converged", "wall time", "28 + 28/28"] {
        assert!(text.contains(needle), "missing {needle:?} in\n{text}");
    }
    let doc: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert_documented_shape(&doc);
    assert_eq!(doc["tolerance"].as_f64(), Some(DEFAULT_TOLERANCE));
    let converged: Vec<bool> = PEAK_NAMES.iter().map(|n| doc["peaks"][n]["converged"].as_bool().unwrap()).collect();
    assert_eq!(converged, [true, true, false, false, false]);
}

/// Bad input to `verify`: exit code 2 and one line naming what is wrong, before any run.
#[test]
fn cli_verify_bad_input_is_a_one_line_error() {
    for (args, needle) in [
        (vec!["verify", "--tolerance", "1"], "--tolerance must be > 0 and < 1"),
        (vec!["verify", "--tolerance", "0"], "--tolerance must be > 0 and < 1"),
        (vec!["verify", "/nonexistent/x.toml"], "/nonexistent/x.toml"),
    ] {
        let out = beam_impact().args(&args).output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let stderr = String::from_utf8(out.stderr).unwrap();
        assert_eq!(stderr.lines().count(), 1, "{stderr}");
        assert!(stderr.contains(needle), "{stderr}");
    }
}
