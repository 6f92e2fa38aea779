//! FMI 2.0 and 3.0 co-simulation export: all of the crate's unsafe code lives here.
//!
//! - [`boundary`]: the panic boundary every exported body runs in, and the pointer checks.
//! - [`status`]: status codes, the state enum and the allowed-states table per function.
//! - [`variables`]: the variable table (value references, names, units, start values).
//! - [`instance`]: one instance: parameters, simulation, MCAP log, state machine.
//! - [`logger`]: the importer's logging callbacks (their C types) and the call into them.
//! - [`fmi2`], [`fmi3`]: the exported C functions; they check arguments and delegate.
//! - [`state`]: FMU state snapshots and their portable byte format; [`slots`]: the importer's handles to them.
//! - [`resource`]: resource-location parsing and the starting scenario an FMU may carry
//!   (`resources/scenario.toml`, written by `pack --scenario`).
//! - [`description`]: the two modelDescription.xml files, generated from the table.
//! - [`pack`]: writes the two .fmu archives (one binary per platform); [`reference`](mod@reference): the paper
//!   scenario run through an instance, their reference results; [`documentation`]: their
//!   `documentation/index.html` and figures.

pub mod boundary;
pub mod description;
pub mod documentation;
pub mod fmi2;
pub mod fmi3;
pub mod instance;
pub mod logger;
pub mod pack;
pub mod packed_scenario;
pub mod reference;
pub mod resource;
pub mod slots;
pub mod state;
pub mod status;
pub mod variables;
