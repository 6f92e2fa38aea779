//! The protobuf messages of the log and their self-describing schemas.
//!
//! The structs below are encoded with prost; the `FileDescriptorSet`s that describe them are
//! built here in code (no `protoc`, no build script) and embedded in the MCAP schema records,
//! so Foxglove, the Python `mcap-protobuf-support` decoder and our own reader all decode the
//! same bytes. Field numbers are part of the file format: never renumber, only append.
//!
//! Messages of the `beam_impact` package:
//! - [`StepMessage`] (`beam_impact.Step`, one per internal step),
//! - [`ContactEventMessage`] (`beam_impact.ContactEvent`, contact starts and ends),
//! - [`ModelMessage`] (`beam_impact.Model`, once: node positions and the nodal shape matrix).
//!
//! Foxglove's well-known `foxglove.SceneUpdate` and `foxglove.Log` are described in full (every
//! field of the published schemas), though only the fields we fill have prost structs here.

use prost::Message;
use prost_types::field_descriptor_proto::{Label, Type};
use prost_types::{
    DescriptorProto, EnumDescriptorProto, EnumValueDescriptorProto, FieldDescriptorProto, FileDescriptorProto,
    FileDescriptorSet,
};

use crate::results::{ContactEvent, EnergyAccount, Peaks, StepResult};

/// Schema name of the step messages.
pub const STEP_SCHEMA: &str = "beam_impact.Step";
/// Schema name of the contact events.
pub const CONTACT_SCHEMA: &str = "beam_impact.ContactEvent";
/// Schema name of the one-off model message.
pub const MODEL_SCHEMA: &str = "beam_impact.Model";
/// Foxglove's 3D scene schema.
pub const SCENE_SCHEMA: &str = "foxglove.SceneUpdate";
/// Foxglove's log line schema.
pub const LOG_SCHEMA: &str = "foxglove.Log";

/// The energy account of one step (`beam_impact.EnergyAccount`), J.
#[derive(Clone, Copy, PartialEq, Message)]
pub struct EnergyMessage {
    /// Kinetic energy of both beams.
    #[prost(double, tag = "1")]
    pub kinetic: f64,
    /// Strain energy of both beams and of the bar while in contact.
    #[prost(double, tag = "2")]
    pub strain: f64,
    /// Gravity potential from the undeformed position.
    #[prost(double, tag = "3")]
    pub gravity_potential: f64,
    /// Work of the external tip forces since t = 0.
    #[prost(double, tag = "4")]
    pub external_work: f64,
    /// Energy dissipated by damping since t = 0.
    #[prost(double, tag = "5")]
    pub damping_dissipation: f64,
    /// Balance residual.
    #[prost(double, tag = "6")]
    pub residual: f64,
}

/// Running peaks max |.| since t = 0 (`beam_impact.Peaks`).
#[derive(Clone, Copy, PartialEq, Message)]
pub struct PeaksMessage {
    /// Arrestor end deflection, m.
    #[prost(double, tag = "1")]
    pub lower_tip_deflection: f64,
    /// Bending stress at the clamp, Pa.
    #[prost(double, tag = "2")]
    pub lower_clamp_bending_stress: f64,
    /// Shear stress at the clamp, Pa.
    #[prost(double, tag = "3")]
    pub lower_clamp_shear_stress: f64,
    /// Bending stress at the bridge's contact node, Pa.
    #[prost(double, tag = "4")]
    pub upper_contact_bending_stress: f64,
    /// Contact bar force, N.
    #[prost(double, tag = "5")]
    pub contact_force: f64,
}

