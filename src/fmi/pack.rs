//! Writes the two FMUs: `out_root/fmi2/BeamImpact.fmu` and `out_root/fmi3/BeamImpact.fmu`, each
//! with its modelDescription.xml, one binary per platform under the directory its standard names
//! (FMI 2: `linux64`, `win64`, `darwin64`; FMI 3: `x86_64-linux`, `x86_64-windows`,
//! `x86_64-darwin`, `aarch64-darwin`), `documentation/` (the repository's `fmu/documentation/`,
//! its `index.html` completed by [`super::documentation`]), the reference results in `extra/`
//! and, packed with a scenario of its own (issue 30), `resources/scenario.toml`.

use std::io::Write;
use std::path::{Path, PathBuf};

use std::ops::Range;
use zip::write::SimpleFileOptions;
use zip::{CompressionMethod, ZipWriter};

use super::description::{self, MODEL_IDENTIFIER};
pub use super::packed_scenario::PackedScenario;
use super::reference::{reference_run_from, REFERENCE_CSV};
use super::resource::SCENARIO_RESOURCE;
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
            let kind = entry.file_type().map_err(io("cannot read documentation directory", &path))?;
            // A link could point anywhere (or loop): the documentation is packed as it stands.
            if kind.is_symlink() {
                return Err(Error::Other(format!(
                    "{} is a symbolic link: the FMU's documentation takes regular files and folders only",
                    entry.path().display()
                )));
            }
            if kind.is_dir() {
                pending.push((format!("{name}/"), entry.path()));
            } else {
                files.push((name, entry.path()));
            }
        }
    }
    files.sort();
    Ok(files)
}

/// A platform an FMU carries a binary for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Platform {
    /// Linux x86-64: an ELF shared object (glibc 2.17 when built by `pack`).
    Linux,
    /// Windows x86-64: a DLL.
    Windows,
    /// macOS: a universal2 Mach-O dylib (x86-64 and arm64 slices).
    Darwin,
}

impl Platform {
    /// Every platform, in the order the FMUs list them.
    pub const ALL: [Platform; 3] = [Platform::Linux, Platform::Windows, Platform::Darwin];

    /// The name `pack --platforms` takes.
    pub fn name(self) -> &'static str {
        match self {
            Platform::Linux => "linux",
            Platform::Windows => "windows",
            Platform::Darwin => "darwin",
        }
    }

    /// The binary's file extension.
    pub fn extension(self) -> &'static str {
        match self {
            Platform::Linux => "so",
            Platform::Windows => "dll",
            Platform::Darwin => "dylib",
        }
    }

    /// The FMI 2.0 platform directory (one per platform: macOS's is the universal2 binary).
    pub fn fmi2_dir(self) -> &'static str {
        match self {
            Platform::Linux => "linux64",
            Platform::Windows => "win64",
            Platform::Darwin => "darwin64",
        }
    }

    /// `all` (also inside a list), or a comma-separated list of names (`linux,windows`), in
    /// [`Platform::ALL`] order without repeats; an unknown or empty name is an error naming it.
    pub fn parse_list(list: &str) -> Result<Vec<Platform>> {
        if list.split(',').any(|name| name.trim() == "all") {
            return Ok(Platform::ALL.to_vec());
        }
        let mut platforms = Vec::new();
        for name in list.split(',').map(str::trim) {
            let platform = Platform::ALL.into_iter().find(|p| p.name() == name).ok_or_else(|| {
                Error::Other(format!(
                    "--platforms: unknown platform `{name}` in `{list}` (known: linux, windows, darwin, or all)"
                ))
            })?;
            platforms.push(platform);
        }
        platforms.sort();
        platforms.dedup();
        Ok(platforms)
    }
}

/// One file of an FMU: its path inside the archive, its bytes, whether it is executable.
struct Entry {
    name: String,
    data: Vec<u8>,
    executable: bool,
}

