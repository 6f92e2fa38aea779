//! The `foxglove.SceneUpdate` of both beams, so Foxglove's 3D panel animates the impact: each
//! beam through its deflected nodes, each element coloured by its current utilisation.
//!
//! Frame `world`, z up, true scale. The bridge lies along x from its hinge; the arrestor is drawn
//! at right angles to it (along y), its free end under the bridge's contact point, so the two
//! lines meet where the beams touch instead of lying on top of each other. The paper's Figure 5
//! (the real layout) is not in the text; this drawing is schematic in plan, exact in deflection.
//!
//! **Utilisation colours** (issue 30). With the run's stress stations, each element takes the
//! colour of its utilisation at that instant: the largest |stress| / allowable over the bending
//! and shear stations at its two ends (on its own side of a section change or a point load), on a
//! scale from green (0) through yellow (0.5) to red (1 and above) ([`utilisation_color`]), in
//! steps of 1/[`COLOR_LEVELS`]. A beam is drawn as one line strip per run of elements of the same
//! colour (a colour per point would blend neighbours and triple the message). An element none of
//! whose stations has an allowable keeps the beam's own colour (the arrestor orange, the bridge
//! blue), as does every element of a log written without stations (one line strip per beam).
//! Each beam's entity carries its largest utilisation at that instant, with where, as metadata
//! whose key states the scale ([`UTILISATION_KEY`]; Foxglove shows it on selecting the beam).

use super::schema::{
    ColorMessage, KeyValueMessage, LinePrimitiveMessage, PoseMessage, QuaternionMessage, SceneEntityMessage,
    SceneUpdateMessage, TimeMessage, Vector3Message,
};
use super::stations::StationGroup;
use super::RunInfo;

/// Entity id of the arrestor's line.
pub const ARRESTOR_ID: &str = "arrestor";
/// Entity id of the bridge's line.
pub const BRIDGE_ID: &str = "bridge";
/// Frame of the scene.
pub const FRAME: &str = "world";

/// The arrestor's own colour (elements without an allowable, logs without stations).
const ARRESTOR_COLOR: ColorMessage = ColorMessage { r: 0.95, g: 0.5, b: 0.1, a: 1.0 };
/// The bridge's own colour.
const BRIDGE_COLOR: ColorMessage = ColorMessage { r: 0.2, g: 0.45, b: 0.95, a: 1.0 };

/// The key of each beam's entity metadata that gives its largest utilisation at that instant
/// (`0.772 at x = 3.000 m`, the element's middle), and the colour scale in words (elements
/// without an allowable keep the beam's own colour).
pub const UTILISATION_KEY: &str = "utilisation (colours: green 0, yellow 0.5, red 1 or more)";

/// Steps of the colour scale between 0 and 1: an element's colour is that of its utilisation
/// rounded to the nearest 1/20 (0.05).
pub const COLOR_LEVELS: u32 = 20;

/// `foxglove.LinePrimitive.Type.LINE_STRIP`.
const LINE_STRIP: i32 = super::schema::foxglove::line_primitive::Type::LineStrip as i32;

/// The colour of utilisation `u`: green (0.1, 0.75, 0.2) at 0, yellow (0.95, 0.85, 0.1) at 0.5,
/// red (0.9, 0.1, 0.1) at 1 and above, linear between; a utilisation that is not a number is red
/// (a stress the log cannot vouch for is shown, not hidden).
pub fn utilisation_color(u: f64) -> ColorMessage {
    const GREEN: [f64; 3] = [0.1, 0.75, 0.2];
    const YELLOW: [f64; 3] = [0.95, 0.85, 0.1];
    const RED: [f64; 3] = [0.9, 0.1, 0.1];
    let u = if u.is_nan() { 1.0 } else { u.clamp(0.0, 1.0) };
    let (a, b, t) = if u <= 0.5 { (GREEN, YELLOW, u / 0.5) } else { (YELLOW, RED, (u - 0.5) / 0.5) };
    let mix = |i: usize| a[i] + (b[i] - a[i]) * t;
    ColorMessage { r: mix(0), g: mix(1), b: mix(2), a: 1.0 }
}

/// One beam's elements and the stations that bound each (indices into the run's stations in the
/// order of [`super::stations::StationLayout::groups`]), with each station's allowable.
#[derive(Clone, Debug, Default)]
struct ElementStations {
    /// Per element: (station index, its allowable, > 0).
    elements: Vec<Vec<(usize, f64)>>,
    /// Each element's midpoint, m from the support (for the metadata's "where").
    middles: Vec<f64>,
}

/// Builds scene updates from modal coordinates, reusing one message.
#[derive(Clone, Debug)]
pub struct SceneBuilder {
    shapes: Vec<f64>,
    cols: usize,
    /// Each beam's undeformed points (arrestor, bridge).
    points: [Vec<Vector3Message>; 2],
    /// Per beam (arrestor, bridge): its elements' stations; None without stations.
    elements: Option<[ElementStations; 2]>,
    update: SceneUpdateMessage,
}