/// One internal solver step (`beam_impact.Step`): every field of [`StepResult`] and the modal
/// coordinates (nodal deflections = `ModelMessage::nodal_shapes` * `modal_coordinates`).
#[derive(Clone, PartialEq, Message)]
pub struct StepMessage {
    /// Steps since t = 0 (0 is the initial state).
    #[prost(uint64, tag = "1")]
    pub step: u64,
    /// Simulated time, ns (also the message's log and publish time).
    #[prost(uint64, tag = "2")]
    pub time_ns: u64,
    /// Simulated time, s.
    #[prost(double, tag = "3")]
    pub time: f64,
    /// Size of the step that ended here, s.
    #[prost(double, tag = "4")]
    pub step_size: f64,
    /// Contact stage of the step: true when taken in contact (Eq. 6 at its start).
    #[prost(bool, tag = "5")]
    pub contact: bool,
    /// Deflection of the arrestor's end (node 8), m.
    #[prost(double, tag = "6")]
    pub lower_tip_deflection: f64,
    /// Deflection of the bridge's contact node (node 16), m.
    #[prost(double, tag = "7")]
    pub upper_contact_deflection: f64,
    /// Deflection of the bridge's free end, m.
    #[prost(double, tag = "8")]
    pub upper_tip_deflection: f64,
    /// Bending stress at the clamp (node 1), Pa.
    #[prost(double, tag = "9")]
    pub lower_clamp_bending_stress: f64,
    /// Shear stress at the clamp, Pa.
    #[prost(double, tag = "10")]
    pub lower_clamp_shear_stress: f64,
    /// Bending stress at the bridge's contact node, Pa.
    #[prost(double, tag = "11")]
    pub upper_contact_bending_stress: f64,
    /// Contact bar force, N (negative in compression).
    #[prost(double, tag = "12")]
    pub contact_force: f64,
    /// Contact bar stress, Pa.
    #[prost(double, tag = "13")]
    pub contact_stress: f64,
    /// Energy account.
    #[prost(message, optional, tag = "14")]
    pub energy: Option<EnergyMessage>,
    /// Running peaks.
    #[prost(message, optional, tag = "15")]
    pub peaks: Option<PeaksMessage>,
    /// Modal coordinates of the displacement, single precision (7 significant digits: enough
    /// to redraw the deflected shapes, at half the bytes of the largest part of the message).
    #[prost(float, repeated, tag = "16")]
    pub modal_coordinates: Vec<f32>,
    /// Vertical force of the clamp on the arrestor, N, up positive.
    #[prost(double, tag = "17")]
    pub lower_clamp_reaction_force: f64,
    /// Moment of the clamp on the arrestor, N m, counter-clockwise positive.
    #[prost(double, tag = "18")]
    pub lower_clamp_reaction_moment: f64,
    /// Vertical force of the hinge on the bridge, N, up positive.
    #[prost(double, tag = "19")]
    pub upper_hinge_reaction_force: f64,
    /// Vertical velocity of the arrestor's end, m/s.
    #[prost(double, tag = "20")]
    pub lower_tip_velocity: f64,
    /// Vertical velocity of the bridge's free end, m/s.
    #[prost(double, tag = "21")]
    pub upper_tip_velocity: f64,
}

