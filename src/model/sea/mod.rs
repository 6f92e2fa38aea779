//! The sea (issue 42): a long-crested irregular sea from its significant wave height and peak
//! period, and the vessel's response to it through its motion RAOs, sampled at the two supports'
//! deck points as the supports' motion. Pure: the RAO file's text is parsed here, read elsewhere
//! (`crate::scenario_file`).
//!
//! - [`spectrum`]: the Pierson-Moskowitz and JONSWAP spectra in Hs/Tp form (DNV-RP-C205 3.5.5),
//!   DNV's peak-enhancement rule and the spectral moments;
//! - [`components`]: the wave components a seed picks (splitmix64: the same bits on every
//!   platform) and the elevation at the vessel's motion reference point;
//! - [`raos`]: the RAO table (our CSV and VERES's `.re1`), interpolated between frequencies and
//!   headings; [`raos_write`] the table as our CSV (the vessel FMU's resource);
//! - [`deck_motion`]: deck points and the arrestor's axis, the six motions projected onto the
//!   hinge's heave and the clamp's heave and rotation (small angles);
//! - [`record`]: the supports' motion as the sum of the components, with exact derivatives, and
//!   its samples as the motion table the solver already takes;
//! - [`settings`]: the scenario's `[sea]` section (fields, defaults, ranges); [`fields`] the same
//!   fields as `--set` / `--vary` parameters.
//!
//! Trigonometric and exponential functions come from the `libm` crate (pure Rust), as elsewhere
//! in the physics: a seed gives the same record to the bit on every platform.

pub mod components;
pub mod deck_motion;
pub mod fields;
pub mod raos;
pub mod raos_write;
pub mod record;
pub mod settings;
pub mod spectrum;

pub use components::WaveComponents;
pub use deck_motion::DeckPoints;
pub use raos::RaoTable;
pub use record::SeaRecord;
pub use settings::SeaSettings;
pub use spectrum::{Spectrum, SpectrumKind};
