//! The `foxglove.SceneUpdate` of both beams: each beam a line strip through its deflected nodes,
//! so Foxglove's 3D panel animates the impact.
//!
//! Frame `world`, z up, true scale. The bridge lies along x from its hinge; the arrestor is drawn
//! at right angles to it (along y), its free end under the bridge's contact point, so the two
//! lines meet where the beams touch instead of lying on top of each other. The paper's Figure 5
//! (the real layout) is not in the text; this drawing is schematic in plan, exact in deflection.

use super::schema::{
    ColorMessage, LinePrimitiveMessage, PoseMessage, QuaternionMessage, SceneEntityMessage, SceneUpdateMessage,
    TimeMessage, Vector3Message,
};
use super::RunInfo;

/// Entity id of the arrestor's line strip.
pub const ARRESTOR_ID: &str = "arrestor";
/// Entity id of the bridge's line strip.
pub const BRIDGE_ID: &str = "bridge";
/// Frame of the scene.
pub const FRAME: &str = "world";

/// Builds scene updates from modal coordinates, reusing one message.
#[derive(Clone, Debug)]
pub struct SceneBuilder {
    shapes: Vec<f64>,
    cols: usize,
    lower_nodes: usize,
    update: SceneUpdateMessage,
}

fn line(color: ColorMessage, points: Vec<Vector3Message>) -> LinePrimitiveMessage {
    LinePrimitiveMessage {
        r#type: 0, // LINE_STRIP
        pose: Some(PoseMessage {
            position: Some(Vector3Message { x: 0.0, y: 0.0, z: 0.0 }),
            orientation: Some(QuaternionMessage { x: 0.0, y: 0.0, z: 0.0, w: 1.0 }),
        }),
        thickness: 0.15,
        scale_invariant: false,
        points,
        color: Some(color),
    }
}

fn entity(id: &str, line: LinePrimitiveMessage) -> SceneEntityMessage {
    SceneEntityMessage {
        timestamp: Some(TimeMessage::default()),
        frame_id: FRAME.to_string(),
        id: id.to_string(),
        lifetime: None,
        frame_locked: false,
        metadata: Vec::new(),
        lines: vec![line],
    }
}

impl SceneBuilder {
    /// The undeformed layout of both beams from the run's description.
    pub fn new(info: &RunInfo<'_>) -> Self {
        let s = info.nodal_shapes;
        let shapes: Vec<f64> = (0..s.nrows()).flat_map(|r| (0..s.ncols()).map(move |c| s[(r, c)])).collect();
        let contact = info.scenario.contact_position;
        let lower_length = info.lower_nodes.last().copied().unwrap_or(0.0);
        let arrestor: Vec<Vector3Message> =
            info.lower_nodes.iter().map(|&x| Vector3Message { x: contact, y: x - lower_length, z: 0.0 }).collect();
        let bridge: Vec<Vector3Message> =
            info.upper_nodes.iter().map(|&x| Vector3Message { x, y: 0.0, z: 0.0 }).collect();
        let update = SceneUpdateMessage {
            entities: vec![
                entity(ARRESTOR_ID, line(ColorMessage { r: 0.95, g: 0.5, b: 0.1, a: 1.0 }, arrestor)),
                entity(BRIDGE_ID, line(ColorMessage { r: 0.2, g: 0.45, b: 0.95, a: 1.0 }, bridge)),
            ],
        };
        SceneBuilder { shapes, cols: s.ncols(), lower_nodes: info.lower_nodes.len(), update }
    }

    /// The scene at `time_ns` for modal coordinates `q` (deflections w = shapes * q on z).
    pub fn update(&mut self, time_ns: u64, q: &[f64]) -> &SceneUpdateMessage {
        let stamp = TimeMessage::from_ns(time_ns);
        let cols = self.cols.min(q.len());
        let mut row = 0;
        for (e, entity) in self.update.entities.iter_mut().enumerate() {
            entity.timestamp = Some(stamp);
            for point in entity.lines[0].points.iter_mut() {
                let shape = &self.shapes[row * self.cols..row * self.cols + cols];
                point.z = shape.iter().zip(q).map(|(s, q)| s * q).sum();
                row += 1;
            }
            debug_assert!(e != 0 || row == self.lower_nodes);
        }
        &self.update
    }
}