fn write_fmu(fmu: &Path, entries: &[Entry]) -> Result<()> {
    if let Some(parent) = fmu.parent() {
        // Never into a folder that is a symbolic link (the output guard's rule for folders).
        crate::record::output::create_output_dir(parent, "cannot create directory")?;
    }
    let file = crate::record::output::OutputFile::create(fmu, false, "cannot create FMU")?;
    let mut zip = ZipWriter::new(file);
    let options = SimpleFileOptions::default().compression_method(CompressionMethod::Deflated);
    for entry in entries {
        let options = if entry.executable { options.unix_permissions(0o755) } else { options };
        zip.start_file(entry.name.as_str(), options).map_err(zip_error(fmu))?;
        zip.write_all(&entry.data).map_err(io("cannot write FMU", fmu))?;
    }
    // Complete: the FMU replaces an earlier one only now.
    zip.finish().map_err(zip_error(fmu))?.commit()
}

/// The entry points an importer looks up first, as they stand in the ELF and PE name tables.
const ENTRY_POINTS: [&[u8]; 2] = [b"\0fmi2Instantiate\0", b"\0fmi3InstantiateCoSimulation\0"];
/// ... and in a Mach-O string table (C names take a leading underscore there).
const MACHO_ENTRY_POINTS: [&[u8]; 2] = [b"\0_fmi2Instantiate\0", b"\0_fmi3InstantiateCoSimulation\0"];

fn names_entry_points(binary: &[u8], names: &[&[u8]]) -> std::result::Result<(), String> {
    for name in names {
        if !binary.windows(name.len()).any(|w| w == *name) {
            let shown = String::from_utf8_lossy(&name[1..name.len() - 1]).into_owned();
            return Err(format!("it does not export {shown}: not the beam-impact library"));
        }
    }
    Ok(())
}

fn u16_le(b: &[u8], at: usize) -> Option<u16> {
    Some(u16::from_le_bytes(b.get(at..at + 2)?.try_into().ok()?))
}

fn u32_le(b: &[u8], at: usize) -> Option<u32> {
    Some(u32::from_le_bytes(b.get(at..at + 4)?.try_into().ok()?))
}

fn u32_be(b: &[u8], at: usize) -> Option<u32> {
    Some(u32::from_be_bytes(b.get(at..at + 4)?.try_into().ok()?))
}

/// Checks that `binary` is what an FMU must carry on Linux: a 64-bit little-endian x86-64 ELF
/// shared object (e_type ET_DYN) that names the FMI 2 and FMI 3 entry points.
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
    names_entry_points(binary, &ENTRY_POINTS)
}

