//! Writes the two FMUs: `out_root/fmi2/BeamImpact.fmu` and `out_root/fmi3/BeamImpact.fmu`, each
//! with its modelDescription.xml, the shared library under the platform directory its standard
//! names, and `documentation/` (the repository's `fmu/documentation/`).

use std::io::Write;
use std::path::{Path, PathBuf};

use zip::write::SimpleFileOptions;
use zip::{CompressionMethod, ZipWriter};

use super::description::{self, MODEL_IDENTIFIER};
use crate::error::{Error, Result};

/// The documentation directory: `fmu/documentation/` of the repository this crate was built from,
/// or of the working directory if that one is gone.
pub fn documentation_dir() -> PathBuf {
    let built = Path::new(env!("CARGO_MANIFEST_DIR")).join("fmu").join("documentation");
    if built.is_dir() {
        built
    } else {
        PathBuf::from("fmu/documentation")
    }
}

fn io<'a>(action: &'static str, path: &'a Path) -> impl FnOnce(std::io::Error) -> Error + 'a {
    move |source| Error::Io { action, path: path.display().to_string(), source }
}

fn zip_error(path: &Path) -> impl FnOnce(zip::result::ZipError) -> Error + '_ {
    move |e| Error::Other(format!("cannot write FMU {}: {e}", path.display()))
}

/// Every file under `dir` as (path inside `documentation/`, absolute path), sorted.
fn documentation_files(dir: &Path) -> Result<Vec<(String, PathBuf)>> {
    let mut files = Vec::new();
    let mut pending = vec![(String::new(), dir.to_path_buf())];
    while let Some((prefix, path)) = pending.pop() {
        for entry in std::fs::read_dir(&path).map_err(io("cannot read documentation directory", &path))? {
            let entry = entry.map_err(io("cannot read documentation directory", &path))?;
            let name = format!("{prefix}{}", entry.file_name().to_string_lossy());
            if entry.path().is_dir() {
                pending.push((format!("{name}/"), entry.path()));
            } else {
                files.push((name, entry.path()));
            }
        }
    }
    files.sort();
    Ok(files)
}

fn write_fmu(fmu: &Path, xml: &str, platform: &str, library: &[u8], docs: &[(String, PathBuf)]) -> Result<()> {
    if let Some(parent) = fmu.parent() {
        // Never into a folder that is a symbolic link (the output guard's rule for folders).
        crate::record::output::create_output_dir(parent, "cannot create directory")?;
    }
    let file = crate::record::output::OutputFile::create(fmu, false, "cannot create FMU")?;
    let mut zip = ZipWriter::new(file);
    let options = SimpleFileOptions::default().compression_method(CompressionMethod::Deflated);
    zip.start_file("modelDescription.xml", options).map_err(zip_error(fmu))?;
    zip.write_all(xml.as_bytes()).map_err(io("cannot write FMU", fmu))?;
    zip.start_file(format!("binaries/{platform}/{MODEL_IDENTIFIER}.so"), options.unix_permissions(0o755))
        .map_err(zip_error(fmu))?;
    zip.write_all(library).map_err(io("cannot write FMU", fmu))?;
    for (name, path) in docs {
        let data = std::fs::read(path).map_err(io("cannot read", path))?;
        zip.start_file(format!("documentation/{name}"), options).map_err(zip_error(fmu))?;
        zip.write_all(&data).map_err(io("cannot write FMU", fmu))?;
    }
    // Complete: the FMU replaces an earlier one only now.
    zip.finish().map_err(zip_error(fmu))?.commit()
}

/// The entry points an importer looks up first, as they stand in the dynamic string table.
const ENTRY_POINTS: [&[u8]; 2] = [b"\0fmi2Instantiate\0", b"\0fmi3InstantiateCoSimulation\0"];

/// Checks that `binary` is what an FMU must carry: a 64-bit little-endian x86-64 ELF shared
/// object (e_type ET_DYN) that names the FMI 2 and FMI 3 entry points.
pub fn check_library(binary: &[u8]) -> std::result::Result<(), String> {
    if binary.len() < 64 || &binary[..4] != b"\x7fELF" {
        return Err(format!("not an ELF file ({} bytes, no ELF magic)", binary.len()));
    }
    let (class, data) = (binary[4], binary[5]);
    let e_type = u16::from_le_bytes([binary[16], binary[17]]);
    let machine = u16::from_le_bytes([binary[18], binary[19]]);
    if class != 2 || data != 1 || machine != 62 {
        return Err(format!("not a 64-bit little-endian x86-64 ELF (class {class}, data {data}, machine {machine})"));
    }
    if e_type != 3 {
        return Err(format!("not a shared object (ELF type {e_type}, a shared object is 3)"));
    }
    for name in ENTRY_POINTS {
        if !binary.windows(name.len()).any(|w| w == name) {
            let shown = String::from_utf8_lossy(&name[1..name.len() - 1]).into_owned();
            return Err(format!("it does not export {shown}: not the beam-impact library"));
        }
    }
    Ok(())
}

/// Packs `library` (the crate's `libbeam_impact.so`, checked by [`check_library`]) into both FMUs
/// under `out_root`; returns their paths.
pub fn pack(library: &Path, out_root: &Path) -> Result<Vec<PathBuf>> {
    let binary = {
        use std::io::Read;
        // A regular file only (a FIFO would block, a device never end), at most 1 GiB.
        let file = crate::record::output::open_regular_input(library, "cannot read the shared library to pack")?;
        let mut bytes = Vec::new();
        file.take(1 << 30).read_to_end(&mut bytes).map_err(io("cannot read the shared library to pack", library))?;
        bytes
    };
    check_library(&binary).map_err(|why| Error::Other(format!("{} cannot be packed: {why}", library.display())))?;
    let docs = documentation_files(&documentation_dir())?;
    if !docs.iter().any(|(name, _)| name == "index.html") {
        return Err(Error::Other(format!(
            "{} has no index.html (the FMU's main documentation page)",
            documentation_dir().display()
        )));
    }
    // Created only once everything is checked (a refused library leaves no folder).
    crate::record::output::create_output_dir(out_root, "cannot create directory")?;
    let fmi2 = out_root.join("fmi2").join(format!("{MODEL_IDENTIFIER}.fmu"));
    let fmi3 = out_root.join("fmi3").join(format!("{MODEL_IDENTIFIER}.fmu"));
    write_fmu(&fmi2, &description::fmi2(), "linux64", &binary, &docs)?;
    write_fmu(&fmi3, &description::fmi3(), "x86_64-linux", &binary, &docs)?;
    Ok(vec![fmi2, fmi3])
}