fn line(color: ColorMessage, points: Vec<Vector3Message>) -> LinePrimitiveMessage {
    LinePrimitiveMessage {
        r#type: LINE_STRIP,
        pose: Some(PoseMessage {
            position: Some(Vector3Message { x: 0.0, y: 0.0, z: 0.0 }),
            orientation: Some(QuaternionMessage { x: 0.0, y: 0.0, z: 0.0, w: 1.0 }),
        }),
        thickness: 0.15,
        scale_invariant: false,
        points,
        color: Some(color),
        colors: Vec::new(),
    }
}

fn entity(id: &str, lines: Vec<LinePrimitiveMessage>, metadata: Vec<KeyValueMessage>) -> SceneEntityMessage {
    SceneEntityMessage {
        timestamp: Some(TimeMessage::default()),
        frame_id: FRAME.to_string(),
        id: id.to_string(),
        lifetime: None,
        frame_locked: false,
        metadata,
        lines,
    }
}

fn key_value(key: &str, value: &str) -> KeyValueMessage {
    KeyValueMessage { key: key.to_string(), value: value.to_string() }
}

/// The stations of `groups` (bending and shear of one beam, with the index of each group's first
/// station among the run's) bounding each element of a beam with nodes at `nodes`.
fn element_stations(groups: [(&StationGroup, usize); 2], nodes: &[f64]) -> ElementStations {
    let elements = nodes.len().saturating_sub(1);
    let mut out = ElementStations {
        elements: vec![Vec::new(); elements],
        middles: (0..elements).map(|e| 0.5 * (nodes[e] + nodes[e + 1])).collect(),
    };
    for (group, offset) in groups {
        for (e, stations) in group.stations_of_elements(elements).into_iter().enumerate() {
            for k in stations {
                if group.allowable.get(k).is_some_and(|&a| a > 0.0) {
                    out.elements[e].push((offset + k, group.allowable[k]));
                }
            }
        }
    }
    out
}