/// The FMI functions the library exports: every `extern "C" fn fmi2*` / `fmi3*` in `src/fmi`, the
/// list `scripts/cross-build.sh` derives from the source and requires of the DLL it builds
/// (`tests/fmi_pack.rs` holds this copy to the source).
pub const FMI_FUNCTIONS: [&str; 109] = [
    "fmi2CancelStep",
    "fmi2DeSerializeFMUstate",
    "fmi2DoStep",
    "fmi2EnterInitializationMode",
    "fmi2ExitInitializationMode",
    "fmi2FreeFMUstate",
    "fmi2FreeInstance",
    "fmi2GetBoolean",
    "fmi2GetBooleanStatus",
    "fmi2GetDirectionalDerivative",
    "fmi2GetFMUstate",
    "fmi2GetInteger",
    "fmi2GetIntegerStatus",
    "fmi2GetReal",
    "fmi2GetRealOutputDerivatives",
    "fmi2GetRealStatus",
    "fmi2GetStatus",
    "fmi2GetString",
    "fmi2GetStringStatus",
    "fmi2GetTypesPlatform",
    "fmi2GetVersion",
    "fmi2Instantiate",
    "fmi2Reset",
    "fmi2SerializeFMUstate",
    "fmi2SerializedFMUstateSize",
    "fmi2SetBoolean",
    "fmi2SetDebugLogging",
    "fmi2SetFMUstate",
    "fmi2SetInteger",
    "fmi2SetReal",
    "fmi2SetRealInputDerivatives",
    "fmi2SetString",
    "fmi2SetupExperiment",
    "fmi2Terminate",
    "fmi3ActivateModelPartition",
    "fmi3CompletedIntegratorStep",
    "fmi3DeserializeFMUState",
    "fmi3DoStep",
    "fmi3EnterConfigurationMode",
    "fmi3EnterContinuousTimeMode",
    "fmi3EnterEventMode",
    "fmi3EnterInitializationMode",
    "fmi3EnterStepMode",
    "fmi3EvaluateDiscreteStates",
    "fmi3ExitConfigurationMode",
    "fmi3ExitInitializationMode",
    "fmi3FreeFMUState",
    "fmi3FreeInstance",
    "fmi3GetAdjointDerivative",
    "fmi3GetBinary",
    "fmi3GetBoolean",
    "fmi3GetClock",
    "fmi3GetContinuousStateDerivatives",
    "fmi3GetContinuousStates",
    "fmi3GetDirectionalDerivative",
    "fmi3GetEventIndicators",
    "fmi3GetFMUState",
    "fmi3GetFloat32",
    "fmi3GetFloat64",
    "fmi3GetInt16",
    "fmi3GetInt32",
    "fmi3GetInt64",
    "fmi3GetInt8",
    "fmi3GetIntervalDecimal",
    "fmi3GetIntervalFraction",
    "fmi3GetNominalsOfContinuousStates",
    "fmi3GetNumberOfContinuousStates",
    "fmi3GetNumberOfEventIndicators",
    "fmi3GetNumberOfVariableDependencies",
    "fmi3GetOutputDerivatives",
    "fmi3GetShiftDecimal",
    "fmi3GetShiftFraction",
    "fmi3GetString",
    "fmi3GetUInt16",
    "fmi3GetUInt32",
    "fmi3GetUInt64",
    "fmi3GetUInt8",
    "fmi3GetVariableDependencies",
    "fmi3GetVersion",
    "fmi3InstantiateCoSimulation",
    "fmi3InstantiateModelExchange",
    "fmi3InstantiateScheduledExecution",
    "fmi3Reset",
    "fmi3SerializeFMUState",
    "fmi3SerializedFMUStateSize",
    "fmi3SetBinary",
    "fmi3SetBoolean",
    "fmi3SetClock",
    "fmi3SetContinuousStates",
    "fmi3SetDebugLogging",
    "fmi3SetFMUState",
    "fmi3SetFloat32",
    "fmi3SetFloat64",
    "fmi3SetInt16",
    "fmi3SetInt32",
    "fmi3SetInt64",
    "fmi3SetInt8",
    "fmi3SetIntervalDecimal",
    "fmi3SetIntervalFraction",
    "fmi3SetShiftDecimal",
    "fmi3SetShiftFraction",
    "fmi3SetString",
    "fmi3SetTime",
    "fmi3SetUInt16",
    "fmi3SetUInt32",
    "fmi3SetUInt64",
    "fmi3SetUInt8",
    "fmi3Terminate",
    "fmi3UpdateDiscreteStates",
];

/// The most sections a PE image has (the Windows loader's limit).
const MAX_PE_SECTIONS: u16 = 96;

/// The most names an export directory may list here (ours lists 109; a DLL linked without an
/// export list, such as zig's, a few thousand).
const MAX_PE_EXPORTS: u32 = 1 << 20;

/// The longest export name read, bytes.
const MAX_EXPORT_NAME: usize = 512;

