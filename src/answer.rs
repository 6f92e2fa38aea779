//! An answer an engineer can sign: the printed run, the discretisation check that vouches for each
//! of its peaks, its reproducibility twin, and the design check against the allowables.
//!
//! - **Discretisation.** A converged run is judged against two coarser rungs (the ladder's previous
//!   ones, or halves of explicit element counts): each peak's figure is its change against the next
//!   coarser rung, relative to the printed value, or, where the three rungs converge at a sane
//!   observed order ([`richardson`]), the Richardson estimate of the printed value's
//!   own error, |v - v_inf| / |v_inf|. A paper-method run is judged against the converged answer:
//!   its figure is the paper mesh's error.
//! - **Sensitivity.** A twin run with the drop height changed by 1e-9 (relative; 1e-9 m from 0):
//!   the peaks of lightly damped multi-bounce runs can be chaotic. A peak whose spread exceeds
//!   `discretisation_tolerance` is flagged.
//! - **Design.** Each stress peak's utilisation, converged peak / allowable (the paper's 533 MPa
//!   bending and 355 MPa shear by default); the design passes when every one is <= 1. The stresses
//!   exist at the arrestor's clamp (sigma_a, tau_a) and the bridge's contact node (sigma_b).
//! - **Yield.** With a yield stress given, max(sigma_a, sqrt(3) tau_a) (the extreme fibre's bending
//!   and the neutral axis's shear, each the larger of the two) and sigma_b above it put the run out
//!   of the elastic model's range: not trusted.
//!
//! `trusted` means that every check that ran passes.

use serde::{Deserialize, Serialize};

use crate::error::Result;
use crate::model::{Method, Scenario};
use crate::record::{NullRecorder, Recorder};
use crate::results::{Peaks, Summary};
use crate::Simulation;

/// The five peaks by name, in the order of [`Peaks::as_array`].
pub const PEAK_NAMES: [&str; 5] = crate::vocabulary::PEAK_FIELDS;

pub use crate::model::discretisation::LIGHT_DAMPING;

/// Relative change of the drop height in the twin run.
pub const TWIN_PERTURBATION: f64 = 1e-9;

/// One check: whether it passes, the value it measured and its limit (`None`: not checked).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Check {
    /// True when the value is within the limit.
    pub pass: bool,
    /// The measured value (a fraction for energy, discretisation and sensitivity; Pa for yield).
    pub value: f64,
    /// The limit it is held to.
    pub limit: f64,
}

impl Check {
    /// A check of `value` against `limit`: passes when finite and within it.
    pub fn new(value: f64, limit: f64) -> Check {
        Check { pass: value.is_finite() && value <= limit, value, limit }
    }
}

/// Every check of a run (`None` where it did not run).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Checks {
    /// The energy balance's largest residual against `energy_tolerance`.
    pub energy: Option<Check>,
    /// The largest discretisation figure of the whole-run and first-contact peaks against
    /// `discretisation_tolerance`.
    pub discretisation: Option<Check>,
    /// The largest spread against the twin run against `discretisation_tolerance`.
    pub sensitivity: Option<Check>,
    /// The largest stress against the given yield stress (as utilisation of it).
    #[serde(rename = "yield")]
    pub yield_stress: Option<Check>,
}

/// The design check against the allowables.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Design {
    /// True when every utilisation is <= 1.
    pub pass: bool,
    /// Converged stress peak / allowable, by peak name.
    pub utilisation: DesignUtilisation,
}

/// The utilisation of each stress peak.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct DesignUtilisation {
    /// sigma_a / lower.allowable_bending_stress.
    pub lower_clamp_bending_stress: f64,
    /// tau_a / lower.allowable_shear_stress.
    pub lower_clamp_shear_stress: f64,
    /// sigma_b / upper.allowable_bending_stress.
    pub upper_contact_bending_stress: f64,
}

impl Design {
    /// The design check of `peaks` (Pa) against the scenario's allowables.
    pub fn assess(scenario: &Scenario, peaks: &Peaks) -> Design {
        let utilisation = DesignUtilisation {
            lower_clamp_bending_stress: peaks.lower_clamp_bending_stress / scenario.lower.allowable_bending_stress,
            lower_clamp_shear_stress: peaks.lower_clamp_shear_stress / scenario.lower.allowable_shear_stress,
            upper_contact_bending_stress: peaks.upper_contact_bending_stress / scenario.upper.allowable_bending_stress,
        };
        let pass = utilisation.as_array().iter().all(|u| *u <= 1.0);
        Design { pass, utilisation }
    }
}

