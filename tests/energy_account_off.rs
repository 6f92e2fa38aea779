//! An answer's check rungs and twin keep no energy account (`Simulation::without_energy_account`:
//! only their peaks are read). Their states, peaks, first-contact peaks, contact windows, step
//! counts and stress envelopes must be those of the same run with its energies, to the bit, and
//! the energies must really be off (read 0), or the saving is not there. Held on the peaks-only
//! scope's grid (`envelope_scope::grid`: drop heights 0.1-2 m, damping 0-0.05, contact positions
//! 10-16 m, the paper method (Eqs. 7-11) on a four times finer mesh, two section examples).

use beam_impact::record::NullRecorder;
use beam_impact::results::Summary;
use beam_impact::solver::envelope::EnvelopeScope;
use beam_impact::{Scenario, Simulation};

/// The run of `scenario` as an answer's check run takes it (peaks-only envelope), with or without
/// its energy account; its summary and its final displacements and velocities.
fn run(scenario: &Scenario, energies: bool) -> (Summary, Vec<f64>) {
    let mut sim = Simulation::new(scenario).unwrap();
    sim.set_envelope_scope(EnvelopeScope::Peaks);
    if !energies {
        sim.without_energy_account();
    }
    let summary = sim.run(&mut NullRecorder).unwrap();
    let k = &sim.state().kinematics;
    (summary, k.displacement.iter().chain(k.velocity.iter()).copied().collect())
}

#[test]
fn a_run_without_its_energy_account_keeps_its_states_and_peaks_to_the_bit() {
    for (name, scenario) in super::envelope_scope::grid() {
        let (with, state_with) = run(&scenario, true);
        let (without, state_without) = run(&scenario, false);
        // Bitwise: to_bits distinguishes what == would let pass (-0.0, NaN).
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&state_with), bits(&state_without), "{name}: final state");
        assert_eq!(with.steps, without.steps, "{name}: steps");
        assert_eq!(bits(&with.peaks.as_array()), bits(&without.peaks.as_array()), "{name}: peaks");
        assert_eq!(bits(&with.peak_times.as_array()), bits(&without.peak_times.as_array()), "{name}: peak times");
        assert_eq!(
            bits(&with.first_contact_peaks.as_array()),
            bits(&without.first_contact_peaks.as_array()),
            "{name}: first-contact peaks"
        );
        assert_eq!(with.contact_windows, without.contact_windows, "{name}: contact windows");
        assert_eq!(with.envelope, without.envelope, "{name}: stress envelope");
        // The energies are off: without them each step's balance misses the beams' energy, so
        // the largest residual is of the order of the impact energy, where the account's own
        // closes to a small fraction of it (or the flag did nothing).
        assert!(
            without.max_energy_residual > 10.0 * with.max_energy_residual,
            "{name}: residual {} without the account, {} with it",
            without.max_energy_residual,
            with.max_energy_residual
        );
    }
}