/// The names a PE32+ image exports (the name table of its export directory), `pe` being the offset
/// of its `PE\0\0` signature. Every count and offset is checked against the file before it is
/// used: a header that lies (65535 sections, a table beyond the file) is refused with a reason.
pub fn pe_exports(binary: &[u8], pe: usize) -> std::result::Result<Vec<String>, String> {
    let cut = || format!("a PE header cut short ({} bytes)", binary.len());
    let sections = u16_le(binary, pe + 6).ok_or_else(cut)?;
    if !(1..=MAX_PE_SECTIONS).contains(&sections) {
        return Err(format!("a PE header with {sections} sections (an image has 1 to {MAX_PE_SECTIONS})"));
    }
    let optional_size = usize::from(u16_le(binary, pe + 20).ok_or_else(cut)?);
    let optional = pe + 24;
    let magic = u16_le(binary, optional).ok_or_else(cut)?;
    if magic != 0x20b {
        return Err(format!("not a PE32+ image (optional header magic 0x{magic:04x}, PE32+ is 0x020b)"));
    }
    // PE32+: 112 bytes of fields (the count of data directories at 108), then the directories,
    // the export directory's first.
    let directories = u32_le(binary, optional + 108).ok_or_else(cut)?;
    if optional_size < 120 || directories == 0 {
        return Err(format!(
            "the PE optional header has no export directory ({optional_size} bytes, {directories} data directories)"
        ));
    }
    let table = optional + optional_size;
    let table_end = table + 40 * usize::from(sections);
    if table_end > binary.len() {
        return Err(format!(
            "the PE section table (bytes {table}..{table_end}) lies beyond the file ({} bytes)",
            binary.len()
        ));
    }
    // Each section's (virtual address, raw size, raw offset); its raw data must lie in the file.
    let mut raw = Vec::with_capacity(usize::from(sections));
    for k in 0..usize::from(sections) {
        let at = table + 40 * k;
        let (va, size, offset) = (u32_le(binary, at + 12), u32_le(binary, at + 16), u32_le(binary, at + 20));
        let (Some(va), Some(size), Some(offset)) = (va, size, offset) else { return Err(cut()) };
        let (size, offset) = (u64::from(size), u64::from(offset));
        if size > 0 && offset + size > binary.len() as u64 {
            return Err(format!(
                "PE section {k}'s data (bytes {offset}..{}) lies beyond the file ({} bytes)",
                offset + size,
                binary.len()
            ));
        }
        raw.push((u64::from(va), size, offset));
    }
    // The file offset of `len` bytes at `rva`, inside one section's raw data.
    let offset_of = |rva: u32, len: u64| -> Option<usize> {
        let rva = u64::from(rva);
        raw.iter()
            .find(|&&(va, size, _)| rva >= va && rva - va + len <= size)
            .and_then(|&(va, _, offset)| usize::try_from(offset + (rva - va)).ok())
    };
    let export_rva = u32_le(binary, optional + 112).ok_or_else(cut)?;
    if export_rva == 0 {
        return Err("it has no export directory: it exports no function".into());
    }
    let directory = offset_of(export_rva, 40)
        .ok_or_else(|| format!("its export directory (RVA 0x{export_rva:x}) lies outside the file's sections"))?;
    let (Some(count), Some(names_rva)) = (u32_le(binary, directory + 24), u32_le(binary, directory + 32)) else {
        return Err(cut());
    };
    if count > MAX_PE_EXPORTS {
        return Err(format!("its export directory lists {count} names (more than {MAX_PE_EXPORTS})"));
    }
    let names = offset_of(names_rva, 4 * u64::from(count)).ok_or_else(|| {
        format!("its export name table ({count} names at RVA 0x{names_rva:x}) lies outside the file's sections")
    })?;
    let mut exports = Vec::with_capacity(count as usize);
    for k in 0..count as usize {
        let rva = u32_le(binary, names + 4 * k).ok_or_else(cut)?;
        let start = offset_of(rva, 1)
            .ok_or_else(|| format!("export name {k} (RVA 0x{rva:x}) lies outside the file's sections"))?;
        let text = &binary[start..binary.len().min(start + MAX_EXPORT_NAME + 1)];
        let end = text
            .iter()
            .position(|&b| b == 0)
            .ok_or_else(|| format!("export name {k} is not ended within {MAX_EXPORT_NAME} bytes"))?;
        exports.push(String::from_utf8_lossy(&text[..end]).into_owned());
    }
    Ok(exports)
}

/// Checks that the exported `names` include every one of [`FMI_FUNCTIONS`].
fn exports_fmi_functions(names: &[String]) -> std::result::Result<(), String> {
    let exported: std::collections::HashSet<&str> = names.iter().map(String::as_str).collect();
    let missing: Vec<&str> = FMI_FUNCTIONS.iter().copied().filter(|f| !exported.contains(f)).collect();
    if missing.is_empty() {
        return Ok(());
    }
    let shown = missing.iter().take(3).copied().collect::<Vec<_>>().join(", ");
    let more = if missing.len() > 3 { format!(" and {} more", missing.len() - 3) } else { String::new() };
    Err(format!(
        "it exports {} of the {} FMI functions ({} names in all), not {shown}{more}: not the beam-impact library",
        FMI_FUNCTIONS.len() - missing.len(),
        FMI_FUNCTIONS.len(),
        names.len()
    ))
}

