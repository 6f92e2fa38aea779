//! Any text as a scenario file: `Scenario::from_toml` (parse and validate); what it accepts
//! validates again and round-trips through `to_toml`.
#![no_main]

use beam_impact::Scenario;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    match Scenario::from_toml(text, "fuzz.toml") {
        Err(e) => assert!(!e.to_string().contains('\n')),
        Ok(s) => {
            s.validate().expect("an accepted scenario validates");
            let again =
                Scenario::from_toml(&s.to_toml(), "again.toml").expect("to_toml of an accepted scenario parses");
            assert_eq!(again, s);
        }
    }
});