impl DesignUtilisation {
    /// The three utilisations in the order of [`DesignUtilisation::NAMES`].
    pub fn as_array(&self) -> [f64; 3] {
        [self.lower_clamp_bending_stress, self.lower_clamp_shear_stress, self.upper_contact_bending_stress]
    }

    /// The names of the stress peaks, as in [`Peaks`].
    pub const NAMES: [&'static str; 3] =
        ["lower_clamp_bending_stress", "lower_clamp_shear_stress", "upper_contact_bending_stress"];
}

/// One run of the answer, for the record.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RungRun {
    /// What the run is for: `printed`, `check` (the next coarser rung, or the converged answer of
    /// a paper-method run), `coarse` (the rung before), `twin`.
    pub role: String,
    /// The method.
    pub method: Method,
    /// Elements: arrestor, bridge to the contact node, bridge beyond it.
    pub elements: [u32; 3],
    /// The modal cut-off, rad/s (null: the full basis).
    pub modal_cutoff: Option<f64>,
    /// Modal coordinates kept, of the mesh's.
    pub modes: [usize; 2],
    /// Internal steps.
    pub steps: u64,
    /// Whole-run peaks.
    pub peaks: Peaks,
    /// First-contact peaks.
    pub first_contact_peaks: Peaks,
}

/// The quality of an answer: today's energy verdict keys, and every check.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct AnswerQuality {
    /// Largest |energy residual| as a fraction of the energy that flows in the printed run.
    pub energy_residual_fraction: f64,
    /// The scenario's energy tolerance.
    pub energy_tolerance: f64,
    /// True when every check that ran passes.
    pub trusted: bool,
    /// Why the run is not trusted, one line per failed check (empty when trusted).
    pub reasons: Vec<String>,
    /// Warnings that do not decide trust.
    pub advisories: Vec<String>,
    /// Each check.
    pub checks: Checks,
}

/// The printed run with its checks.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Answer {
    /// The printed run's summary (its `quality` is the energy verdict alone).
    pub summary: Summary,
    /// The scenario as run (the printed rung, `"auto"` resolved).
    pub resolved: Scenario,
    /// The converged value of each whole-run peak: the printed run's for the converged method, the
    /// converged answer's for the paper method.
    pub converged_peaks: Peaks,
    /// The converged value of each first-contact peak.
    pub converged_first_contact_peaks: Peaks,
    /// Each whole-run peak's discretisation figure (a fraction; see the module documentation).
    pub discretisation_error: Peaks,
    /// Each first-contact peak's discretisation figure.
    pub first_contact_discretisation_error: Peaks,
    /// Whole-run peaks reached after the first sustained contact of a lightly damped converged run
    /// (damping ratio below [`LIGHT_DAMPING`]): not vouched for, the rungs being all truncated.
    pub unvouched_late_peaks: Vec<String>,
    /// Each whole-run peak's spread against the twin run (a fraction); null when not checked.
    pub sensitivity_spread: Option<Peaks>,
    /// The design check of the converged peaks.
    pub design: Design,
    /// Every check and the verdict.
    pub quality: AnswerQuality,
    /// The runs behind the answer, printed first.
    pub runs: Vec<RungRun>,
}

/// What to run besides the printed run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Options {
    /// Run the reproducibility twin.
    pub sensitivity: bool,
    /// Refuse any run that needs more internal steps than this.
    pub max_steps: u64,
}

impl Default for Options {
    fn default() -> Self {
        Options { sensitivity: true, max_steps: crate::model::scenario::MAX_STEPS }
    }
}