/// The largest utilisation |stress| / allowable over `stations` (NaN if any is not a number).
fn utilisation(stations: &[(usize, f64)], stresses: &[f64]) -> f64 {
    stations
        .iter()
        .map(|&(k, allowable)| stresses.get(k).map_or(0.0, |v| v.abs() / allowable))
        .fold(0.0, |m: f64, u| if u.is_nan() || m.is_nan() { f64::NAN } else { m.max(u) })
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
        let elements = info.stations.map(|probe| {
            let l = &probe.layout;
            let (lb, ls, ub) = (l.lower_bending.len(), l.lower_shear.len(), l.upper_bending.len());
            [
                element_stations([(&l.lower_bending, 0), (&l.lower_shear, lb)], info.lower_nodes),
                element_stations([(&l.upper_bending, lb + ls), (&l.upper_shear, lb + ls + ub)], info.upper_nodes),
            ]
        });
        let metadata = || match elements {
            Some(_) => vec![key_value(UTILISATION_KEY, "")],
            None => Vec::new(),
        };
        let update = SceneUpdateMessage {
            entities: vec![
                entity(ARRESTOR_ID, vec![line(ARRESTOR_COLOR, arrestor.clone())], metadata()),
                entity(BRIDGE_ID, vec![line(BRIDGE_COLOR, bridge.clone())], metadata()),
            ],
        };
        SceneBuilder { shapes, cols: s.ncols(), points: [arrestor, bridge], elements, update }
    }

    /// The scene at `time_ns` for modal coordinates `q` (deflections w = shapes * q on z), its
    /// elements coloured by the `stresses` at every station (signed, Pa, in the order of the
    /// stations' layout), if given.
    pub fn update(&mut self, time_ns: u64, q: &[f64], stresses: Option<&[f64]>) -> &SceneUpdateMessage {
        let stamp = TimeMessage::from_ns(time_ns);
        let cols = self.cols.min(q.len());
        let mut row = 0;
        for beam in 0..2 {
            let count = self.points[beam].len();
            let w: Vec<f64> = (row..row + count)
                .map(|r| {
                    let shape = &self.shapes[r * self.cols..r * self.cols + cols];
                    shape.iter().zip(q).map(|(s, q)| s * q).sum()
                })
                .collect();
            row += count;
            let own = if beam == 0 { ARRESTOR_COLOR } else { BRIDGE_COLOR };
            let points = &self.points[beam];
            let deflected = |k: usize| Vector3Message { z: w[k], ..points[k] };
            let Some(entity) = self.update.entities.get_mut(beam) else { break };
            entity.timestamp = Some(stamp);
            let Some(elements) = &self.elements else {
                for (k, point) in entity.lines[0].points.iter_mut().enumerate() {
                    *point = deflected(k);
                }
                continue;
            };
            // Each element's colour level (None: the beam's own colour), then a strip per run.
            let beam_elements = &elements[beam];
            let mut worst: Option<(f64, f64)> = None;
            let levels: Vec<Option<u32>> = (0..count.saturating_sub(1))
                .map(|e| {
                    let stations = beam_elements.elements.get(e).map_or(&[][..], Vec::as_slice);
                    let values = stresses.filter(|_| !stations.is_empty())?;
                    let u = utilisation(stations, values);
                    if worst.is_none_or(|(w, _)| u > w || u.is_nan()) {
                        worst = Some((u, beam_elements.middles.get(e).copied().unwrap_or(0.0)));
                    }
                    let clamped = if u.is_nan() { 1.0 } else { u.clamp(0.0, 1.0) };
                    Some((clamped * f64::from(COLOR_LEVELS)).round() as u32)
                })
                .collect();
            let mut lines = Vec::new();
            let mut start = 0;
            for e in 1..=levels.len() {
                if e == levels.len() || levels[e] != levels[start] {
                    let color = levels[start]
                        .map_or(own, |level| utilisation_color(f64::from(level) / f64::from(COLOR_LEVELS)));
                    lines.push(line(color, (start..=e).map(deflected).collect()));
                    start = e;
                }
            }
            entity.lines = lines;
            if let Some(entry) = entity.metadata.first_mut() {
                entry.value = match worst {
                    Some((u, x)) => format!("{u:.3} at x = {x:.3} m"),
                    None => "no allowable given".to_string(),
                };
            }
        }
        &self.update
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The scale runs green, yellow, red, and stays red above 1 and for a value that is not one.
    #[test]
    fn the_colour_scale_runs_from_green_through_yellow_to_red() {
        let (g, y, r) = (utilisation_color(0.0), utilisation_color(0.5), utilisation_color(1.0));
        assert!(g.g > g.r && g.g > g.b, "{g:?}");
        assert!(y.r > 0.9 && y.g > 0.8 && y.b < 0.2, "{y:?}");
        assert!(r.r > 0.8 && r.g < 0.2, "{r:?}");
        assert_eq!(utilisation_color(3.0), r);
        assert_eq!(utilisation_color(f64::NAN), r);
        assert_eq!(utilisation_color(-1.0), g);
    }

    /// Each element takes the colour of the larger utilisation at its end stations; neighbours
    /// of one colour are one strip; a beam without allowables keeps its own colour and says so.
    #[test]
    fn elements_are_coloured_by_their_utilisation_in_strips_of_one_colour() {
        use super::super::stations::{StationLayout, StationProbe};
        let group = |x: [f64; 3], allowable: f64| StationGroup {
            positions: x.to_vec(),
            allowable: vec![allowable; 3],
            nodes: vec![0, 1, 2],
        };
        let layout = StationLayout {
            lower_bending: group([0.0, 6.0, 12.0], 1e8),
            upper_bending: group([0.0, 13.0, 29.0], 0.0),
            sampled_every: 1,
            ..StationLayout::default()
        };
        let probe = StationProbe { layout, rows: Default::default(), feed: Default::default() };
        let scenario = crate::Scenario::default();
        let shapes = nalgebra::DMatrix::from_element(6, 1, 0.5);
        let info = RunInfo {
            scenario: &scenario,
            lower_nodes: &[0.0, 6.0, 12.0],
            upper_nodes: &[0.0, 13.0, 29.0],
            nodal_shapes: &shapes,
            stations: Some(&probe),
        };
        let mut builder = SceneBuilder::new(&info);
        let update = builder.update(7, &[2.0], Some(&[-1e8, 2e7, 0.0, 5e8, 5e8, 5e8])).clone();
        let (arrestor, bridge) = (&update.entities[0], &update.entities[1]);
        assert_eq!(arrestor.lines.len(), 2);
        assert_eq!(arrestor.lines[0].color, Some(utilisation_color(1.0)));
        assert_eq!(arrestor.lines[1].color, Some(utilisation_color(0.2)));
        assert_eq!(arrestor.lines[0].points.len(), 2);
        assert!(arrestor.lines.iter().flat_map(|l| &l.points).all(|p| p.z == 1.0));
        let value = |e: &SceneEntityMessage, key: &str| e.metadata.iter().find(|m| m.key == key).unwrap().value.clone();
        assert_eq!(value(arrestor, UTILISATION_KEY), "1.000 at x = 3.000 m");
        assert_eq!(bridge.lines.len(), 1);
        assert_eq!(bridge.lines[0].color, Some(BRIDGE_COLOR));
        assert_eq!(bridge.lines[0].points.len(), 3);
        assert_eq!(value(bridge, UTILISATION_KEY), "no allowable given");
        let update = builder.update(8, &[2.0], Some(&[-1e8, 1e8, 3e8, 0.0, 0.0, 0.0]));
        assert_eq!(update.entities[0].lines.len(), 1, "both elements at 1 or above: one red strip");
        assert_eq!(update.entities[0].lines[0].points.len(), 3);
    }
}
