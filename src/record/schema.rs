//! The protobuf messages of the log and their self-describing schemas.
//!
//! Generated at build time from the `.proto` files in `proto/`, the one source of truth:
//! `build.rs` compiles them with protox (no system `protoc`) and prost-build, into the Rust types
//! of the [`beam_impact`] and [`foxglove`] modules here and into the serialized
//! `FileDescriptorSet`s embedded in the MCAP schema records ([`beam_impact_descriptor`],
//! [`scene_update_descriptor`], [`log_descriptor`]). So Foxglove, the Python
//! `mcap-protobuf-support` decoder and our own reader all decode the same bytes by the same
//! definition. Field numbers are part of the file format: never renumber, only append.
//!
//! Messages of the `beam_impact` package (`proto/beam_impact.proto`):
//! - [`StepMessage`] (`beam_impact.Step`, one per internal step),
//! - [`ContactEventMessage`] (`beam_impact.ContactEvent`, contact starts and ends),
//! - [`ModelMessage`] (`beam_impact.Model`, once: node positions and the nodal shape matrix),
//! - [`ModalCoordinatesMessage`] (`beam_impact.ModalCoordinates`, the deflected shapes' coordinates),
//! - [`StationStressesMessage`] (`beam_impact.StationStresses`, the stress at every station of a
//!   recorded step; the stations are [`StationGroupMessage`]s of the model message).
//!
//! Foxglove's well-known `foxglove.SceneUpdate` and `foxglove.Log` (`proto/foxglove/`, one file
//! per message as Foxglove publishes them) are described in full in the schema records; the
//! generated Rust types leave out the fields this crate never fills (see `OMITTED_FIELDS` in
//! `build.rs`), and a line's `foxglove.Point3` points are [`Vector3Message`]s (same fields).
//! `google.protobuf.Timestamp` and `Duration` are both [`TimeMessage`].

use crate::results::{ContactEvent, EnergyAccount, Peaks, StepResult};

// The generated modules: clippy's lints are prost-build's business there; rustc's stay on, so
// `missing_docs` asks for a comment on every message, field and enum value in the `.proto` files.

/// The `beam_impact` package, generated from `proto/beam_impact.proto`.
#[allow(clippy::all)]
pub mod beam_impact {
    include!(concat!(env!("OUT_DIR"), "/beam_impact.rs"));
}

/// The `foxglove` package (the messages of `foxglove.SceneUpdate` and `foxglove.Log` that this
/// crate fills), generated from `proto/foxglove/`.
#[allow(clippy::all)]
pub mod foxglove {
    include!(concat!(env!("OUT_DIR"), "/foxglove.rs"));
}

/// Schema name of the step messages.
pub const STEP_SCHEMA: &str = "beam_impact.Step";
/// Schema name of the contact events.
pub const CONTACT_SCHEMA: &str = "beam_impact.ContactEvent";
/// Schema name of the one-off model message.
pub const MODEL_SCHEMA: &str = "beam_impact.Model";
/// Schema name of the modal coordinates (log format 2: step 0, every 1 ms of simulated time,
/// contact changes, the latest peak of the arrestor's deflection in each 1 ms, the last step).
pub const MODES_SCHEMA: &str = "beam_impact.ModalCoordinates";
/// Schema name of the per-step stresses at the stress stations (issue 30).
pub const STATIONS_SCHEMA: &str = "beam_impact.StationStresses";
/// Foxglove's 3D scene schema.
pub const SCENE_SCHEMA: &str = "foxglove.SceneUpdate";
/// Foxglove's log line schema.
pub const LOG_SCHEMA: &str = "foxglove.Log";

