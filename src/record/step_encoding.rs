//! The protobuf bytes of a `beam_impact.Step` message (log format 2), written directly.
//!
//! This is the recorder's hottest path: one message per internal step. prost's generic encoder
//! walks the message three times (its length, the nested messages' lengths, the bytes), about
//! 800 instructions a step; this writes the same bytes in one pass. It is not a second schema:
//! the field numbers and types are those of `proto/beam_impact.proto`, and the tests require the
//! bytes to equal prost's encoding of [`StepMessage`](super::schema::StepMessage) (the generated code) for real and edge-case
//! steps, so a schema change that this file does not follow fails there.
//!
//! proto3 rules followed: a scalar equal to its default (0, 0.0, -0.0, false) is left out; a
//! present nested message is written even when empty; fields in field-number order, as prost.

use crate::results::StepResult;

/// Wire types.
const VARINT: u8 = 0;
const FIXED64: u8 = 1;
const LENGTH_DELIMITED: u8 = 2;

/// The largest message: two 10-byte varints and their keys (22), `step_size` (9), `contact` (2),
/// 8 doubles (72), the energy account (2 + 54) and the peaks (2 + 45), 9 doubles with two-byte
/// keys (90: fields 17 to 23, 25 and 26), `sample` (3): 301 bytes.
const MAX_BYTES: usize = 301;

/// The message built in a fixed array (one pass, no capacity checks), then appended at once.
struct Bytes {
    bytes: [u8; MAX_BYTES],
    len: usize,
}

impl Bytes {
    fn push(&mut self, byte: u8) {
        self.bytes[self.len] = byte;
        self.len += 1;
    }

    fn varint(&mut self, mut value: u64) {
        while value >= 0x80 {
            self.push((value as u8) | 0x80);
            value >>= 7;
        }
        self.push(value as u8);
    }

    /// The key of `field` (below 2048: one or two bytes).
    fn key(&mut self, field: u8, wire_type: u8) {
        self.varint(u64::from(field) << 3 | u64::from(wire_type));
    }

    fn double(&mut self, field: u8, value: f64) {
        // prost's proto3 test for a default double: `value != 0.0` (so -0.0 is left out, NaN kept).
        if value != 0.0 {
            self.key(field, FIXED64);
            self.bytes[self.len..self.len + 8].copy_from_slice(&value.to_le_bytes());
            self.len += 8;
        }
    }

    fn uint64(&mut self, field: u8, value: u64) {
        if value != 0 {
            self.key(field, VARINT);
            self.varint(value);
        }
    }

    /// Nested message `field` of at most six doubles (54 bytes: its length is one byte).
    fn nested(&mut self, field: u8, doubles: &[f64]) {
        debug_assert!(doubles.len() <= 6);
        self.key(field, LENGTH_DELIMITED);
        let at = self.len;
        self.push(0);
        for (k, &value) in doubles.iter().enumerate() {
            self.double(k as u8 + 1, value);
        }
        self.bytes[at] = (self.len - at - 1) as u8;
    }
}

/// Appends the `beam_impact.Step` message of `r` to the cleared `buffer` as log format 2 writes
/// it: `time` (field 3) left out, `modal_coordinates` (16) empty, and `peaks` (15) only if
/// `with_peaks`.
/// `sample` marks a sample of the dense output (field 24).
pub fn encode_step(buffer: &mut Vec<u8>, r: &StepResult, with_peaks: bool, sample: bool) {
    let mut b = Bytes { bytes: [0; MAX_BYTES], len: 0 };
    b.uint64(1, r.step);
    b.uint64(2, r.time_ns);
    b.double(4, r.step_size);
    if r.contact {
        b.key(5, VARINT);
        b.push(1);
    }
    b.double(6, r.lower_tip_deflection);
    b.double(7, r.upper_contact_deflection);
    b.double(8, r.upper_tip_deflection);
    b.double(9, r.lower_clamp_bending_stress);
    b.double(10, r.lower_clamp_shear_stress);
    b.double(11, r.upper_contact_bending_stress);
    b.double(12, r.contact_force);
    b.double(13, r.contact_stress);
    let e = &r.energy;
    b.nested(14, &[e.kinetic, e.strain, e.gravity_potential, e.external_work, e.damping_dissipation, e.residual]);
    if with_peaks {
        let p = &r.peaks;
        b.nested(
            15,
            &[
                p.lower_tip_deflection,
                p.lower_clamp_bending_stress,
                p.lower_clamp_shear_stress,
                p.upper_contact_bending_stress,
                p.contact_force,
            ],
        );
    }
    b.double(17, r.lower_clamp_reaction_force);
    b.double(18, r.lower_clamp_reaction_moment);
    b.double(19, r.upper_hinge_reaction_force);
    b.double(20, r.lower_tip_velocity);
    b.double(21, r.upper_tip_velocity);
    b.double(22, r.upper_support_displacement);
    b.double(23, r.lower_support_displacement);
    if sample {
        b.key(24, VARINT);
        b.push(1);
    }
    b.double(25, r.lower_far_reaction_force);
    b.double(26, r.lower_far_reaction_moment);
    buffer.clear();
    buffer.extend_from_slice(&b.bytes[..b.len]);
}