/// Checks that `binary` is a Windows x86-64 DLL (PE32+, machine AMD64, IMAGE_FILE_DLL) whose export
/// directory names every one of [`FMI_FUNCTIONS`] (issue 27; read by [`pe_exports`], its headers
/// bounded by the file). Its imports, and that it exports nothing else, are checked where it is
/// built, `scripts/cross-build.sh`.
pub fn check_dll(binary: &[u8]) -> std::result::Result<(), String> {
    if binary.get(..2) != Some(b"MZ") {
        return Err(format!("not a Windows DLL ({} bytes, no MZ header)", binary.len()));
    }
    let pe = u32_le(binary, 0x3c)
        .and_then(|p| usize::try_from(p).ok())
        .filter(|&p| p.checked_add(4).and_then(|end| binary.get(p..end)) == Some(b"PE\0\0"));
    let Some(pe) = pe else { return Err("not a Windows DLL (no PE signature)".into()) };
    let machine = u16_le(binary, pe + 4).unwrap_or(0);
    let characteristics = u16_le(binary, pe + 22).unwrap_or(0);
    if machine != 0x8664 {
        return Err(format!("not an x86-64 PE file (machine 0x{machine:04x}, x86-64 is 0x8664)"));
    }
    if characteristics & 0x2000 == 0 {
        return Err("a PE file but not a DLL (IMAGE_FILE_DLL not set)".into());
    }
    exports_fmi_functions(&pe_exports(binary, pe)?)
}

/// Mach-O CPU types of the two slices of a universal2 binary, with the FMI 3.0 platform
/// directory of each.
const MACHO_SLICES: [(u32, &str); 2] = [(0x0100_0007, "x86_64-darwin"), (0x0100_000c, "aarch64-darwin")];

/// Checks that `binary` is a universal2 Mach-O (a fat file holding an x86-64 and an arm64
/// 64-bit dylib, MH_DYLIB, each naming the FMI entry points); returns each slice's FMI 3.0
/// platform directory and byte range. (Exports, linked libraries and code signatures are
/// checked where it is built, `scripts/cross-build.sh`.)
pub fn check_universal_dylib(binary: &[u8]) -> std::result::Result<Vec<(&'static str, Range<usize>)>, String> {
    if u32_be(binary, 0) != Some(0xcafe_babe) {
        return Err(format!(
            "not a universal (fat) Mach-O file ({} bytes, no 0xcafebabe magic): pack a universal2 dylib",
            binary.len()
        ));
    }
    let count = u32_be(binary, 4).unwrap_or(0) as usize;
    if !(1..=8).contains(&count) {
        return Err(format!("a fat Mach-O header with {count} architectures"));
    }
    let mut slices = Vec::new();
    for k in 0..count {
        let at = 8 + 20 * k;
        let (Some(cpu), Some(offset), Some(size)) =
            (u32_be(binary, at), u32_be(binary, at + 8), u32_be(binary, at + 12))
        else {
            return Err("a fat Mach-O header cut short".into());
        };
        // u64: no overflow of offset + size on any host.
        let (start, end) = (u64::from(offset), u64::from(offset) + u64::from(size));
        let range = usize::try_from(start).unwrap_or(usize::MAX)..usize::try_from(end).unwrap_or(usize::MAX);
        let slice = binary.get(range.clone()).ok_or(format!(
            "architecture {k} of the fat Mach-O lies beyond the file (bytes {}..{} of {})",
            range.start,
            range.end,
            binary.len()
        ))?;
        if u32_le(slice, 0) != Some(0xfeed_facf) || u32_le(slice, 4) != Some(cpu) {
            return Err(format!("architecture {k} of the fat Mach-O is not a 64-bit Mach-O of CPU type 0x{cpu:08x}"));
        }
        let file_type = u32_le(slice, 12).unwrap_or(0);
        if file_type != 6 {
            return Err(format!("architecture {k} is not a dylib (Mach-O file type {file_type}, MH_DYLIB is 6)"));
        }
        names_entry_points(slice, &MACHO_ENTRY_POINTS)?;
        if let Some(&(_, dir)) = MACHO_SLICES.iter().find(|(c, _)| *c == cpu) {
            if slices.iter().any(|(d, _)| *d == dir) {
                return Err(format!("the fat Mach-O has two {dir} slices (CPU type 0x{cpu:08x})"));
            }
            slices.push((dir, range));
        }
    }
    for (cpu, dir) in MACHO_SLICES {
        if !slices.iter().any(|(d, _)| *d == dir) {
            return Err(format!("the fat Mach-O has no {dir} slice (CPU type 0x{cpu:08x}): pack a universal2 dylib"));
        }
    }
    Ok(slices)
}

