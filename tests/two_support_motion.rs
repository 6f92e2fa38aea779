//! `[motion]` and `[sea]` on a beam on two supports (issue 45, item 3). On a vessel both supports
//! of a deck beam move with the deck, heave h plus rotation theta times x along the beam, a rigid
//! field every support condition follows; the model's moving-base loads -M r a describe it (these
//! tests: a steady heave acceleration a gives the static deflection of the inertial load m' a,
//! 5 q L^4 / 384 EI at midspan of a pinned-pinned beam, and a steady angular acceleration alpha the
//! triangular load's 5 q_0 L^4 / 768 EI, q_0 = m' alpha L). The run still refuses the motion: the
//! far support's reaction would miss that motion's inertia (its rows see no support
//! acceleration). The refusal says so and what to do: fold a steady heave acceleration into
//! gravity, which loads the beam exactly as the moving deck does (also shown here).

use beam_impact::model::supports::Supports;
use beam_impact::model::Model;
use beam_impact::Scenario;
use nalgebra::DVector;

/// The paper's arrestor section on `supports`, uniform, no lumped mass, 20 elements.
fn deck_beam(supports: Supports) -> Scenario {
    let mut s = Scenario::paper_mesh();
    s.lower.supports = supports;
    s.lower.tip_mass = 0.0;
    s.lower.elements = 20;
    s
}

/// The struck beam's static deflection under `load` (its DOFs' part of a global load vector).
fn static_deflection(model: &Model, load: &DVector<f64>) -> DVector<f64> {
    let lower = load.rows(0, model.lower.dofs()).into_owned();
    model.lower.stiffness.clone().cholesky().unwrap().solve(&lower)
}

/// The midspan node's deflection of `u`.
fn midspan(model: &Model, u: &DVector<f64>) -> f64 {
    let nodes = &model.lower.mesh.nodes;
    let length = nodes.last().unwrap().x;
    let node = nodes.iter().position(|n| (n.x - 0.5 * length).abs() < 1e-9).expect("a node at midspan");
    u[nodes[node].w.unwrap()]
}

/// Both pins heaving with a steady upward acceleration a: the moving-base load a x_heave
/// (x_heave = -M r, r = 1 along the beam, pins included) bends the beam as the static inertial load
/// q = m' a down, 5 q L^4 / 384 EI at midspan; rotating about the first pin with a steady angular
/// acceleration alpha (the far pin rising alpha L per unit time squared): the triangular load
/// q(x) = m' alpha x, whose midspan deflection is half the uniform q_0 = m' alpha L's,
/// 5 q_0 L^4 / 768 EI. The Hermite element's consistent loads are exact at the nodes for uniform
/// and linear loads, so round-off only: 1e-9.
#[test]
fn both_supports_moving_rigidly_bend_a_pinned_beam_as_its_inertial_load() {
    let s = deck_beam(Supports::PinnedPinned);
    let model = Model::new(&s).unwrap();
    let (length, ei) = (s.lower.length, s.lower.elastic_modulus * s.lower.second_moment);
    let per_length = s.lower.mass / length;
    let [_, heave, rotation] = model.support_loads();
    let a = 2.5;
    let w = midspan(&model, &static_deflection(&model, &(heave * a)));
    let closed = -5.0 * per_length * a * length.powi(4) / (384.0 * ei);
    assert!((w / closed - 1.0).abs() < 1e-9, "heave: {w} vs 5 q L^4 / 384 EI = {closed}");
    let alpha = 0.3;
    let w = midspan(&model, &static_deflection(&model, &(rotation * alpha)));
    let closed = -5.0 * per_length * alpha * length * length.powi(4) / (768.0 * ei);
    assert!((w / closed - 1.0).abs() < 1e-9, "rotation: {w} vs 5 q0 L^4 / 768 EI = {closed}");
}

/// The refusal's workaround is exact: the beam's gravity load at g is g times the heave's unit
/// inertia load, so a steady deck heave acceleration a stated as gravity = g + a loads the beam
/// as the moving deck does, on every support condition (to round-off, 1e-12).
#[test]
fn a_steady_heave_folded_into_gravity_is_the_moving_decks_load() {
    for supports in [Supports::PinnedPinned, Supports::ClampedClamped, Supports::ClampedPinned] {
        let mut s = deck_beam(supports);
        s.gravity = 9.81 + 2.5;
        let model = Model::new(&s).unwrap();
        let heave = &model.support_loads()[1];
        let gravity = &model.lower.gravity_load;
        let n = model.lower.dofs();
        let scale = gravity.amax();
        for i in 0..n {
            assert!((gravity[i] - s.gravity * heave[i]).abs() <= 1e-12 * scale, "{supports:?} DOF {i}");
        }
    }
}

/// `[motion]` or `[sea]` with two supports: refused in one line naming the supports, why (the far
/// support's reaction) and what to do (gravity = 9.81 + a, or clamped-free).
#[test]
fn motion_on_two_supports_is_refused_saying_why_and_what_to_do() {
    let text = "[lower]\nsupports = \"pinned-pinned\"\n\n[motion]\ntime_shift = 1.0\n";
    let e = match Scenario::from_toml(text, "deck.toml").and_then(|s| s.validate().map(|_| s)) {
        Ok(_) => panic!("a deck beam with [motion] runs"),
        Err(e) => e.to_string(),
    };
    assert!(!e.contains('\n'), "{e}");
    for part in ["lower.supports = \"pinned-pinned\" with [motion]", "far support's reaction", "gravity = 9.81 + a"] {
        assert!(e.contains(part), "{part:?} in {e}");
    }
}