/// Runs `scenario` into `recorder` (the printed run) and its checks (unrecorded, in parallel).
pub fn run(scenario: &Scenario, recorder: &mut (dyn Recorder + Send), options: Options) -> Result<Answer> {
    let mut printed = Simulation::new(scenario)?;
    printed.check_step_count(scenario.duration_ns(), options.max_steps)?;
    let resolved = printed.scenario().clone();
    let check_scenarios = check_scenarios(scenario)?;
    let twin = options.sensitivity.then(|| twin_scenario(scenario));
    let (printed_run, others) = rayon::join(
        || -> Result<(Summary, RungRun)> {
            let summary = printed.run(recorder)?;
            let run = rung_run("printed", &printed, &summary);
            Ok((summary, run))
        },
        || -> Result<Vec<(Summary, RungRun)>> {
            use rayon::prelude::*;
            let mut jobs: Vec<(&str, Scenario)> =
                check_scenarios.iter().cloned().zip(["check", "coarse"]).map(|(s, r)| (r, s)).collect();
            if let Some(t) = &twin {
                jobs.push(("twin", t.clone()));
            }
            jobs.par_iter()
                .map(|(role, s)| {
                    // A check rung's mesh the printed one does not share (a short element beyond
                    // the supported ratio on a coarser rung): say which run it is.
                    let mut sim = Simulation::new(s).map_err(|e| match e {
                        crate::Error::InvalidParameter { .. } | crate::Error::Invalid(_) => e,
                        e => crate::Error::Other(format!(
                            "the {role} run of the answer ({}): {e}",
                            crate::discretise::printed(s)
                                .map_or_else(|_| "?".into(), |r| crate::discretise::describe(&r))
                        )),
                    })?;
                    sim.check_step_count(s.duration_ns(), options.max_steps)?;
                    let summary = sim.run(&mut NullRecorder)?;
                    let run = rung_run(role, &sim, &summary);
                    Ok((summary, run))
                })
                .collect()
        },
    );
    let (summary, printed_rung) = printed_run?;
    let others = others?;
    Ok(assemble(&resolved, summary, printed_rung, others))
}

/// The scenarios that judge the printed run's discretisation: the next coarser rung and the one
/// before it (converged method), or the converged answer (paper method).
pub fn check_scenarios(scenario: &Scenario) -> Result<Vec<Scenario>> {
    Ok(match scenario.method {
        Method::Paper => vec![crate::discretise::check(scenario)?],
        Method::Converged => vec![crate::discretise::check(scenario)?, crate::discretise::coarse(scenario)?],
    })
}

/// The twin: the drop height changed by [`TWIN_PERTURBATION`] (relative, or absolute from 0 m).
pub fn twin_scenario(scenario: &Scenario) -> Scenario {
    let mut twin = scenario.clone();
    let h = scenario.drop_height;
    twin.drop_height = if h > 0.0 { h * (1.0 + TWIN_PERTURBATION) } else { TWIN_PERTURBATION };
    twin
}

fn rung_run(role: &str, sim: &Simulation, summary: &Summary) -> RungRun {
    let s = sim.scenario();
    let modal = sim.modal();
    RungRun {
        role: role.to_string(),
        method: s.method,
        elements: [s.lower.elements, s.upper.elements_to_contact, s.upper.elements_beyond_contact],
        modal_cutoff: modal.cutoff,
        modes: [modal.dofs(), modal.full_dofs],
        steps: summary.steps,
        peaks: summary.peaks,
        first_contact_peaks: summary.first_contact_peaks,
    }
}

/// |value - reference| / |reference| (0 when equal).
pub fn relative(value: f64, reference: f64) -> f64 {
    if value == reference {
        0.0
    } else {
        (value - reference).abs() / reference.abs()
    }
}

/// Observed orders of convergence accepted for a Richardson estimate: below 0.5 the differences
/// barely shrink (no asymptotic range yet), above 6 they shrink faster than any term of the method
/// can explain (a coincidence of three numbers, not convergence).
pub const ORDER_RANGE: (f64, f64) = (0.5, 6.0);

/// A Richardson extrapolation from three meshes, each twice as fine as the one before.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Richardson {
    /// Observed order p = log2((v_2x - v_1x) / (v_4x - v_2x)).
    pub order: f64,
    /// Estimated converged value v_4x + (v_4x - v_2x) / (2^p - 1).
    pub estimate: f64,
}

/// The Richardson estimate from the values on three meshes refined by 2 each time, or `None`
/// where they do not allow one: differences of alternating sign (oscillating or non-monotone
/// sequence), a zero difference, or an observed order outside [`ORDER_RANGE`].
pub fn richardson(coarse: f64, medium: f64, fine: f64) -> Option<Richardson> {
    let ratio = (medium - coarse) / (fine - medium);
    if !(ratio.is_finite() && ratio > 0.0) {
        return None;
    }
    // libm's log2 (pure Rust), as the physics' atan and hypot: the FMU computes this check, and
    // every platform's binary must decide it alike.
    let order = libm::log2(ratio);
    if !(ORDER_RANGE.0..=ORDER_RANGE.1).contains(&order) {
        return None;
    }
    Some(Richardson { order, estimate: fine + (fine - medium) / (ratio - 1.0) })
}

