//! Every integration test of beam-impact, in one test binary: one link instead of one per file
//! (the release build linked 38 binaries, each holding the whole library), and one pool of test
//! threads across the files. Each file below is a module named after what it holds;
//! `cargo test --release --test integration fmi_drift::` runs one file's tests.

// Helpers shared by several files.
mod fmi_common;
mod fuzz_support;
mod recording_support;

mod answer;
mod benchmarks;
mod cli;
mod cli_defects;
mod closed_form;
mod contact_laws;
mod converged_references;
mod docs;
mod energy_account_off;
mod energy_method;
mod energy_safety;
mod envelope_log;
mod envelope_sampling;
mod envelope_scope;
mod examples;
mod figures;
mod fmi_answer;
mod fmi_default_log;
mod fmi_description;
mod fmi_drift;
mod fmi_full_disk;
mod fmi_grid;
mod fmi_importer;
mod fmi_issue28;
mod fmi_misuse;
mod fmi_motion;
mod fmi_pack;
mod fmi_quality;
mod fmi_sections;
mod fmi_state_restore;
mod fuzz_log_reader;
mod fuzz_motion_table;
mod fuzz_output_paths;
mod fuzz_resource_scenario;
mod fuzz_scenario;
mod fuzz_state;
mod hostile_logs;
mod hostile_motion;
mod hostile_outputs;
mod mcap_format2;
mod mcap_killed;
mod mcap_layout;
mod mcap_recording;
mod modes_fine_mesh;
mod no_circles;
mod one_run;
mod paper;
mod reactions;
mod report_csv;
mod robust_meshes;
mod scenario;
mod ssp_pack;
mod stepped_beams;
mod stepping;
mod support_motion;
mod sweep;
mod truncation;
mod verify;