/// One internal solver step (`beam_impact.Step`).
pub type StepMessage = beam_impact::Step;
/// The energy account of one step (`beam_impact.EnergyAccount`), J.
pub type EnergyMessage = beam_impact::EnergyAccount;
/// Running peaks max |.| since t = 0 (`beam_impact.Peaks`).
pub type PeaksMessage = beam_impact::Peaks;
/// A contact stage starts or ends (`beam_impact.ContactEvent`).
pub type ContactEventMessage = beam_impact::ContactEvent;
/// What is needed once to redraw both beams at any step (`beam_impact.Model`, at t = 0).
pub type ModelMessage = beam_impact::Model;
/// The modal coordinates of the displacement at one step (`beam_impact.ModalCoordinates`).
pub type ModalCoordinatesMessage = beam_impact::ModalCoordinates;
/// One stress's stations along one beam (`beam_impact.StationGroup`, in the model message).
pub type StationGroupMessage = beam_impact::StationGroup;
/// The stress at every station at one recorded step (`beam_impact.StationStresses`).
pub type StationStressesMessage = beam_impact::StationStresses;
/// `foxglove.Vector3` (and `foxglove.Point3`, same layout).
pub type Vector3Message = foxglove::Vector3;
/// `foxglove.Quaternion`.
pub type QuaternionMessage = foxglove::Quaternion;
/// `foxglove.Pose`.
pub type PoseMessage = foxglove::Pose;
/// `foxglove.Color`, components in 0..1.
pub type ColorMessage = foxglove::Color;
/// `foxglove.LinePrimitive` (the fields we use).
pub type LinePrimitiveMessage = foxglove::LinePrimitive;
/// `foxglove.KeyValuePair`.
pub type KeyValueMessage = foxglove::KeyValuePair;
/// `foxglove.SceneEntity` (the fields we use).
pub type SceneEntityMessage = foxglove::SceneEntity;
/// `foxglove.SceneUpdate` (entities only: nothing is ever deleted).
pub type SceneUpdateMessage = foxglove::SceneUpdate;
/// `foxglove.Log`.
pub type LogMessage = foxglove::Log;

/// `foxglove.Log.Level.INFO`.
pub const LOG_LEVEL_INFO: i32 = foxglove::log::Level::Info as i32;
/// `foxglove.Log.Level.WARNING`.
pub const LOG_LEVEL_WARNING: i32 = foxglove::log::Level::Warning as i32;

/// `google.protobuf.Timestamp` / `Duration` (same wire layout); the generated Foxglove messages
/// use it for both (see `EXTERN_TYPES` in `build.rs`).
#[derive(Clone, Copy, PartialEq, Eq, Hash, prost::Message)]
pub struct TimeMessage {
    /// Whole seconds.
    #[prost(int64, tag = "1")]
    pub seconds: i64,
    /// Nanoseconds within the second.
    #[prost(int32, tag = "2")]
    pub nanos: i32,
}

impl TimeMessage {
    /// From integer nanoseconds.
    pub fn from_ns(ns: u64) -> Self {
        TimeMessage { seconds: (ns / 1_000_000_000) as i64, nanos: (ns % 1_000_000_000) as i32 }
    }
}

impl StepMessage {
    /// Overwrites every field from `result` (log format 2: the modal coordinates stay empty).
    pub fn fill(&mut self, r: &StepResult) {
        self.step = r.step;
        self.time_ns = r.time_ns;
        self.time = r.time;
        self.step_size = r.step_size;
        self.contact = r.contact;
        self.lower_tip_deflection = r.lower_tip_deflection;
        self.upper_contact_deflection = r.upper_contact_deflection;
        self.upper_tip_deflection = r.upper_tip_deflection;
        self.lower_clamp_bending_stress = r.lower_clamp_bending_stress;
        self.lower_clamp_shear_stress = r.lower_clamp_shear_stress;
        self.upper_contact_bending_stress = r.upper_contact_bending_stress;
        self.contact_force = r.contact_force;
        self.contact_stress = r.contact_stress;
        self.lower_clamp_reaction_force = r.lower_clamp_reaction_force;
        self.lower_clamp_reaction_moment = r.lower_clamp_reaction_moment;
        self.upper_hinge_reaction_force = r.upper_hinge_reaction_force;
        self.lower_tip_velocity = r.lower_tip_velocity;
        self.upper_tip_velocity = r.upper_tip_velocity;
        self.upper_support_displacement = r.upper_support_displacement;
        self.lower_support_displacement = r.lower_support_displacement;
        self.lower_far_reaction_force = r.lower_far_reaction_force;
        self.lower_far_reaction_moment = r.lower_far_reaction_moment;
        let e = &r.energy;
        self.energy = Some(EnergyMessage {
            kinetic: e.kinetic,
            strain: e.strain,
            gravity_potential: e.gravity_potential,
            external_work: e.external_work,
            damping_dissipation: e.damping_dissipation,
            residual: e.residual,
        });
        let p = &r.peaks;
        self.peaks = Some(PeaksMessage {
            lower_tip_deflection: p.lower_tip_deflection,
            lower_clamp_bending_stress: p.lower_clamp_bending_stress,
            lower_clamp_shear_stress: p.lower_clamp_shear_stress,
            upper_contact_bending_stress: p.upper_contact_bending_stress,
            contact_force: p.contact_force,
        });
        self.modal_coordinates.clear();
    }