impl StepMessage {
    /// Overwrites every field from `result` and `coordinates`, reusing the coordinate buffer.
    pub fn fill(&mut self, r: &StepResult, coordinates: &[f64]) {
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
        self.modal_coordinates.extend(coordinates.iter().map(|&q| q as f32));
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

/// A contact stage starts or ends (`beam_impact.ContactEvent`).
#[derive(Clone, Copy, PartialEq, Message)]
pub struct ContactEventMessage {
    /// True when contact starts, false when the beams separate.
    #[prost(bool, tag = "1")]
    pub start: bool,
    /// Time at which Eq. (6) changed, ns.
    #[prost(uint64, tag = "2")]
    pub time_ns: u64,
    /// Index of the first step in the new stage.
    #[prost(uint64, tag = "3")]
    pub step: u64,
    /// Relative velocity of the contact points, m/s (negative approaching).
    #[prost(double, tag = "4")]
    pub relative_velocity: f64,
    /// Time at which Eq. (6) changed, s.
    #[prost(double, tag = "5")]
    pub time: f64,
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

/// What is needed once to redraw both beams at any step (`beam_impact.Model`, at t = 0).
#[derive(Clone, PartialEq, Message)]
pub struct ModelMessage {
    /// The scenario, as TOML.
    #[prost(string, tag = "1")]
    pub scenario_toml: String,
    /// Arrestor node positions from the clamp, m.
    #[prost(double, repeated, tag = "2")]
    pub lower_nodes: Vec<f64>,
    /// Bridge node positions from the hinge, m.
    #[prost(double, repeated, tag = "3")]
    pub upper_nodes: Vec<f64>,
    /// Rows of the nodal shape matrix (arrestor nodes then bridge nodes).
    #[prost(uint32, tag = "4")]
    pub shape_rows: u32,
    /// Columns of the nodal shape matrix (modal coordinates).
    #[prost(uint32, tag = "5")]
    pub shape_cols: u32,
    /// The nodal shape matrix, row-major: w = shapes * q, m.
    #[prost(double, repeated, tag = "6")]
    pub nodal_shapes: Vec<f64>,
}

/// `google.protobuf.Timestamp` / `Duration` (same wire layout).
#[derive(Clone, Copy, PartialEq, Message)]
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

/// `foxglove.Vector3` (and `Point3`, same layout).
#[derive(Clone, Copy, PartialEq, Message)]
pub struct Vector3Message {
    /// x.
    #[prost(double, tag = "1")]
    pub x: f64,
    /// y.
    #[prost(double, tag = "2")]
    pub y: f64,
    /// z.
    #[prost(double, tag = "3")]
    pub z: f64,
}

/// `foxglove.Quaternion`.
#[derive(Clone, Copy, PartialEq, Message)]
pub struct QuaternionMessage {
    /// x.
    #[prost(double, tag = "1")]
    pub x: f64,
    /// y.
    #[prost(double, tag = "2")]
    pub y: f64,
    /// z.
    #[prost(double, tag = "3")]
    pub z: f64,
    /// w.
    #[prost(double, tag = "4")]
    pub w: f64,
}

/// `foxglove.Pose`.
#[derive(Clone, Copy, PartialEq, Message)]
pub struct PoseMessage {
    /// Position.
    #[prost(message, optional, tag = "1")]
    pub position: Option<Vector3Message>,
    /// Orientation.
    #[prost(message, optional, tag = "2")]
    pub orientation: Option<QuaternionMessage>,
}

/// `foxglove.Color`, components in 0..1.
#[derive(Clone, Copy, PartialEq, Message)]
pub struct ColorMessage {
    /// Red.
    #[prost(double, tag = "1")]
    pub r: f64,
    /// Green.
    #[prost(double, tag = "2")]
    pub g: f64,
    /// Blue.
    #[prost(double, tag = "3")]
    pub b: f64,
    /// Alpha.
    #[prost(double, tag = "4")]
    pub a: f64,
}

/// `foxglove.LinePrimitive` (the fields we use).
#[derive(Clone, PartialEq, Message)]
pub struct LinePrimitiveMessage {
    /// 0 = LINE_STRIP.
    #[prost(int32, tag = "1")]
    pub r#type: i32,
    /// Origin of the points.
    #[prost(message, optional, tag = "2")]
    pub pose: Option<PoseMessage>,
    /// Line thickness.
    #[prost(double, tag = "3")]
    pub thickness: f64,
    /// Thickness in pixels rather than metres.
    #[prost(bool, tag = "4")]
    pub scale_invariant: bool,
    /// Points of the strip.
    #[prost(message, repeated, tag = "5")]
    pub points: Vec<Vector3Message>,
    /// Colour of the whole line.
    #[prost(message, optional, tag = "6")]
    pub color: Option<ColorMessage>,
}

/// `foxglove.KeyValuePair`.
#[derive(Clone, PartialEq, Message)]
pub struct KeyValueMessage {
    /// Key.
    #[prost(string, tag = "1")]
    pub key: String,
    /// Value.
    #[prost(string, tag = "2")]
    pub value: String,
}

/// `foxglove.SceneEntity` (the fields we use).
#[derive(Clone, PartialEq, Message)]
pub struct SceneEntityMessage {
    /// Time of the entity.
    #[prost(message, optional, tag = "1")]
    pub timestamp: Option<TimeMessage>,
    /// Frame the entity is drawn in.
    #[prost(string, tag = "2")]
    pub frame_id: String,
    /// Entity id: re-sending the same id replaces (animates) it.
    #[prost(string, tag = "3")]
    pub id: String,
    /// Lifetime (zero: until replaced).
    #[prost(message, optional, tag = "4")]
    pub lifetime: Option<TimeMessage>,
    /// Whether to move with the frame.
    #[prost(bool, tag = "5")]
    pub frame_locked: bool,
    /// Extra information shown in the 3D panel.
    #[prost(message, repeated, tag = "6")]
    pub metadata: Vec<KeyValueMessage>,
    /// Line primitives.
    #[prost(message, repeated, tag = "11")]
    pub lines: Vec<LinePrimitiveMessage>,
}

/// `foxglove.SceneUpdate` (entities only: nothing is ever deleted).
#[derive(Clone, PartialEq, Message)]
pub struct SceneUpdateMessage {
    /// Entities added or replaced.
    #[prost(message, repeated, tag = "2")]
    pub entities: Vec<SceneEntityMessage>,
}

/// `foxglove.Log`.
#[derive(Clone, PartialEq, Message)]
pub struct LogMessage {
    /// Time of the line.
    #[prost(message, optional, tag = "1")]
    pub timestamp: Option<TimeMessage>,
    /// 2 = INFO.
    #[prost(int32, tag = "2")]
    pub level: i32,
    /// The text.
    #[prost(string, tag = "3")]
    pub message: String,
    /// Source name.
    #[prost(string, tag = "4")]
    pub name: String,
    /// Source file.
    #[prost(string, tag = "5")]
    pub file: String,
    /// Source line.
    #[prost(fixed32, tag = "6")]
    pub line: u32,
}

/// `foxglove.Log.Level.INFO`.
pub const LOG_LEVEL_INFO: i32 = 2;
/// `foxglove.Log.Level.WARNING`.
pub const LOG_LEVEL_WARNING: i32 = 3;

// ---------------------------------------------------------------------------------------------
// Descriptors.

fn scalar(name: &str, number: i32, ty: Type) -> FieldDescriptorProto {
    FieldDescriptorProto {
        name: Some(name.to_string()),
        number: Some(number),
        label: Some(Label::Optional as i32),
        r#type: Some(ty as i32),
        json_name: Some(json_name(name)),
        ..Default::default()
    }
}

fn repeated(name: &str, number: i32, ty: Type) -> FieldDescriptorProto {
    FieldDescriptorProto { label: Some(Label::Repeated as i32), ..scalar(name, number, ty) }
}

fn message(name: &str, number: i32, type_name: &str) -> FieldDescriptorProto {
    FieldDescriptorProto { type_name: Some(type_name.to_string()), ..scalar(name, number, Type::Message) }
}

fn messages(name: &str, number: i32, type_name: &str) -> FieldDescriptorProto {
    FieldDescriptorProto { label: Some(Label::Repeated as i32), ..message(name, number, type_name) }
}

fn enumeration(name: &str, number: i32, type_name: &str) -> FieldDescriptorProto {
    FieldDescriptorProto { type_name: Some(type_name.to_string()), ..scalar(name, number, Type::Enum) }
}

fn json_name(name: &str) -> String {
    let mut out = String::with_capacity(name.len());
    let mut upper = false;
    for c in name.chars() {
        if c == '_' {
            upper = true;
        } else if upper {
            out.extend(c.to_uppercase());
            upper = false;
        } else {
            out.push(c);
        }
    }
    out
}

fn descriptor(name: &str, field: Vec<FieldDescriptorProto>) -> DescriptorProto {
    DescriptorProto { name: Some(name.to_string()), field, ..Default::default() }
}

fn enum_type(name: &str, values: &[(&str, i32)]) -> EnumDescriptorProto {
    EnumDescriptorProto {
        name: Some(name.to_string()),
        value: values
            .iter()
            .map(|(n, v)| EnumValueDescriptorProto { name: Some(n.to_string()), number: Some(*v), options: None })
            .collect(),
        ..Default::default()
    }
}

fn file(name: &str, package: &str, dependency: &[&str], message_type: Vec<DescriptorProto>) -> FileDescriptorProto {
    FileDescriptorProto {
        name: Some(name.to_string()),
        package: Some(package.to_string()),
        dependency: dependency.iter().map(|d| d.to_string()).collect(),
        message_type,
        syntax: Some("proto3".to_string()),
        ..Default::default()
    }
}

fn encode_set(file: Vec<FileDescriptorProto>) -> Vec<u8> {
    FileDescriptorSet { file }.encode_to_vec()
}

/// `beam_impact.proto`: Step, EnergyAccount, Peaks, ContactEvent, Model.
fn beam_impact_file() -> FileDescriptorProto {
    use Type::{Bool, Double, Float, String as Str, Uint32, Uint64};
    let d = |n: &str, k: i32| scalar(n, k, Double);
    let energy = descriptor(
        "EnergyAccount",
        vec![
            d("kinetic", 1),
            d("strain", 2),
            d("gravity_potential", 3),
            d("external_work", 4),
            d("damping_dissipation", 5),
            d("residual", 6),
        ],
    );
    let peaks = descriptor(
        "Peaks",
        vec![
            d("lower_tip_deflection", 1),
            d("lower_clamp_bending_stress", 2),
            d("lower_clamp_shear_stress", 3),
            d("upper_contact_bending_stress", 4),
            d("contact_force", 5),
        ],
    );
    let step = descriptor(
        "Step",
        vec![
            scalar("step", 1, Uint64),
            scalar("time_ns", 2, Uint64),
            d("time", 3),
            d("step_size", 4),
            scalar("contact", 5, Bool),
            d("lower_tip_deflection", 6),
            d("upper_contact_deflection", 7),
            d("upper_tip_deflection", 8),
            d("lower_clamp_bending_stress", 9),
            d("lower_clamp_shear_stress", 10),
            d("upper_contact_bending_stress", 11),
            d("contact_force", 12),
            d("contact_stress", 13),
            message("energy", 14, ".beam_impact.EnergyAccount"),
            message("peaks", 15, ".beam_impact.Peaks"),
            repeated("modal_coordinates", 16, Float),
            d("lower_clamp_reaction_force", 17),
            d("lower_clamp_reaction_moment", 18),
            d("upper_hinge_reaction_force", 19),
            d("lower_tip_velocity", 20),
            d("upper_tip_velocity", 21),
        ],
    );
    let event = descriptor(
        "ContactEvent",
        vec![
            scalar("start", 1, Bool),
            scalar("time_ns", 2, Uint64),
            scalar("step", 3, Uint64),
            d("relative_velocity", 4),
            d("time", 5),
        ],
    );
    let model = descriptor(
        "Model",
        vec![
            scalar("scenario_toml", 1, Str),
            repeated("lower_nodes", 2, Double),
            repeated("upper_nodes", 3, Double),
            scalar("shape_rows", 4, Uint32),
            scalar("shape_cols", 5, Uint32),
            repeated("nodal_shapes", 6, Double),
        ],
    );
    file("beam_impact.proto", "beam_impact", &[], vec![step, energy, peaks, event, model])
}

/// The `FileDescriptorSet` of the `beam_impact` messages (one set serves all three schemas).
pub fn beam_impact_descriptor() -> Vec<u8> {
    encode_set(vec![beam_impact_file()])
}

fn google_time_files() -> Vec<FileDescriptorProto> {
    let seconds_nanos =
        |name: &str| descriptor(name, vec![scalar("seconds", 1, Type::Int64), scalar("nanos", 2, Type::Int32)]);
    vec![
        file("google/protobuf/timestamp.proto", "google.protobuf", &[], vec![seconds_nanos("Timestamp")]),
        file("google/protobuf/duration.proto", "google.protobuf", &[], vec![seconds_nanos("Duration")]),
    ]
}

/// The `FileDescriptorSet` of `foxglove.SceneUpdate` with every message it references, as
/// published by Foxglove (field names, numbers and types).
pub fn scene_update_descriptor() -> Vec<u8> {
    use Type::{Bool, Bytes, Double, Fixed32, String as Str};
    let d = |n: &str, k: i32| scalar(n, k, Double);
    let pose = || message("pose", 1, ".foxglove.Pose");
    let color = |k: i32| message("color", k, ".foxglove.Color");
    let xyz = |name: &str| descriptor(name, vec![d("x", 1), d("y", 2), d("z", 3)]);
    let mut line = descriptor(
        "LinePrimitive",
        vec![
            enumeration("type", 1, ".foxglove.LinePrimitive.Type"),
            message("pose", 2, ".foxglove.Pose"),
            d("thickness", 3),
            scalar("scale_invariant", 4, Bool),
            messages("points", 5, ".foxglove.Point3"),
            color(6),
            messages("colors", 7, ".foxglove.Color"),
            repeated("indices", 8, Fixed32),
        ],
    );
    line.enum_type = vec![enum_type("Type", &[("LINE_STRIP", 0), ("LINE_LOOP", 1), ("LINE_LIST", 2)])];
    let mut deletion = descriptor(
        "SceneEntityDeletion",
        vec![
            message("timestamp", 1, ".google.protobuf.Timestamp"),
            enumeration("type", 2, ".foxglove.SceneEntityDeletion.Type"),
            scalar("id", 3, Str),
        ],
    );
    deletion.enum_type = vec![enum_type("Type", &[("MATCHING_ID", 0), ("ALL", 1)])];
    let types = vec![
        descriptor(
            "SceneUpdate",
            vec![
                messages("deletions", 1, ".foxglove.SceneEntityDeletion"),
                messages("entities", 2, ".foxglove.SceneEntity"),
            ],
        ),
        deletion,
        descriptor(
            "SceneEntity",
            vec![
                message("timestamp", 1, ".google.protobuf.Timestamp"),
                scalar("frame_id", 2, Str),
                scalar("id", 3, Str),
                message("lifetime", 4, ".google.protobuf.Duration"),
                scalar("frame_locked", 5, Bool),
                messages("metadata", 6, ".foxglove.KeyValuePair"),
                messages("arrows", 7, ".foxglove.ArrowPrimitive"),
                messages("cubes", 8, ".foxglove.CubePrimitive"),
                messages("spheres", 9, ".foxglove.SpherePrimitive"),
                messages("cylinders", 10, ".foxglove.CylinderPrimitive"),
                messages("lines", 11, ".foxglove.LinePrimitive"),
                messages("triangles", 12, ".foxglove.TriangleListPrimitive"),
                messages("texts", 13, ".foxglove.TextPrimitive"),
                messages("models", 14, ".foxglove.ModelPrimitive"),
            ],
        ),
        descriptor("KeyValuePair", vec![scalar("key", 1, Str), scalar("value", 2, Str)]),
        descriptor(
            "ArrowPrimitive",
            vec![
                pose(),
                d("shaft_length", 2),
                d("shaft_diameter", 3),
                d("head_length", 4),
                d("head_diameter", 5),
                color(6),
            ],
        ),
        descriptor("CubePrimitive", vec![pose(), message("size", 2, ".foxglove.Vector3"), color(3)]),
        descriptor("SpherePrimitive", vec![pose(), message("size", 2, ".foxglove.Vector3"), color(3)]),
        descriptor(
            "CylinderPrimitive",
            vec![pose(), message("size", 2, ".foxglove.Vector3"), d("bottom_scale", 3), d("top_scale", 4), color(5)],
        ),
        line,
        descriptor(
            "TriangleListPrimitive",
            vec![
                pose(),
                messages("points", 2, ".foxglove.Point3"),
                color(3),
                messages("colors", 4, ".foxglove.Color"),
                repeated("indices", 5, Fixed32),
            ],
        ),
        descriptor(
            "TextPrimitive",
            vec![
                pose(),
                scalar("billboard", 2, Bool),
                d("font_size", 3),
                scalar("scale_invariant", 4, Bool),
                color(5),
                scalar("text", 6, Str),
            ],
        ),
        descriptor(
            "ModelPrimitive",
            vec![
                pose(),
                message("scale", 2, ".foxglove.Vector3"),
                color(3),
                scalar("override_color", 4, Bool),
                scalar("url", 5, Str),
                scalar("media_type", 6, Str),
                scalar("data", 7, Bytes),
            ],
        ),
        descriptor(
            "Pose",
            vec![message("position", 1, ".foxglove.Vector3"), message("orientation", 2, ".foxglove.Quaternion")],
        ),
        xyz("Vector3"),
        xyz("Point3"),
        descriptor("Quaternion", vec![d("x", 1), d("y", 2), d("z", 3), d("w", 4)]),
        descriptor("Color", vec![d("r", 1), d("g", 2), d("b", 3), d("a", 4)]),
    ];
    let mut files = google_time_files();
    files.push(file(
        "foxglove/SceneUpdate.proto",
        "foxglove",
        &["google/protobuf/timestamp.proto", "google/protobuf/duration.proto"],
        types,
    ));
    encode_set(files)
}

/// The `FileDescriptorSet` of `foxglove.Log`.
pub fn log_descriptor() -> Vec<u8> {
    use Type::{Fixed32, String as Str};
    let mut log = descriptor(
        "Log",
        vec![
            message("timestamp", 1, ".google.protobuf.Timestamp"),
            enumeration("level", 2, ".foxglove.Log.Level"),
            scalar("message", 3, Str),
            scalar("name", 4, Str),
            scalar("file", 5, Str),
            scalar("line", 6, Fixed32),
        ],
    );
    log.enum_type = vec![enum_type(
        "Level",
        &[("UNKNOWN", 0), ("DEBUG", 1), ("INFO", 2), ("WARNING", 3), ("ERROR", 4), ("FATAL", 5)],
    )];
    let mut files = google_time_files();
    files.truncate(1);
    files.push(file("foxglove/Log.proto", "foxglove", &["google/protobuf/timestamp.proto"], vec![log]));
    encode_set(files)
}
