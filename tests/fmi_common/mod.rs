//! Shared by the FMI integration tests: where the freshly built shared library is.

#![allow(dead_code)]

use std::path::PathBuf;

pub mod importer;

/// `libbeam_impact.so` of the profile the tests were built with: `cargo test` builds the cdylib
/// into `deps/` beside the test executable (the copy one level up is only refreshed by `cargo build`).
pub fn library() -> PathBuf {
    let exe = std::env::current_exe().unwrap();
    let deps = exe.parent().unwrap();
    for candidate in [deps.join("libbeam_impact.so"), deps.parent().unwrap().join("libbeam_impact.so")] {
        if candidate.is_file() {
            return candidate;
        }
    }
    panic!("libbeam_impact.so not found next to {}", deps.display());
}