/// The discretisation figure of `fine` against `medium` (and `coarse`, when given).
pub fn discretisation_figure(fine: f64, medium: f64, coarse: Option<f64>) -> f64 {
    let change = relative(medium, fine);
    match coarse.and_then(|c| richardson(c, medium, fine)) {
        Some(r) => relative(fine, r.estimate).min(change),
        None => change,
    }
}

fn per_peak(f: impl Fn(usize) -> f64) -> Peaks {
    let v: [f64; 5] = std::array::from_fn(f);
    Peaks {
        lower_tip_deflection: v[0],
        lower_clamp_bending_stress: v[1],
        lower_clamp_shear_stress: v[2],
        upper_contact_bending_stress: v[3],
        contact_force: v[4],
    }
}

fn largest(p: &Peaks) -> (usize, f64) {
    p.as_array()
        .into_iter()
        .enumerate()
        .fold((0, 0.0), |(bi, bv), (i, v)| if v > bv || v.is_nan() { (i, v) } else { (bi, bv) })
}

fn assemble(resolved: &Scenario, summary: Summary, printed: RungRun, others: Vec<(Summary, RungRun)>) -> Answer {
    let find = |role: &str| others.iter().find(|(_, r)| r.role == role);
    let check = find("check");
    let coarse = find("coarse");
    let twin = find("twin");
    let paper = resolved.method == Method::Paper;
    let tolerance = resolved.discretisation_tolerance;
    let (converged_peaks, converged_first) = match (paper, check) {
        (true, Some((c, _))) => (c.peaks, c.first_contact_peaks),
        _ => (summary.peaks, summary.first_contact_peaks),
    };
    let figures = |get: fn(&Summary) -> Peaks| -> Peaks {
        let fine = get(&summary).as_array();
        match check {
            Some((c, _)) => {
                let medium = get(c).as_array();
                let coarse = coarse.map(|(s, _)| get(s).as_array());
                per_peak(|k| {
                    if paper {
                        relative(fine[k], medium[k])
                    } else {
                        discretisation_figure(fine[k], medium[k], coarse.map(|c| c[k]))
                    }
                })
            }
            None => per_peak(|_| f64::NAN),
        }
    };
    let discretisation_error = figures(|s| s.peaks);
    let first_contact_discretisation_error = figures(|s| s.first_contact_peaks);
    let sensitivity_spread = twin.map(|(t, _)| {
        let (a, b) = (summary.peaks.as_array(), t.peaks.as_array());
        per_peak(|k| relative(b[k], a[k]))
    });
    let design = Design::assess(resolved, &converged_peaks);

    let energy = &summary.quality;
    let mut reasons = energy.reasons.clone();
    let energy_check = Check::new(energy.energy_residual_fraction, energy.energy_tolerance);
    let (worst, worst_figure) = {
        let (i, a) = largest(&discretisation_error);
        let (j, b) = largest(&first_contact_discretisation_error);
        if b > a {
            (format!("first-contact {}", PEAK_NAMES[j]), b)
        } else {
            (PEAK_NAMES[i].to_string(), a)
        }
    };
    // Late-impact peaks of lightly damped runs: the modes above the cut-off, replaced by their
    // static response, keep ringing in the full model from one impact to the next; the rungs (all
    // truncated) cannot see it (measured: tau_a 13 % above the truncated answer at drop 0.3 m,
    // contact 13 m, damping 0.01). Such a peak is not vouched for; the first-contact ones are.
    // (A paper-method run on a graded mesh sets aside only its short elements' own modes, far
    // above anything that rings between impacts: not a truncation at a cut-off.)
    let truncated = !paper && printed.modal_cutoff.is_some() && printed.modes[0] < printed.modes[1];
    let unvouched_late_peaks: Vec<String> = if truncated && resolved.damping_ratio < LIGHT_DAMPING {
        PEAK_NAMES
            .iter()
            .zip(summary.peaks.as_array().into_iter().zip(summary.first_contact_peaks.as_array()))
            .filter(|(_, (whole, first))| whole > first)
            .map(|(n, _)| n.to_string())
            .collect()
    } else {
        Vec::new()
    };
    let mut discretisation = Check::new(worst_figure, tolerance);
    if !unvouched_late_peaks.is_empty() {
        discretisation.pass = false;
        reasons.push(format!(
            "discretisation: late-impact peaks of a lightly damped run (damping_ratio = {} < {LIGHT_DAMPING}) are not \
             vouched for by the truncated basis (its modes above the cut-off ring in the full model): {}; the \
             first-contact peaks are",
            resolved.damping_ratio,
            unvouched_late_peaks.join(", ")
        ));
    }
    if worst_figure.is_nan() || worst_figure > tolerance {
        let flagged: Vec<String> = PEAK_NAMES
            .iter()
            .zip(discretisation_error.as_array())
            .filter(|(_, e)| e.is_nan() || *e > tolerance)
            .map(|(n, e)| format!("{n} {}", percent(e)))
            .chain(
                PEAK_NAMES
                    .iter()
                    .zip(first_contact_discretisation_error.as_array())
                    .filter(|(_, e)| e.is_nan() || *e > tolerance)
                    .map(|(n, e)| format!("first-contact {n} {}", percent(e))),
            )
            .collect();
        reasons.push(if paper {
            format!(
                "the paper mesh's peaks differ from the converged answer by more than discretisation_tolerance = {}: {}",
                percent(tolerance),
                flagged.join(", ")
            )
        } else {
            format!(
                "discretisation: peaks not vouched for within discretisation_tolerance = {} (largest: {worst}): {}",
                percent(tolerance),
                flagged.join(", ")
            )
        });
    }
    let sensitivity = sensitivity_spread.map(|spread| {
        let (i, v) = largest(&spread);
        let check = Check::new(v, tolerance);
        if !check.pass {
            reasons.push(format!(
                "sensitivity: a drop height changed by 1e-9 moves {} by {} (> {}): the whole-run peaks of this run are \
                 not reproducible; the first-contact peaks are the design quantity",
                PEAK_NAMES[i],
                percent(v),
                percent(tolerance)
            ));
        }
        check
    });
    let yield_check = yield_check(resolved, &converged_peaks);
    if let Some(c) = &yield_check {
        if !c.pass {
            reasons.push(format!(
                "yield: the stresses reach {} of the yield stress: the elastic model is out of its range",
                percent(c.value)
            ));
        }
    }
    let checks = Checks {
        energy: Some(energy_check),
        discretisation: Some(discretisation),
        sensitivity,
        yield_stress: yield_check,
    };
    let trusted = [checks.energy, checks.discretisation, checks.sensitivity, checks.yield_stress]
        .iter()
        .flatten()
        .all(|c| c.pass);
    let quality = AnswerQuality {
        energy_residual_fraction: energy.energy_residual_fraction,
        energy_tolerance: energy.energy_tolerance,
        trusted,
        reasons,
        advisories: energy.advisories.clone(),
        checks,
    };
    let mut runs = vec![printed];
    runs.extend(others.into_iter().map(|(_, r)| r));
    Answer {
        summary,
        resolved: resolved.clone(),
        converged_peaks,
        converged_first_contact_peaks: converged_first,
        discretisation_error,
        first_contact_discretisation_error,
        unvouched_late_peaks,
        sensitivity_spread,
        design,
        quality,
        runs,
    }
}