    /// The [`StepResult`] this message carries.
    pub fn result(&self) -> StepResult {
        let e = self.energy.unwrap_or_default();
        let p = self.peaks.unwrap_or_default();
        StepResult {
            step: self.step,
            time_ns: self.time_ns,
            time: self.time,
            step_size: self.step_size,
            contact: self.contact,
            lower_tip_deflection: self.lower_tip_deflection,
            upper_contact_deflection: self.upper_contact_deflection,
            upper_tip_deflection: self.upper_tip_deflection,
            lower_clamp_bending_stress: self.lower_clamp_bending_stress,
            lower_clamp_shear_stress: self.lower_clamp_shear_stress,
            upper_contact_bending_stress: self.upper_contact_bending_stress,
            contact_force: self.contact_force,
            contact_stress: self.contact_stress,
            lower_clamp_reaction_force: self.lower_clamp_reaction_force,
            lower_clamp_reaction_moment: self.lower_clamp_reaction_moment,
            upper_hinge_reaction_force: self.upper_hinge_reaction_force,
            lower_tip_velocity: self.lower_tip_velocity,
            upper_tip_velocity: self.upper_tip_velocity,
            upper_support_displacement: self.upper_support_displacement,
            lower_support_displacement: self.lower_support_displacement,
            // Issue 45 (fields 25, 26): 0 in older logs, which had no far support.
            lower_far_reaction_force: self.lower_far_reaction_force,
            lower_far_reaction_moment: self.lower_far_reaction_moment,
            energy: EnergyAccount {
                kinetic: e.kinetic,
                strain: e.strain,
                gravity_potential: e.gravity_potential,
                external_work: e.external_work,
                damping_dissipation: e.damping_dissipation,
                residual: e.residual,
            },
            peaks: Peaks {
                lower_tip_deflection: p.lower_tip_deflection,
                lower_clamp_bending_stress: p.lower_clamp_bending_stress,
                lower_clamp_shear_stress: p.lower_clamp_shear_stress,
                upper_contact_bending_stress: p.upper_contact_bending_stress,
                contact_force: p.contact_force,
            },
        }
    }
}

impl From<&ContactEvent> for ContactEventMessage {
    fn from(e: &ContactEvent) -> Self {
        ContactEventMessage {
            start: e.start,
            time_ns: e.time_ns,
            step: e.step,
            relative_velocity: e.relative_velocity,
            time: crate::results::seconds(e.time_ns),
        }
    }
}

impl From<&ContactEventMessage> for ContactEvent {
    fn from(m: &ContactEventMessage) -> Self {
        ContactEvent { start: m.start, time_ns: m.time_ns, step: m.step, relative_velocity: m.relative_velocity }
    }
}

// ---------------------------------------------------------------------------------------------
// Descriptors (written by build.rs from the same `.proto` files).

/// `beam_impact.proto` and its imports (none).
const BEAM_IMPACT_DESCRIPTOR: &[u8] = include_bytes!(concat!(env!("OUT_DIR"), "/beam_impact.fds.bin"));
/// `foxglove/SceneUpdate.proto` and everything it imports.
const SCENE_UPDATE_DESCRIPTOR: &[u8] = include_bytes!(concat!(env!("OUT_DIR"), "/foxglove_scene_update.fds.bin"));
/// `foxglove/Log.proto` and everything it imports.
const LOG_DESCRIPTOR: &[u8] = include_bytes!(concat!(env!("OUT_DIR"), "/foxglove_log.fds.bin"));

/// The `FileDescriptorSet` of the `beam_impact` messages (one set serves all their schemas).
pub fn beam_impact_descriptor() -> Vec<u8> {
    BEAM_IMPACT_DESCRIPTOR.to_vec()
}