/// The largest binary `pack` reads, bytes (ours are 3-7 MB).
pub const MAX_BINARY: u64 = 1 << 30;

/// Opens a binary to pack and checks it before anything of it is read (issue 27): a regular file
/// (a FIFO would block, a device never end) of at most [`MAX_BINARY`] bytes by its metadata, so
/// that a huge or sparse file is refused at once. Returns the open file and its size.
fn open_binary(path: &Path) -> Result<(std::fs::File, u64)> {
    let what = "cannot read the shared library to pack";
    let file = crate::record::output::open_regular_input(path, what)?;
    let size = file.metadata().map_err(io(what, path))?.len();
    if size > MAX_BINARY {
        return Err(Error::Other(format!(
            "{} cannot be packed: {size} bytes, larger than {MAX_BINARY} (not the beam-impact library)",
            path.display()
        )));
    }
    Ok((file, size))
}

/// Checks a binary given to `pack` without reading it: a regular file of at most [`MAX_BINARY`]
/// bytes by its metadata; returns its size. The CLI calls it for every file given before it
/// builds anything.
pub fn check_binary_file(path: &Path) -> Result<u64> {
    open_binary(path).map(|(_, size)| size)
}

/// Reads a binary to pack, checked first by [`open_binary`]; at most [`MAX_BINARY`] bytes are
/// read even if the file grows meanwhile (a larger file is refused, not cut).
fn read_binary(path: &Path) -> Result<Vec<u8>> {
    use std::io::Read;
    let (file, size) = open_binary(path)?;
    let mut bytes = Vec::with_capacity(usize::try_from(size).unwrap_or(0));
    file.take(MAX_BINARY + 1).read_to_end(&mut bytes).map_err(io("cannot read the shared library to pack", path))?;
    if bytes.len() as u64 > MAX_BINARY {
        return Err(Error::Other(format!(
            "{} cannot be packed: larger than {MAX_BINARY} bytes (not the beam-impact library)",
            path.display()
        )));
    }
    Ok(bytes)
}

/// The newest glibc symbol version an ELF library names (`GLIBC_2.17` gives (2, 17)).
pub fn glibc_needed(binary: &[u8]) -> Option<(u32, u32)> {
    const TAG: &[u8] = b"GLIBC_2.";
    let mut newest = None;
    let mut at = 0;
    while let Some(found) = binary[at..].windows(TAG.len()).position(|w| w == TAG) {
        let digits = &binary[at + found + TAG.len()..];
        let end = digits.iter().position(|b| !b.is_ascii_digit()).unwrap_or(digits.len());
        if let Some(minor) = std::str::from_utf8(&digits[..end]).ok().and_then(|d| d.parse::<u32>().ok()) {
            newest = newest.max(Some((2, minor)));
        }
        at += found + TAG.len();
    }
    newest
}

/// The binary files of each FMU for one checked binary: (FMI 2 entries, FMI 3 entries, what the
/// documentation page says of it).
fn binary_entries(platform: Platform, path: &Path) -> Result<(Vec<Entry>, Vec<Entry>, String)> {
    let bytes = read_binary(path)?;
    let refuse = |why: String| {
        Error::Other(format!("{} cannot be packed as the {} binary: {why}", path.display(), platform.name()))
    };
    let file = format!("{MODEL_IDENTIFIER}.{}", platform.extension());
    let entry = |dir: &str, data: Vec<u8>| Entry { name: format!("binaries/{dir}/{file}"), data, executable: true };
    let mut what = match platform {
        Platform::Linux => "Linux x86-64 shared library".to_string(),
        Platform::Windows => "Windows x86-64 DLL".to_string(),
        Platform::Darwin => {
            "macOS universal2 dylib, x86-64 and arm64 (never loaded on macOS by the project's tests)".to_string()
        }
    };
    let fmi3 = match platform {
        Platform::Linux => {
            check_library(&bytes).map_err(refuse)?;
            if let Some((major, minor)) = glibc_needed(&bytes) {
                what = format!("{what} (needs glibc {major}.{minor} or later)");
            }
            vec![entry("x86_64-linux", bytes.clone())]
        }
        Platform::Windows => {
            check_dll(&bytes).map_err(refuse)?;
            vec![entry("x86_64-windows", bytes.clone())]
        }
        // FMI 3 has one directory per architecture: each gets its own slice (a thin dylib).
        Platform::Darwin => check_universal_dylib(&bytes)
            .map_err(refuse)?
            .into_iter()
            .map(|(dir, range)| entry(dir, bytes[range].to_vec()))
            .collect(),
    };
    Ok((vec![entry(platform.fmi2_dir(), bytes)], fmi3, what))
}