#[cfg(test)]
mod tests {
    use prost::Message;

    use super::*;
    use crate::record::schema::StepMessage;
    use crate::results::{EnergyAccount, Peaks};

    /// prost's bytes of the same message: the generated code from proto/ is the oracle.
    fn prost_bytes(r: &StepResult, with_peaks: bool, sample: bool) -> Vec<u8> {
        let mut message = StepMessage::default();
        message.fill(r);
        message.sample = sample;
        message.time = 0.0;
        if !with_peaks {
            message.peaks = None;
        }
        message.encode_to_vec()
    }

    fn assert_same(r: &StepResult) {
        for (with_peaks, sample) in [(true, false), (false, false), (true, true), (false, true)] {
            let mut ours = Vec::new();
            encode_step(&mut ours, r, with_peaks, sample);
            assert_eq!(ours, prost_bytes(r, with_peaks, sample), "{r:?} (peaks: {with_peaks}, sample: {sample})");
            // And it decodes to the same result (time and peaks aside).
            let decoded = StepMessage::decode(ours.as_slice()).unwrap().result();
            assert_eq!(decoded.step, r.step);
            assert_eq!(decoded.lower_tip_velocity.to_bits(), (r.lower_tip_velocity + 0.0).to_bits());
        }
    }

    #[test]
    fn the_bytes_equal_prosts_for_real_steps() {
        let scenario = crate::Scenario { duration: 0.05, ..crate::Scenario::paper() };
        let mut memory = crate::record::MemoryRecorder::default();
        crate::Simulation::new(&scenario).unwrap().run(&mut memory).unwrap();
        assert!(memory.steps.len() > 1000);
        memory.steps.iter().for_each(assert_same);
    }

    #[test]
    fn the_bytes_equal_prosts_for_edge_values() {
        let all = |v: f64, step: u64| StepResult {
            step,
            time_ns: step.wrapping_mul(25_000),
            time: 0.0,
            step_size: v,
            contact: step % 2 == 1,
            lower_tip_deflection: v,
            upper_contact_deflection: -v,
            upper_tip_deflection: v,
            lower_clamp_bending_stress: v,
            lower_clamp_shear_stress: v,
            upper_contact_bending_stress: v,
            contact_force: v,
            contact_stress: v,
            lower_clamp_reaction_force: v,
            lower_clamp_reaction_moment: v,
            upper_hinge_reaction_force: v,
            lower_tip_velocity: v,
            upper_tip_velocity: v,
            upper_support_displacement: v,
            lower_support_displacement: -v,
            lower_far_reaction_force: v,
            lower_far_reaction_moment: -v,
            energy: EnergyAccount {
                kinetic: v,
                strain: v,
                gravity_potential: v,
                external_work: v,
                damping_dissipation: v,
                residual: v,
            },
            peaks: Peaks {
                lower_tip_deflection: v,
                lower_clamp_bending_stress: v,
                lower_clamp_shear_stress: v,
                upper_contact_bending_stress: v,
                contact_force: v,
            },
        };
        let values = [0.0, -0.0, 1.0, -1.5e300, f64::MIN_POSITIVE, 5e-324, f64::INFINITY, f64::NEG_INFINITY, f64::NAN];
        for (k, &v) in values.iter().enumerate() {
            for step in [0, 1, 127, 128, 16_383, 16_384, u64::MAX, k as u64] {
                assert_same(&all(v, step));
            }
        }
    }
}
