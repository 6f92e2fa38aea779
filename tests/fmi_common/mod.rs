//! Shared by the FMI integration tests: where the freshly built shared library is.

#![allow(dead_code)]

use std::path::PathBuf;

/// `libbeam_impact.so` of the profile the tests were built with (cargo builds the cdylib for
/// integration tests; it sits next to the `deps/` directory of the test executable).
pub fn library() -> PathBuf {
    let exe = std::env::current_exe().unwrap();
    let deps = exe.parent().unwrap();
    for candidate in [deps.parent().unwrap().join("libbeam_impact.so"), deps.join("libbeam_impact.so")] {
        if candidate.is_file() {
            return candidate;
        }
    }
    panic!("libbeam_impact.so not found next to {}", deps.display());
}
