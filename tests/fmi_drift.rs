//! Drift tests: the committed modelDescription.xml files (FMI 2.0 at the top of the repository,
//! FMI 3.0 under `fmu/`) and the C header in `include/` must equal what the source generates
//! from the one variable table and the exported functions.
//! `BEAM_IMPACT_BLESS=1 cargo test --release --test integration fmi_drift::` rewrites them.

use std::path::Path;

use beam_impact::fmi::description;

fn check(relative: &str, generated: &str) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(relative);
    if std::env::var_os("BEAM_IMPACT_BLESS").is_some() {
        std::fs::write(&path, generated).unwrap();
        return;
    }
    let committed = std::fs::read_to_string(&path).unwrap_or_default();
    if committed != generated {
        let line = committed
            .lines()
            .zip(generated.lines())
            .position(|(a, b)| a != b)
            .unwrap_or_else(|| committed.lines().count().min(generated.lines().count()));
        panic!(
            "{relative} differs from the generated text from line {} on: committed {:?}, generated {:?}; \
             run BEAM_IMPACT_BLESS=1 cargo test --release --test integration fmi_drift:: and commit",
            line + 1,
            committed.lines().nth(line),
            generated.lines().nth(line)
        );
    }
}

#[test]
fn fmi2_model_description_matches_the_variable_table() {
    check("modelDescription.xml", &description::fmi2());
}

#[test]
fn fmi3_model_description_matches_the_variable_table() {
    check("fmu/modelDescription.xml", &description::fmi3());
}

#[test]
fn header_matches_cbindgen() {
    let root = env!("CARGO_MANIFEST_DIR");
    let config = cbindgen::Config::from_file(Path::new(root).join("cbindgen.toml")).unwrap();
    let bindings = cbindgen::generate_with_config(root, config).unwrap();
    let mut header = Vec::new();
    bindings.write(&mut header);
    check("include/beam_impact.h", &String::from_utf8(header).unwrap());
}
