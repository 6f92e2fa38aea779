//! Any bytes as an FMU's `resources/scenario.toml` (issue 30): `fmi::resource::scenario_from_bytes`
//! (the size limit, UTF-8, `Scenario::from_toml`, what an FMU refuses); what it accepts validates,
//! has an instantiation token and round-trips through `to_toml`; an error is one bounded line.
#![no_main]

use beam_impact::fmi::description::token_for;
use beam_impact::fmi::resource::scenario_from_bytes;
use beam_impact::Scenario;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    match scenario_from_bytes(data) {
        Err(e) => assert!(!e.contains('\n') && e.chars().count() <= 700),
        Ok(s) => {
            s.validate().expect("an accepted scenario validates");
            assert!(s.motion.is_unset());
            assert_eq!(token_for(Some(&s)).len(), 38);
            let again =
                Scenario::from_toml(&s.to_toml(), "again.toml").expect("to_toml of an accepted scenario parses");
            assert_eq!(again, s);
        }
    }
});
