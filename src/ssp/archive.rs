//! Writing `GangwayOnVessel.ssp`: a zip holding `SystemStructure.ssd` at its root and the two
//! FMUs under `resources/` (the SSP 1.0 layout), written through the output guard.

use std::io::{Read, Write};
use std::path::{Path, PathBuf};

use zip::write::SimpleFileOptions;
use zip::{CompressionMethod, ZipWriter};

use super::ssd;
use crate::fmi::pack::Platform;
use crate::record::output::{create_output_dir, open_regular_input, OutputFile};
use crate::{Error, Result};

/// The archive's file name.
pub const FILE_NAME: &str = "GangwayOnVessel.ssp";

/// The largest BeamImpact FMU the archive takes, bytes (ours are 10-30 MB).
const MAX_FMU: u64 = 1 << 30;

/// Checks `out_dir/GangwayOnVessel.ssp` and `out_dir` through the output guard
/// ([`crate::record::output::check_output`]), creating nothing: `pack --ssp` checks it before the
/// FMUs are written, so that a link there no longer fails only after both were replaced.
pub fn check_output(out_dir: &Path) -> Result<()> {
    crate::record::output::check_output(&out_dir.join(FILE_NAME), &[out_dir], "cannot create SSP")
}

/// Writes `out_dir/GangwayOnVessel.ssp` from `ssd_text` (the text of [`ssd::system_structure`],
/// made before the FMUs are packed so that a description it cannot be written for stops `pack`
/// early), the BeamImpact FMI 2 FMU at `beam_fmu`, the vessel-motion libraries built for each
/// platform and the vessel's RAO table `raos` (our CSV; the vessel FMU's resource). The archive
/// replaces an earlier one only when complete. Returns its path.
pub fn write_ssp(
    out_dir: &Path,
    ssd_text: &str,
    beam_fmu: &Path,
    vessel_libraries: &[(Platform, PathBuf)],
    raos: &str,
) -> Result<PathBuf> {
    let vessel_fmu = super::vessel::pack_fmu(vessel_libraries, raos)?;
    let what = "cannot read the BeamImpact FMU";
    let mut beam_bytes = Vec::new();
    open_regular_input(beam_fmu, what)?.take(MAX_FMU + 1).read_to_end(&mut beam_bytes).map_err(|source| Error::Io {
        action: what,
        path: beam_fmu.display().to_string(),
        source,
    })?;
    if beam_bytes.len() as u64 > MAX_FMU {
        return Err(Error::Other(format!(
            "{} is larger than {MAX_FMU} bytes: not a BeamImpact FMU",
            beam_fmu.display()
        )));
    }
    create_output_dir(out_dir, "cannot create directory")?;
    let path = out_dir.join(FILE_NAME);
    let file = OutputFile::create(&path, false, "cannot create SSP")?;
    let failed = |e: &dyn std::fmt::Display| Error::Other(format!("cannot write {}: {e}", path.display()));
    let mut zip = ZipWriter::new(file);
    let options = SimpleFileOptions::default().compression_method(CompressionMethod::Deflated);
    // The FMUs are zips already: stored, not compressed again.
    let stored = SimpleFileOptions::default().compression_method(CompressionMethod::Stored);
    for (name, data, options) in [
        ("SystemStructure.ssd", ssd_text.as_bytes(), options),
        (ssd::BEAM_SOURCE, beam_bytes.as_slice(), stored),
        (ssd::VESSEL_SOURCE, vessel_fmu.as_slice(), stored),
    ] {
        zip.start_file(name, options).map_err(|e| failed(&e))?;
        zip.write_all(data).map_err(|e| failed(&e))?;
    }
    zip.finish().map_err(|e| failed(&e))?.commit()?;
    Ok(path)
}