/// The `FileDescriptorSet` of `foxglove.SceneUpdate` with every file it imports, as published
/// by Foxglove (field names, numbers and types).
pub fn scene_update_descriptor() -> Vec<u8> {
    SCENE_UPDATE_DESCRIPTOR.to_vec()
}

/// The `FileDescriptorSet` of `foxglove.Log` with `google/protobuf/timestamp.proto`.
pub fn log_descriptor() -> Vec<u8> {
    LOG_DESCRIPTOR.to_vec()
}

#[cfg(test)]
mod tests {
    use std::collections::{BTreeMap, HashMap};

    use prost::Message;
    use prost_types::field_descriptor_proto::{Label, Type};
    use prost_types::{DescriptorProto, FileDescriptorSet};

    use super::*;

    /// Every message of a descriptor set by its fully qualified name (`.package.Name`).
    fn messages(bytes: &[u8]) -> HashMap<String, DescriptorProto> {
        let set = FileDescriptorSet::decode(bytes).unwrap();
        let mut out = HashMap::new();
        for file in set.file {
            let package = file.package().to_string();
            for m in file.message_type {
                out.insert(format!(".{package}.{}", m.name()), m);
            }
        }
        out
    }

    fn varint(bytes: &mut &[u8]) -> u64 {
        let mut value = 0;
        for shift in (0..64).step_by(7) {
            let (&b, rest) = bytes.split_first().expect("truncated varint");
            *bytes = rest;
            value |= u64::from(b & 0x7f) << shift;
            if b < 0x80 {
                return value;
            }
        }
        panic!("varint too long")
    }

