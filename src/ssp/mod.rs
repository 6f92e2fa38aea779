//! The gangway on a vessel as an SSP 1.0 archive (issue 31, item 1): `beam-impact pack --ssp`
//! writes `GangwayOnVessel.ssp` beside the FMUs, holding `SystemStructure.ssd` ([`ssd`]), the
//! BeamImpact FMU (FMI 2.0) and the vessel-motion FMU ([`vessel`], built from its C source for the
//! same platforms), so that system tools that run FMI 2.0 co-simulation only inside an SSP
//! (libcosim, Ecos, fmpy's `simulate_ssp`) run the coupled example. No `unsafe` and no process:
//! the CLI builds the libraries and hands their paths here ([`archive`]).

pub mod archive;
pub mod ssd;
pub mod vessel;