/// The yield check, as the largest stress's fraction of its beam's yield stress (limit 1), when a
/// yield stress is given.
pub fn yield_check(s: &Scenario, peaks: &Peaks) -> Option<Check> {
    let mut ratios = Vec::new();
    if s.lower.yield_stress > 0.0 {
        let equivalent = peaks.lower_clamp_bending_stress.max(3f64.sqrt() * peaks.lower_clamp_shear_stress);
        ratios.push(equivalent / s.lower.yield_stress);
    }
    if s.upper.yield_stress > 0.0 {
        ratios.push(peaks.upper_contact_bending_stress / s.upper.yield_stress);
    }
    let worst = ratios.into_iter().reduce(f64::max)?;
    Some(Check::new(worst, 1.0))
}

/// A fraction as a percentage: 1 %, 0.12 %.
pub fn percent(fraction: f64) -> String {
    let p = fraction * 100.0;
    if p.is_infinite() {
        return "over 1e308 %".into();
    }
    if p.is_finite() && p != 0.0 && p.abs() < 0.01 {
        format!("{p:.1e} %")
    } else {
        format!("{:.2} %", p)
    }
}

/// The answer as the CLI prints it below Table 1: each peak's converged value, its figures, its
/// allowable and utilisation, then the design and quality verdicts.
pub fn table(answer: &Answer) -> String {
    use std::fmt::Write;
    let mut s = String::new();
    let r = &answer.resolved;
    let paper = r.method == Method::Paper;
    let describe = |run: &RungRun| {
        let cut = match run.modal_cutoff {
            Some(c) => format!("modes up to {c:.0} rad/s ({} of {} coordinates)", run.modes[0], run.modes[1]),
            None => format!("full modal basis ({} coordinates)", run.modes[1]),
        };
        format!("{} + {}/{} elements, {cut}", run.elements[0], run.elements[1], run.elements[2])
    };
    let _ = writeln!(
        s,
        "Converged answer ({}; {})",
        if paper { "method paper: the converged run beside it" } else { "method converged" },
        answer.runs.iter().map(|run| format!("{}: {}", run.role, describe(run))).collect::<Vec<_>>().join("; ")
    );
    let _ = writeln!(
        s,
        "{:36} {:>10} {:>10} {:>11} {:>11} {:>10} {:>10} {:>11}",
        "peak",
        if paper { "paper mesh" } else { "value" },
        "converged",
        if paper { "mesh error" } else { "discretis." },
        "sensitivity",
        "1st contact",
        "allowable",
        "utilisation"
    );
    let printed = answer.summary.peaks.as_array();
    let converged = answer.converged_peaks.as_array();
    let first = answer.converged_first_contact_peaks.as_array();
    let errors = answer.discretisation_error.as_array();
    let spread = answer.sensitivity_spread.map(|p| p.as_array());
    let u = answer.design.utilisation.as_array();
    let allowables = [
        None,
        Some((r.lower.allowable_bending_stress, u[0])),
        Some((r.lower.allowable_shear_stress, u[1])),
        Some((r.upper.allowable_bending_stress, u[2])),
        None,
    ];
    let labels = [
        ("w_din,a arrestor end deflection [m]", 1.0),
        ("sigma_din,a clamp bending [MPa]", 1e-6),
        ("tau_din,a clamp shear [MPa]", 1e-6),
        ("sigma_din,b bridge at contact [MPa]", 1e-6),
        ("F_c contact force [kN]", 1e-3),
    ];
    let tolerance = r.discretisation_tolerance;
    for k in 0..5 {
        let (label, scale) = labels[k];
        let late = answer.unvouched_late_peaks.iter().any(|n| n == PEAK_NAMES[k]);
        let flag = |v: f64| if v <= tolerance { " " } else { "!" };
        let _ = writeln!(
            s,
            "{label:36} {:>10.4} {:>10.4} {:>10}{} {:>10}{} {:>10.4} {:>10} {:>11}",
            printed[k] * scale,
            converged[k] * scale,
            percent(errors[k]),
            if late { "!" } else { flag(errors[k]) },
            spread.map_or("n/a".to_string(), |p| percent(p[k])),
            spread.map_or(" ", |p| flag(p[k])),
            first[k] * scale,
            allowables[k].map_or("-".to_string(), |(a, _)| format!("{:.0}", a * 1e-6)),
            allowables[k].map_or("-".to_string(), |(_, u)| format!("{u:.3}")),
        );
    }
    let (worst, worst_u) =
        DesignUtilisation::NAMES
            .iter()
            .zip(u)
            .fold(("", f64::NEG_INFINITY), |best, (n, v)| if v > best.1 { (n, v) } else { best });
    let _ = writeln!(
        s,
        "design: {} (largest utilisation {worst_u:.3}, {}; converged peaks against the allowables)",
        if answer.design.pass { "PASS" } else { "FAIL" },
        crate::vocabulary::quantity_name(worst)
    );
    let q = &answer.quality;
    let c = &q.checks;
    let figure = |c: Option<Check>| {
        c.map_or("not checked".to_string(), |c| format!("{} (limit {})", percent(c.value), percent(c.limit)))
    };
    let _ = writeln!(
        s,
        "quality: {} (energy {}, discretisation {}, sensitivity {}, yield {})",
        if q.trusted { "trusted" } else { "NOT TRUSTED" },
        figure(c.energy),
        figure(c.discretisation),
        figure(c.sensitivity),
        c.yield_stress
            .map_or("not checked (no yield stress given)".to_string(), |c| format!("{} of yield", percent(c.value))),
    );
    s
}
