//! Generates the log's protobuf messages and schemas from `proto/` (issue 11).
//!
//! The `.proto` files are the one source of truth: protox (a protobuf compiler in Rust, no system
//! `protoc`) compiles them, prost-build turns the result into the Rust types of
//! `record::schema`, and the serialized `FileDescriptorSet`s embedded in the log's schema records
//! are written next to the generated code, so a schema change is one edit in `proto/`.
//!
//! Written to `OUT_DIR`:
//! - `beam_impact.rs`, `foxglove.rs`: the generated messages, one file per package;
//! - `*.fds.bin`: one `FileDescriptorSet` per schema record, the root file and everything it
//!   imports, dependencies first, without source info (comments stay out of every log).

use std::collections::{BTreeSet, HashMap};
use std::env;
use std::error::Error;
use std::path::PathBuf;

use prost_types::{FileDescriptorProto, FileDescriptorSet};

/// Where the `.proto` files are (also the import root).
const PROTO_DIR: &str = "proto";

/// The schema records of the log: root file, and the name of its descriptor set in `OUT_DIR`.
const SCHEMAS: &[(&str, &str)] = &[
    ("beam_impact.proto", "beam_impact.fds.bin"),
    ("foxglove/SceneUpdate.proto", "foxglove_scene_update.fds.bin"),
    ("foxglove/Log.proto", "foxglove_log.fds.bin"),
];

/// Fields of Foxglove's messages that the generated Rust types leave out: the crate never fills
/// them, and leaving them out keeps the struct literals short. They stay in the schema records
/// (the descriptor sets above are not pruned); decoding a message that has them skips them.
const OMITTED_FIELDS: &[(&str, &[&str])] = &[
    ("foxglove.SceneUpdate", &["deletions"]),
    ("foxglove.SceneEntity", &["arrows", "cubes", "spheres", "cylinders", "triangles", "texts", "models"]),
    ("foxglove.LinePrimitive", &["indices"]),
];

/// Protobuf types generated as (mapped to) existing Rust types of the same wire layout.
const EXTERN_TYPES: &[(&str, &str)] = &[
    // `TimeMessage` is written by hand (it has `from_ns`); Timestamp and Duration share a layout.
    (".google.protobuf.Timestamp", "crate::record::schema::TimeMessage"),
    (".google.protobuf.Duration", "crate::record::schema::TimeMessage"),
    // A line's points are built as `Vector3Message`s (Point3 has the same fields and numbers).
    (".foxglove.Point3", "crate::record::schema::Vector3Message"),
];

fn main() -> Result<(), Box<dyn Error>> {
    println!("cargo:rerun-if-changed={PROTO_DIR}");
    let out_dir = PathBuf::from(env::var_os("OUT_DIR").ok_or("OUT_DIR is not set")?);

    for (root, name) in SCHEMAS {
        let mut compiler = protox::Compiler::new([PROTO_DIR])?;
        compiler.include_imports(true).include_source_info(false).open_file(root)?;
        std::fs::write(out_dir.join(name), compiler.encode_file_descriptor_set())?;
    }

    let mut compiler = protox::Compiler::new([PROTO_DIR])?;
    compiler.include_imports(true).include_source_info(true);
    for (root, _) in SCHEMAS {
        compiler.open_file(root)?;
    }
    let mut set = compiler.file_descriptor_set();
    omit_fields(&mut set);
    let roots: Vec<String> = SCHEMAS
        .iter()
        .filter_map(|(root, _)| set.file.iter().find(|f| f.name() == *root))
        .flat_map(|f| f.message_type.iter().map(move |m| format!("{}.{}", f.package(), m.name())))
        .collect();
    keep_reachable_files(&mut set, &roots);

    let mut config = prost_build::Config::new();
    for (proto, rust) in EXTERN_TYPES {
        config.extern_path(*proto, *rust);
    }
    config.compile_fds(set)?;
    Ok(())
}

/// Removes [`OMITTED_FIELDS`] from the set, with their comments (source info is indexed by the
/// field's position in its message, so the later fields' comments are renumbered to follow).
fn omit_fields(set: &mut FileDescriptorSet) {
    for file in &mut set.file {
        let package = file.package().to_string();
        for (m, message) in file.message_type.iter_mut().enumerate() {
            let full_name = format!("{package}.{}", message.name());
            let Some((_, omitted)) = OMITTED_FIELDS.iter().find(|(name, _)| *name == full_name) else { continue };
            let before = message.field.len();
            let mut new_index = HashMap::new();
            let mut kept = Vec::new();
            for (old, field) in message.field.drain(..).enumerate() {
                if !omitted.contains(&field.name()) {
                    new_index.insert(old as i32, kept.len() as i32);
                    kept.push(field);
                }
            }
            let removed = before - kept.len();
            assert_eq!(removed, omitted.len(), "{full_name} lacks one of the omitted fields {omitted:?}");
            message.field = kept;
            if let Some(info) = &mut file.source_code_info {
                // Path [4, message, 2, field, ...]: a top-level message's field.
                info.location.retain_mut(|l| match l.path.as_slice() {
                    [4, mm, 2, f, ..] if *mm == m as i32 => match new_index.get(f) {
                        Some(&n) => {
                            l.path[3] = n;
                            true
                        }
                        None => false,
                    },
                    _ => true,
                });
            }
        }
    }
}

/// Drops the files none of whose messages are reachable from `roots` (fully qualified names,
/// without the leading dot) through message fields: those only the omitted fields used.
fn keep_reachable_files(set: &mut FileDescriptorSet, roots: &[String]) {
    let mut fields: HashMap<String, Vec<String>> = HashMap::new();
    for file in &set.file {
        for message in &file.message_type {
            let referenced = message
                .field
                .iter()
                .filter_map(|f| f.type_name.as_deref())
                .map(|t| t.trim_start_matches('.').to_string())
                .collect();
            fields.insert(format!("{}.{}", file.package(), message.name()), referenced);
        }
    }
    let mut reached = BTreeSet::new();
    let mut queue: Vec<String> = roots.to_vec();
    while let Some(name) = queue.pop() {
        if reached.insert(name.clone()) {
            queue.extend(fields.get(&name).into_iter().flatten().cloned());
        }
    }
    let used = |f: &FileDescriptorProto| {
        f.message_type.iter().any(|m| reached.contains(&format!("{}.{}", f.package(), m.name())))
    };
    set.file.retain(used);
}
