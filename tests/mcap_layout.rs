//! The Foxglove layout shipped in `fmu/documentation/` (issue 4) names only what the log has.
//!
//! Goal: every plot path of the layout (`/beam/step.energy.residual`) resolves to a field of the
//! schema embedded in the log, and the 3D and log panels point at the scene and log topics; a
//! renamed field or topic fails here rather than as an empty panel in Foxglove.

use std::collections::BTreeSet;

use beam_impact::record::mcap::{LOG_TOPIC, SCENE_TOPIC, STEP_TOPIC};
use beam_impact::record::schema::beam_impact_descriptor;
use prost::Message;
use prost_types::{DescriptorProto, FileDescriptorSet};

fn collect_strings(value: &serde_json::Value, key: &str, out: &mut Vec<String>) {
    match value {
        serde_json::Value::Object(map) => {
            for (k, v) in map {
                if k == key {
                    if let Some(s) = v.as_str() {
                        out.push(s.to_string());
                    }
                }
                collect_strings(v, key, out);
            }
        }
        serde_json::Value::Array(items) => items.iter().for_each(|v| collect_strings(v, key, out)),
        _ => {}
    }
}

/// Resolves `a.b.c` through the messages of the set, from `root`.
fn resolves(types: &[DescriptorProto], root: &str, path: &str) -> bool {
    let mut message = root.to_string();
    for (k, part) in path.split('.').enumerate() {
        let Some(m) = types.iter().find(|m| m.name() == message) else { return false };
        let Some(f) = m.field.iter().find(|f| f.name() == part) else { return false };
        let last = k == path.split('.').count() - 1;
        if !last {
            message = f.type_name().trim_start_matches(".beam_impact.").to_string();
        }
    }
    true
}

#[test]
fn layout_paths_resolve_in_the_log_schema() {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/fmu/documentation/foxglove-layout.json"))
        .unwrap();
    let layout: serde_json::Value = serde_json::from_str(&text).unwrap();
    let set = FileDescriptorSet::decode(beam_impact_descriptor().as_slice()).unwrap();
    let types = &set.file[0].message_type;

    let mut paths = Vec::new();
    collect_strings(&layout, "value", &mut paths);
    assert!(paths.len() >= 6, "{paths:?}");
    let mut plotted = BTreeSet::new();
    for path in &paths {
        let field =
            path.strip_prefix(&format!("{STEP_TOPIC}.")).unwrap_or_else(|| panic!("{path} is not a step field"));
        assert!(resolves(types, "Step", field), "{path} is not in beam_impact.Step");
        plotted.insert(field.to_string());
    }
    // Figures 6-9.
    for field in [
        "lower_tip_deflection",
        "upper_contact_deflection",
        "lower_clamp_bending_stress",
        "upper_contact_bending_stress",
        "lower_clamp_shear_stress",
        "contact_stress",
    ] {
        assert!(plotted.contains(field), "no plot of {field}");
    }
    let mut log_topics = Vec::new();
    collect_strings(&layout, "topicToRender", &mut log_topics);
    assert_eq!(log_topics, [LOG_TOPIC]);
    assert!(layout["configById"]["3D!beamscene"]["topics"][SCENE_TOPIC]["visible"].as_bool().unwrap());
    // Every panel placed in the layout tree is configured, and every configured panel placed.
    let mut placed = Vec::new();
    collect_strings(&layout["layout"], "first", &mut placed);
    collect_strings(&layout["layout"], "second", &mut placed);
    let placed: BTreeSet<String> = placed.into_iter().collect();
    let configured: BTreeSet<String> = layout["configById"].as_object().unwrap().keys().cloned().collect();
    assert_eq!(placed, configured);
}
