//! Reading results back: the MCAP reader that is safe on any bytes ([`safe_read`]), `report`
//! (the run's summary rebuilt from a log, [`report`]), the step channel as CSV ([`csv`]) and the
//! figures: Figures 6-9 of a run ([`figures`]), the stress envelope along each beam
//! ([`envelope_figure`]), the mode shapes of Figures 10-12 ([`mode_figures`]) and the damping
//! study's ([`damping_figures`]); the report that opens in a browser ([`html`]: one self-contained
//! HTML page of a run or a sweep). Nothing here writes a log;
//! every file it writes goes through [`crate::record::output`].

pub mod csv;
pub mod damping_figures;
pub mod envelope_figure;
pub mod fatigue;
pub mod figures;
pub mod html;
pub mod mode_figures;
pub mod operability_figure;
pub mod report;
pub mod safe_read;