    fn take<'a>(bytes: &mut &'a [u8], n: usize) -> &'a [u8] {
        let (head, rest) = bytes.split_at(n);
        *bytes = rest;
        head
    }

    /// Decodes `bytes` as message `name` from the descriptor set alone, as a reader holding only
    /// the schema record does: every field on the wire must be declared there, with its wire
    /// type; messages are followed. Returns the raw value of each scalar field by dotted path
    /// (doubles as bits, the last element of a packed run).
    fn decode_by_schema(
        types: &HashMap<String, DescriptorProto>,
        name: &str,
        mut bytes: &[u8],
    ) -> BTreeMap<String, u64> {
        let mut out = BTreeMap::new();
        let message = types.get(name).unwrap_or_else(|| panic!("{name} is not in the set"));
        while !bytes.is_empty() {
            let key = varint(&mut bytes);
            let (number, wire) = ((key >> 3) as i32, key & 7);
            let field = message
                .field
                .iter()
                .find(|f| f.number() == number)
                .unwrap_or_else(|| panic!("{name}: field {number} is on the wire but not in the schema"));
            let scalar_wire = match field.r#type() {
                Type::Double | Type::Fixed64 | Type::Sfixed64 => 1,
                Type::Float | Type::Fixed32 | Type::Sfixed32 => 5,
                Type::String | Type::Bytes | Type::Message | Type::Group => 2,
                _ => 0,
            };
            // proto3 packs repeated scalars.
            let packed = field.label() == Label::Repeated && scalar_wire != 2;
            let expected = if packed { 2 } else { scalar_wire };
            assert_eq!(wire, expected, "{name}.{}: wire type {wire}, schema type {:?}", field.name(), field.r#type());
            let path = field.name().to_string();
            let element = |bytes: &mut &[u8], wire: u64| match wire {
                0 => varint(bytes),
                1 => u64::from_le_bytes(take(bytes, 8).try_into().unwrap()),
                5 => u64::from(u32::from_le_bytes(take(bytes, 4).try_into().unwrap())),
                _ => unreachable!(),
            };
            if wire == 2 {
                let len = varint(&mut bytes) as usize;
                let mut payload = take(&mut bytes, len);
                if field.r#type() == Type::Message {
                    for (k, v) in decode_by_schema(types, field.type_name(), payload) {
                        out.insert(format!("{path}.{k}"), v);
                    }
                } else if packed {
                    while !payload.is_empty() {
                        out.insert(path.clone(), element(&mut payload, scalar_wire));
                    }
                } else {
                    out.insert(path, payload.len() as u64);
                }
            } else {
                out.insert(path, element(&mut bytes, wire));
            }
        }
        out
    }

    fn fields(message: &DescriptorProto) -> Vec<(&str, i32, Type, Label)> {
        message.field.iter().map(|f| (f.name(), f.number(), f.r#type(), f.label())).collect()
    }

    #[test]
    fn step_and_modal_coordinates_are_described_field_by_field() {
        use Type::{Bool, Double, Float, Message as Msg, Uint64};
        let types = messages(&beam_impact_descriptor());
        let o = Label::Optional;
        let step = fields(&types[".beam_impact.Step"]);
        let names = [
            "step",
            "time_ns",
            "time",
            "step_size",
            "contact",
            "lower_tip_deflection",
            "upper_contact_deflection",
            "upper_tip_deflection",
            "lower_clamp_bending_stress",
            "lower_clamp_shear_stress",
            "upper_contact_bending_stress",
            "contact_force",
            "contact_stress",
            "energy",
            "peaks",
            "modal_coordinates",
            "lower_clamp_reaction_force",
            "lower_clamp_reaction_moment",
            "upper_hinge_reaction_force",
            "lower_tip_velocity",
            "upper_tip_velocity",
            "upper_support_displacement",
            "lower_support_displacement",
            "sample",
            "lower_far_reaction_force",
            "lower_far_reaction_moment",
        ];
        assert_eq!(step.len(), 26);
        for (k, (field, name)) in step.iter().zip(names).enumerate() {
            let number = k as i32 + 1;
            let (ty, label) = match number {
                1 | 2 => (Uint64, o),
                5 | 24 => (Bool, o),
                14 | 15 => (Msg, o),
                16 => (Float, Label::Repeated),
                _ => (Double, o),
            };
            assert_eq!(*field, (name, number, ty, label));
        }
        let step = &types[".beam_impact.Step"];
        assert_eq!(step.field[13].type_name(), ".beam_impact.EnergyAccount");
        assert_eq!(step.field[14].type_name(), ".beam_impact.Peaks");
        assert_eq!(
            fields(&types[".beam_impact.ModalCoordinates"]),
            [
                ("step", 1, Uint64, o),
                ("time_ns", 2, Uint64, o),
                ("time", 3, Double, o),
                ("coordinates", 4, Double, Label::Repeated),
                ("upper_strain_at_peak", 5, Double, o)
            ]
        );
        let names: Vec<&str> = fields(&types[".beam_impact.EnergyAccount"]).iter().map(|f| f.0).collect();
        assert_eq!(
            names,
            ["kinetic", "strain", "gravity_potential", "external_work", "damping_dissipation", "residual"]
        );
        assert_eq!(fields(&types[".beam_impact.Peaks"]).len(), 5);
        assert_eq!(fields(&types[".beam_impact.ContactEvent"]).len(), 5);
        assert_eq!(fields(&types[".beam_impact.Model"]).len(), 11);
        assert_eq!(
            fields(&types[".beam_impact.StationStresses"]),
            [
                ("step", 1, Uint64, o),
                ("time_ns", 2, Uint64, o),
                ("lower_bending", 3, Float, Label::Repeated),
                ("lower_shear", 4, Float, Label::Repeated),
                ("upper_bending", 5, Float, Label::Repeated),
                ("upper_shear", 6, Float, Label::Repeated),
                ("envelope", 7, Float, Label::Repeated),
                ("envelope_time", 8, Float, Label::Repeated)
            ]
        );
        let names: Vec<&str> = fields(&types[".beam_impact.StationGroup"]).iter().map(|f| f.0).collect();
        assert_eq!(names, ["positions", "allowable", "nodes"]);
    }

    #[test]
    fn an_encoded_step_decodes_by_its_embedded_schema() {
        // Every double field k holds k + 0.5, so a name bound to the wrong number shows.
        let step = StepMessage {
            step: 1,
            time_ns: 2,
            time: 3.5,
            step_size: 4.5,
            contact: true,
            lower_tip_deflection: 6.5,
            upper_contact_deflection: 7.5,
            upper_tip_deflection: 8.5,
            lower_clamp_bending_stress: 9.5,
            lower_clamp_shear_stress: 10.5,
            upper_contact_bending_stress: 11.5,
            contact_force: 12.5,
            contact_stress: 13.5,
            energy: Some(EnergyMessage {
                kinetic: 1.5,
                strain: 2.5,
                gravity_potential: 3.5,
                external_work: 4.5,
                damping_dissipation: 5.5,
                residual: 6.5,
            }),
            peaks: Some(PeaksMessage {
                lower_tip_deflection: 1.5,
                lower_clamp_bending_stress: 2.5,
                lower_clamp_shear_stress: 3.5,
                upper_contact_bending_stress: 4.5,
                contact_force: 5.5,
            }),
            modal_coordinates: vec![16.0, 16.5],
            lower_clamp_reaction_force: 17.5,
            lower_clamp_reaction_moment: 18.5,
            upper_hinge_reaction_force: 19.5,
            lower_tip_velocity: 20.5,
            upper_tip_velocity: 21.5,
            upper_support_displacement: 22.5,
            lower_support_displacement: 23.5,
            sample: true,
            lower_far_reaction_force: 25.5,
            lower_far_reaction_moment: 26.5,
        };
        let types = messages(&beam_impact_descriptor());
        let decoded = decode_by_schema(&types, ".beam_impact.Step", &step.encode_to_vec());
        for (prefix, name) in
            [("", ".beam_impact.Step"), ("energy.", ".beam_impact.EnergyAccount"), ("peaks.", ".beam_impact.Peaks")]
        {
            for f in types[name].field.iter().filter(|f| f.r#type() == Type::Double) {
                let value = decoded.get(&format!("{prefix}{}", f.name())).map(|&bits| f64::from_bits(bits));
                assert_eq!(value, Some(f.number() as f64 + 0.5), "{prefix}{}", f.name());
            }
        }
        assert_eq!(decoded["step"], 1);
        assert_eq!(decoded["time_ns"], 2);
        assert_eq!(decoded["contact"], 1);
        assert_eq!(decoded["sample"], 1);
        assert_eq!(f32::from_bits(decoded["modal_coordinates"] as u32), 16.5);
        assert_eq!(decoded.len(), 26 - 2 + 6 + 5, "{decoded:?}");

        let stations = StationStressesMessage {
            step: 9,
            time_ns: 10,
            lower_bending: vec![1.5, -2.5],
            upper_shear: vec![0.25],
            ..Default::default()
        };
        let decoded = decode_by_schema(&types, ".beam_impact.StationStresses", &stations.encode_to_vec());
        assert_eq!((decoded["step"], decoded["time_ns"]), (9, 10));
        assert_eq!(f32::from_bits(decoded["lower_bending"] as u32), -2.5);
        assert_eq!(f32::from_bits(decoded["upper_shear"] as u32), 0.25);

        let modes = ModalCoordinatesMessage {
            step: 7,
            time_ns: 8,
            time: 3.5,
            coordinates: vec![1.0, 4.5],
            upper_strain_at_peak: Some(510.5),
        };
        let decoded = decode_by_schema(&types, ".beam_impact.ModalCoordinates", &modes.encode_to_vec());
        assert_eq!(decoded["step"], 7);
        assert_eq!(decoded["time_ns"], 8);
        assert_eq!(f64::from_bits(decoded["time"]), 3.5);
        assert_eq!(f64::from_bits(decoded["coordinates"]), 4.5);
        assert_eq!(f64::from_bits(decoded["upper_strain_at_peak"]), 510.5);
    }

    #[test]
    fn scene_and_log_messages_decode_by_foxglove_schemas() {
        let types = messages(&scene_update_descriptor());
        // The schema record carries Foxglove's whole SceneEntity, though the Rust type is a subset.
        let entity: Vec<(&str, i32)> =
            types[".foxglove.SceneEntity"].field.iter().map(|f| (f.name(), f.number())).collect();
        assert_eq!(entity.len(), 14);
        assert_eq!(entity[10], ("lines", 11));
        assert_eq!(entity[13], ("models", 14));
        assert_eq!(types[".foxglove.LinePrimitive"].field.len(), 8);
        assert_eq!(types[".foxglove.LinePrimitive"].field[4].type_name(), ".foxglove.Point3");
        let line = LinePrimitiveMessage {
            r#type: foxglove::line_primitive::Type::LineList as i32,
            pose: Some(PoseMessage {
                position: Some(Vector3Message { x: 1.0, y: 2.0, z: 3.0 }),
                orientation: Some(QuaternionMessage { x: 0.5, y: 0.5, z: 0.5, w: 0.5 }),
            }),
            thickness: 0.25,
            scale_invariant: true,
            points: vec![Vector3Message { x: 1.0, y: 2.0, z: 3.0 }, Vector3Message { x: 4.0, y: 5.0, z: 6.0 }],
            color: Some(ColorMessage { r: 1.0, g: 0.5, b: 0.25, a: 1.0 }),
            colors: vec![ColorMessage { r: 0.125, g: 0.5, b: 0.25, a: 1.0 }; 2],
        };
        let update = SceneUpdateMessage {
            entities: vec![SceneEntityMessage {
                timestamp: Some(TimeMessage::from_ns(1_500_000_000)),
                frame_id: "world".into(),
                id: "bridge".into(),
                lifetime: Some(TimeMessage { seconds: 2, nanos: 0 }),
                frame_locked: true,
                metadata: vec![KeyValueMessage { key: "k".into(), value: "v".into() }],
                lines: vec![line],
            }],
        };
        let decoded = decode_by_schema(&types, ".foxglove.SceneUpdate", &update.encode_to_vec());
        assert_eq!(decoded["entities.timestamp.seconds"], 1);
        assert_eq!(decoded["entities.timestamp.nanos"], 500_000_000);
        assert_eq!(decoded["entities.lifetime.seconds"], 2);
        assert_eq!(decoded["entities.lines.type"], 2);
        assert_eq!(f64::from_bits(decoded["entities.lines.points.z"]), 6.0);
        assert_eq!(f64::from_bits(decoded["entities.lines.pose.orientation.w"]), 0.5);
        assert_eq!(f64::from_bits(decoded["entities.lines.color.b"]), 0.25);
        // Per-point colours (the utilisation of each element, issue 30).
        assert_eq!(f64::from_bits(decoded["entities.lines.colors.r"]), 0.125);
        assert_eq!(decoded["entities.metadata.value"], 1);

        let types = messages(&log_descriptor());
        let log = LogMessage {
            timestamp: Some(TimeMessage::from_ns(3)),
            level: LOG_LEVEL_WARNING,
            message: "m".into(),
            name: "beam-impact".into(),
            file: "f".into(),
            line: 42,
        };
        let decoded = decode_by_schema(&types, ".foxglove.Log", &log.encode_to_vec());
        assert_eq!(decoded["timestamp.nanos"], 3);
        assert_eq!(decoded["level"], 3);
        assert_eq!(decoded["line"], 42);
        assert_eq!(decoded["name"], "beam-impact".len() as u64);
        assert_eq!((LOG_LEVEL_INFO, LOG_LEVEL_WARNING), (2, 3));
    }

    #[test]
    fn descriptor_sets_are_self_contained_and_carry_no_comments() {
        let beam = FileDescriptorSet::decode(beam_impact_descriptor().as_slice()).unwrap();
        assert_eq!(beam.file.len(), 1);
        assert_eq!((beam.file[0].name(), beam.file[0].package()), ("beam_impact.proto", "beam_impact"));
        for bytes in [beam_impact_descriptor(), scene_update_descriptor(), log_descriptor()] {
            let set = FileDescriptorSet::decode(bytes.as_slice()).unwrap();
            let mut seen: Vec<&str> = Vec::new();
            let mut declared = Vec::new();
            for file in &set.file {
                assert_eq!(file.syntax(), "proto3", "{}", file.name());
                assert!(file.source_code_info.is_none(), "{} carries its comments", file.name());
                for dependency in &file.dependency {
                    assert!(seen.contains(&dependency.as_str()), "{} before its import {dependency}", file.name());
                }
                seen.push(file.name());
                for m in &file.message_type {
                    declared.push(format!(".{}.{}", file.package(), m.name()));
                    declared
                        .extend(m.enum_type.iter().map(|e| format!(".{}.{}.{}", file.package(), m.name(), e.name())));
                }
            }
            let types = messages(&bytes);
            for (name, m) in &types {
                for f in m.field.iter().filter(|f| f.type_name.is_some()) {
                    assert!(declared.contains(&f.type_name().to_string()), "{name}.{}: {}", f.name(), f.type_name());
                }
            }
        }
    }
}
