fn main() {
    let mut s = beam_impact::Scenario::default();
    let args: Vec<String> = std::env::args().collect();
    if args.len() > 1 {
        s.damping_ratio = args[1].parse().unwrap();
    }
    let mut sim = beam_impact::Simulation::new(&s).unwrap();
    let mut rec = beam_impact::record::MemoryRecorder::default();
    let sum = sim.run(&mut rec).unwrap();
    for r in rec.steps.iter().filter(|r| r.time_ns % 20_000_000 == 0) {
        println!(
            "{:.3} yl={:.4} yu={:.4} c={} sa={:.0} tau={:.1} sb={:.0} F={:.0} res={:.1} ub={:.0}",
            r.time,
            r.lower_tip_deflection,
            r.upper_contact_deflection,
            r.contact as u8,
            r.lower_clamp_bending_stress / 1e6,
            r.lower_clamp_shear_stress / 1e6,
            r.upper_contact_bending_stress / 1e6,
            r.contact_force / 1e3,
            r.energy.residual,
            r.upper_tip_deflection
        );
    }
    println!("{:?} {:?} {}", sum.peaks, sum.peak_times, sum.upper_strain_at_peak_deflection);
}