/// Packs the binaries (one per platform, each checked for its platform: [`check_library`],
/// [`check_dll`], [`check_universal_dylib`]) into both FMUs under `out_root`, with
/// `generation_tool` in their descriptions ([`description::generation_tool`]), the completed
/// documentation and the reference results; returns the two FMUs' paths.
pub fn pack_platforms(
    binaries: &[(Platform, PathBuf)],
    out_root: &Path,
    generation_tool: &str,
) -> Result<Vec<PathBuf>> {
    pack_platforms_with(binaries, out_root, generation_tool, None)
}

/// The FMUs [`pack_platforms`] writes under `out_root`: `fmi2/BeamImpact.fmu` and
/// `fmi3/BeamImpact.fmu`.
pub fn fmu_paths(out_root: &Path) -> [PathBuf; 2] {
    ["fmi2", "fmi3"].map(|version| out_root.join(version).join(format!("{MODEL_IDENTIFIER}.fmu")))
}

/// Checks both FMUs' outputs under `out_root` and the folders on their way through the output
/// guard ([`crate::record::output::check_output`]) before either is written: a link at
/// `fmi3/BeamImpact.fmu` no longer fails only after `fmi2/BeamImpact.fmu` was replaced.
pub fn check_outputs(out_root: &Path) -> Result<()> {
    for fmu in fmu_paths(out_root) {
        let folders = [out_root, fmu.parent().unwrap_or(out_root)];
        crate::record::output::check_output(&fmu, &folders, "cannot create FMU")?;
    }
    Ok(())
}

/// [`pack_platforms`] with a starting scenario of the FMUs' own (issue 30; `None`: the paper
/// scenario): packed as `resources/scenario.toml`, its values the descriptions' start values (and
/// their token its), the reference results and the documentation its.
pub fn pack_platforms_with(
    binaries: &[(Platform, PathBuf)],
    out_root: &Path,
    generation_tool: &str,
    packed: Option<&PackedScenario>,
) -> Result<Vec<PathBuf>> {
    if binaries.is_empty() {
        return Err(Error::Other("no binary to pack".into()));
    }
    let mut fmi2_binaries = Vec::new();
    let mut fmi3_binaries = Vec::new();
    let mut platforms: Vec<(Platform, String)> = Vec::new();
    for (platform, path) in binaries {
        if platforms.iter().any(|(p, _)| p == platform) {
            return Err(Error::Other(format!("two {} binaries to pack (one per platform)", platform.name())));
        }
        let (two, three, what) = binary_entries(*platform, path)?;
        fmi2_binaries.extend(two);
        fmi3_binaries.extend(three);
        platforms.push((*platform, what));
    }
    platforms.sort();
    // What the documentation page lists: each FMI version's directories with what is in them.
    let listed = |fmi3: bool| -> Vec<(String, String)> {
        platforms
            .iter()
            .map(|(p, what)| {
                let dir = match (p, fmi3) {
                    (Platform::Darwin, true) => "x86_64-darwin, aarch64-darwin".to_string(),
                    (Platform::Linux, true) => "x86_64-linux".to_string(),
                    (Platform::Windows, true) => "x86_64-windows".to_string(),
                    (p, false) => p.fmi2_dir().to_string(),
                };
                (dir, what.clone())
            })
            .collect()
    };
    let dir = documentation_dir();
    let docs = documentation_files(&dir)?;
    let template = docs
        .iter()
        .find(|(name, _)| name == "index.html")
        .map(|(_, path)| std::fs::read_to_string(path).map_err(io("cannot read", path)))
        .transpose()?
        .ok_or_else(|| {
            Error::Other(format!("{} has no index.html (the FMU's main documentation page)", dir.display()))
        })?;
    // The reference results and the documentation come from runs of this build's model: its
    // starting scenario's, and for Table 1 the paper's with its method (an FMU of the paper's).
    let scenario = packed.map(|p| &p.scenario);
    let reference = reference_run_from(scenario, &[]).map_err(Error::Other)?;
    let paper = match packed {
        None => Some(reference_run_from(None, &[("method", 1)]).map_err(Error::Other)?),
        Some(_) => None,
    };
    let figures = super::documentation::figures(&reference).map_err(Error::Other)?;
    let mut shared: Vec<Entry> = Vec::new();
    for (name, path) in docs.iter().filter(|(name, _)| name != "index.html") {
        let data = std::fs::read(path).map_err(io("cannot read", path))?;
        shared.push(Entry { name: format!("documentation/{name}"), data, executable: false });
    }
    for (name, svg) in figures {
        shared.push(Entry { name: format!("documentation/{name}"), data: svg.into_bytes(), executable: false });
    }
    shared.push(Entry { name: REFERENCE_CSV.into(), data: reference.csv().into_bytes(), executable: false });
    if let Some(packed) = packed {
        shared.push(Entry {
            name: format!("resources/{SCENARIO_RESOURCE}"),
            data: packed.text.clone().into_bytes(),
            executable: false,
        });
    }
    let page = |fmi3: bool| -> Result<Entry> {
        let html = super::documentation::index_html(
            &template,
            &listed(fmi3),
            generation_tool,
            &reference,
            paper.as_ref(),
            packed,
        )
        .map_err(Error::Other)?;
        Ok(Entry { name: "documentation/index.html".into(), data: html.into_bytes(), executable: false })
    };
    let assemble = |xml: String, binaries: Vec<Entry>, page: Entry| -> Vec<Entry> {
        let mut entries =
            vec![Entry { name: "modelDescription.xml".into(), data: xml.into_bytes(), executable: false }];
        entries.extend(binaries);
        entries.push(page);
        entries.extend(shared.iter().map(|e| Entry {
            name: e.name.clone(),
            data: e.data.clone(),
            executable: e.executable,
        }));
        entries
    };
    let fmi2_entries = assemble(description::fmi2_for(scenario, generation_tool), fmi2_binaries, page(false)?);
    let fmi3_entries = assemble(description::fmi3_for(scenario, generation_tool), fmi3_binaries, page(true)?);
    // Created only once everything is checked (a refused library leaves no folder), both
    // outputs first.
    check_outputs(out_root)?;
    crate::record::output::create_output_dir(out_root, "cannot create directory")?;
    let [fmi2, fmi3] = fmu_paths(out_root);
    write_fmu(&fmi2, &fmi2_entries)?;
    write_fmu(&fmi3, &fmi3_entries)?;
    Ok(vec![fmi2, fmi3])
}

/// Packs `library` (the crate's `libbeam_impact.so`, checked by [`check_library`]) as the Linux
/// binary of both FMUs under `out_root`, with the committed descriptions; returns their paths.
pub fn pack(library: &Path, out_root: &Path) -> Result<Vec<PathBuf>> {
    pack_platforms(&[(Platform::Linux, library.to_path_buf())], out_root, &description::generation_tool(None))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn platform_lists_are_all_or_known_names_in_order_without_repeats() {
        use Platform::*;
        assert_eq!(Platform::parse_list("all").unwrap(), vec![Linux, Windows, Darwin]);
        assert_eq!(Platform::parse_list("linux, all").unwrap(), vec![Linux, Windows, Darwin]);
        assert_eq!(Platform::parse_list("darwin,linux,darwin").unwrap(), vec![Linux, Darwin]);
        for bad in ["", "linux,", "Linux", "win64"] {
            let err = Platform::parse_list(bad).unwrap_err().to_string();
            assert!(err.contains("unknown platform") && err.contains("known: linux, windows, darwin"), "{bad}: {err}");
        }
    }

    /// The newest `GLIBC_2.N` wins by number, not by text (2.17 > 2.3.4 > 2.2.5).
    #[test]
    fn glibc_needed_is_the_newest_version_named() {
        assert_eq!(glibc_needed(b"\0GLIBC_2.2.5\0GLIBC_2.17\0GLIBC_2.3.4\0GLIBC_2.14"), Some((2, 17)));
        assert_eq!(glibc_needed(b"no versions here"), None);
        assert_eq!(glibc_needed(b"GLIBC_2."), None);
    }
}
