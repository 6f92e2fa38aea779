//! The vessel-motion FMU of the gangway-on-a-vessel example (issue 17, item 4; issue 31): its C
//! source, its FMI 2 types and its `modelDescription.xml`, embedded in the executable so that
//! `beam-impact pack --ssp` builds it wherever it runs; what the SSD needs of its description
//! (the Real variables' names, causalities, units and start values; the units' base units), and
//! the FMU packed from the libraries built for each platform.

use std::io::{Cursor, Write};
use std::path::{Path, PathBuf};

use zip::write::SimpleFileOptions;
use zip::{CompressionMethod, ZipWriter};

use crate::fmi::pack::Platform;
use crate::model::sea::raos::RaoSource;
use crate::model::sea::SeaSettings;
use crate::{Error, Result};

/// The FMU's model identifier (its library's file name without the extension).
pub const MODEL_IDENTIFIER: &str = "VesselMotion";
/// The C source (`fmu/vessel/vessel_motion.c`).
pub const SOURCE: &str = include_str!("../../fmu/vessel/vessel_motion.c");
/// The FMI 2 types it includes (`fmu/vessel/fmi2_abi.h`).
pub const ABI_HEADER: &str = include_str!("../../fmu/vessel/fmi2_abi.h");
/// Its `modelDescription.xml` (`fmu/vessel/VesselMotion.xml`).
pub const DESCRIPTION: &str = include_str!("../../fmu/vessel/VesselMotion.xml");
/// The example vessel's RAO table (`examples/vessel-sea-raos.csv`, our CSV), the FMU's
/// `resources/raos.csv` unless a scenario's `[sea]` names another.
pub const EXAMPLE_RAOS: &str = include_str!("../../examples/vessel-sea-raos.csv");
/// Where the FMU holds the RAO table its irregular sea reads.
pub const RAO_RESOURCE: &str = "resources/raos.csv";

/// One Real variable of the description.
#[derive(Clone, Debug, PartialEq)]
pub struct RealVariable {
    /// Its name (`wave.phase`).
    pub name: String,
    /// `parameter`, `input`, `output` or `calculatedParameter`.
    pub causality: String,
    /// Its unit (`m`), as the description's `UnitDefinitions` name it.
    pub unit: String,
    /// Its start value, when the description gives one.
    pub start: Option<f64>,
}

/// The value of attribute `name` in the start tag `tag` (the text from `<` to `>`).
fn attribute(tag: &str, name: &str) -> Option<String> {
    let key = format!(" {name}=\"");
    let at = tag.find(&key)? + key.len();
    let len = tag[at..].find('"')?;
    Some(tag[at..at + len].to_string())
}

/// The start tags `<element ...>` of `text`, in order (`element` followed by a space, `/` or `>`).
fn start_tags<'a>(text: &'a str, element: &str) -> Vec<&'a str> {
    let open = format!("<{element}");
    let mut tags = Vec::new();
    let mut rest = text;
    while let Some(at) = rest.find(&open) {
        let after = &rest[at + open.len()..];
        let end = after.find('>').map_or(after.len(), |e| e + 1);
        if after.starts_with([' ', '/', '>', '\n']) {
            tags.push(&rest[at..at + open.len() + end]);
        }
        rest = &after[end.min(after.len())..];
    }
    tags
}

/// The Real variables of the description, in its order.
pub fn real_variables() -> Result<Vec<RealVariable>> {
    let mut variables = Vec::new();
    for block in DESCRIPTION.split("<ScalarVariable").skip(1) {
        let head = &block[..block.find('>').unwrap_or(block.len())];
        let (Some(name), Some(causality)) = (attribute(head, "name"), attribute(head, "causality")) else {
            return Err(Error::Other("VesselMotion.xml: a ScalarVariable without name or causality".into()));
        };
        let body = &block[..block.find("</ScalarVariable>").unwrap_or(block.len())];
        let Some(real) = start_tags(body, "Real").first().copied() else { continue };
        let unit = attribute(real, "unit")
            .ok_or_else(|| Error::Other(format!("VesselMotion.xml: the Real variable {name} has no unit")))?;
        let start = match attribute(real, "start") {
            Some(text) => Some(text.parse::<f64>().map_err(|_| {
                Error::Other(format!("VesselMotion.xml: the start value `{text}` of {name} is not a number"))
            })?),
            None => None,
        };
        variables.push(RealVariable { name, causality, unit, start });
    }
    Ok(variables)
}

/// The base-unit exponents (kg, m, s, rad) and factor of each unit the description defines, in its
/// order (`deg`: rad with the factor pi / 180).
pub fn units() -> Vec<(String, [i32; 4], f64)> {
    let mut units = Vec::new();
    for block in DESCRIPTION.split("<Unit ").skip(1) {
        let head = &block[..block.find('>').unwrap_or(block.len())];
        let Some(name) = attribute(&format!(" {head}"), "name") else { continue };
        // `<Unit name="1"/>` has no base unit; otherwise the body runs to `</Unit>`.
        let body = if head.ends_with('/') { "" } else { &block[..block.find("</Unit>").unwrap_or(block.len())] };
        let tag = start_tags(body, "BaseUnit").first().copied();
        let exponents = tag.map_or([0; 4], |tag| {
            ["kg", "m", "s", "rad"].map(|u| attribute(tag, u).and_then(|e| e.parse().ok()).unwrap_or(0))
        });
        let factor = tag.and_then(|tag| attribute(tag, "factor")).and_then(|f| f.parse().ok()).unwrap_or(1.0);
        units.push((name, exponents, factor));
    }
    units
}

/// The vessel FMU's parameters for a scenario's `[sea]` (`pack --ssp --scenario`): the sea state,
/// the deck points and the arrestor's direction, each under its FMU name (0 for a default left
/// out: DNV's gamma, the default frequency range). The SSD binds them, so the SSP runs that sea.
/// A support on a fixed platform (a deck point left out) is refused: the SSD binds Real parameters
/// only, and `hinge.on_vessel` / `clamp.on_vessel` are Boolean.
pub fn sea_bindings(sea: &SeaSettings) -> Result<Vec<(&'static str, f64)>> {
    let (Some(hinge), Some(clamp)) = (sea.hinge_point, sea.clamp_point) else {
        return Err(Error::Other(
            "cannot pack the [sea] into GangwayOnVessel.ssp: sea.hinge_point and sea.clamp_point must both be given \
             (the SSP binds the vessel FMU's Real parameters; a support on a fixed platform is its Boolean \
             hinge.on_vessel or clamp.on_vessel, set in the tool)"
                .into(),
        ));
    };
    Ok(vec![
        ("sea.significant_wave_height", sea.significant_wave_height),
        ("sea.peak_period", sea.peak_period),
        ("sea.spectrum", f64::from(sea.spectrum.index())),
        ("sea.peak_enhancement", sea.peak_enhancement.unwrap_or(0.0)),
        ("sea.heading", sea.heading),
        ("sea.seed", sea.seed as f64),
        ("sea.components", f64::from(sea.components)),
        ("sea.frequency_min", sea.frequency_min.unwrap_or(0.0)),
        ("sea.frequency_max", sea.frequency_max.unwrap_or(0.0)),
        ("sea.time_shift", sea.time_shift),
        ("hinge.x", hinge[0]),
        ("hinge.y", hinge[1]),
        ("clamp.x", clamp[0]),
        ("clamp.y", clamp[1]),
        ("sea.arrestor_direction", sea.arrestor_direction),
    ])
}

/// The vessel FMU's RAO resource for a `[sea]` whose file was read as `text`: the text itself for
/// our CSV (the FMU parses the very bytes the CLI did), the table written as our CSV for a VERES
/// `.re1` ([`crate::model::sea::raos_write`]).
pub fn rao_resource(sea: &SeaSettings, text: &str) -> Result<String> {
    let table =
        sea.rao_table.as_ref().ok_or_else(|| Error::Other(format!("{}: the RAO file is not loaded", sea.raos)))?;
    Ok(match &table.source {
        RaoSource::Csv => text.to_string(),
        RaoSource::Veres { ship, .. } => crate::model::sea::raos_write::write_csv(
            table,
            &format!(
                "The RAOs of {} (VERES .re1: {}), converted to our CSV by beam-impact pack --ssp (docs/sea-states.md)",
                crate::error::bounded_line(ship),
                crate::error::bounded_line(&sea.raos)
            ),
        ),
    })
}

/// The largest library packed, bytes (the vessel's are tens of kB).
const MAX_LIBRARY: u64 = 64 << 20;

/// Packs the FMU from one library per platform (`binaries/<linux64|win64|darwin64>/VesselMotion.<so|dll|dylib>`),
/// each read through the output guard's input check and required to name `fmi2Instantiate`, and
/// the RAO table `raos` (our CSV) as [`RAO_RESOURCE`]; returns the FMU's bytes.
pub fn pack_fmu(libraries: &[(Platform, PathBuf)], raos: &str) -> Result<Vec<u8>> {
    let mut zip = ZipWriter::new(Cursor::new(Vec::new()));
    let options = SimpleFileOptions::default().compression_method(CompressionMethod::Deflated);
    let zip_error = |e: zip::result::ZipError| Error::Other(format!("cannot pack {MODEL_IDENTIFIER}.fmu: {e}"));
    zip.start_file("modelDescription.xml", options).map_err(zip_error)?;
    zip.write_all(DESCRIPTION.as_bytes())
        .map_err(|e| Error::Other(format!("cannot pack {MODEL_IDENTIFIER}.fmu: {e}")))?;
    for (platform, path) in libraries {
        let bytes = read_library(path)?;
        let entry = format!("binaries/{}/{MODEL_IDENTIFIER}.{}", platform.fmi2_dir(), platform.extension());
        zip.start_file(entry.as_str(), options.unix_permissions(0o755)).map_err(zip_error)?;
        zip.write_all(&bytes).map_err(|e| Error::Other(format!("cannot pack {MODEL_IDENTIFIER}.fmu: {e}")))?;
    }
    zip.start_file(RAO_RESOURCE, options).map_err(zip_error)?;
    zip.write_all(raos.as_bytes()).map_err(|e| Error::Other(format!("cannot pack {MODEL_IDENTIFIER}.fmu: {e}")))?;
    Ok(zip.finish().map_err(zip_error)?.into_inner())
}

/// Reads a built library: a regular file of at most [`MAX_LIBRARY`] bytes naming `fmi2Instantiate`.
fn read_library(path: &Path) -> Result<Vec<u8>> {
    use std::io::Read;
    let what = "cannot read the vessel-motion library";
    let file = crate::record::output::open_regular_input(path, what)?;
    let mut bytes = Vec::new();
    file.take(MAX_LIBRARY + 1).read_to_end(&mut bytes).map_err(|source| Error::Io {
        action: what,
        path: path.display().to_string(),
        source,
    })?;
    if bytes.len() as u64 > MAX_LIBRARY {
        return Err(Error::Other(format!(
            "{} is larger than {MAX_LIBRARY} bytes: not the vessel-motion library",
            path.display()
        )));
    }
    if !bytes.windows(15).any(|w| w == b"fmi2Instantiate") {
        return Err(Error::Other(format!(
            "{} does not export fmi2Instantiate: not the vessel-motion library",
            path.display()
        )));
    }
    Ok(bytes)
}

/// Joins thin 64-bit Mach-O dylibs (each `MH_MAGIC_64`, one per CPU type) into one fat
/// (universal) Mach-O: the big-endian fat header, one `fat_arch` per slice (CPU type and subtype
/// read from the slice), each slice at a 16 KiB boundary (arm64's page size, also a multiple of
/// x86-64's). What `lipo -create` makes; zig builds one architecture at a time.
pub fn universal_dylib(slices: &[Vec<u8>]) -> std::result::Result<Vec<u8>, String> {
    const ALIGN_LOG2: u32 = 14;
    let align = 1usize << ALIGN_LOG2;
    let mut header = Vec::new();
    header.extend_from_slice(&0xcafe_babe_u32.to_be_bytes());
    header.extend_from_slice(&(slices.len() as u32).to_be_bytes());
    let mut offset = align;
    let mut body = Vec::new();
    for (k, slice) in slices.iter().enumerate() {
        let word = |at: usize| slice.get(at..at + 4).map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]));
        if word(0) != Some(0xfeed_facf) {
            return Err(format!("slice {k} is not a 64-bit little-endian Mach-O"));
        }
        let (cpu, subtype) = (word(4).unwrap_or(0), word(8).unwrap_or(0));
        let size = u32::try_from(slice.len()).map_err(|_| format!("slice {k} is larger than 4 GiB"))?;
        for value in [cpu, subtype, offset as u32, size, ALIGN_LOG2] {
            header.extend_from_slice(&value.to_be_bytes());
        }
        body.resize(offset - align, 0);
        body.extend_from_slice(slice);
        offset = (align + body.len()).div_ceil(align) * align;
    }
    let mut fat = header;
    fat.resize(align, 0);
    fat.extend_from_slice(&body);
    Ok(fat)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The scan finds every Real variable of the hand-written description (46 of its 48; the
    /// other two are Boolean) with the start values vessel_motion.c's START table also holds.
    #[test]
    fn the_description_scan_finds_the_real_variables_and_their_starts() {
        let vars = real_variables().unwrap();
        assert_eq!(vars.len(), 46);
        let find = |n: &str| vars.iter().find(|v| v.name == n).unwrap().clone();
        assert_eq!(find("wave.period").start, Some(9.0));
        assert_eq!(find("wave.period").unit, "s");
        assert_eq!(find("pitch.phase").start, Some(-1.9));
        assert_eq!(find("hinge_force").causality, "input");
        assert_eq!(find("deck.force").start, None);
        assert_eq!(vars.iter().filter(|v| v.causality == "parameter").count(), 26);
        assert_eq!(find("sea.significant_wave_height").start, Some(0.0), "the regular wave by default");
        assert_eq!(find("sea.heading").unit, "deg");
    }

    /// Two thin slices come back whole at 16 KiB boundaries behind a header naming their CPUs (the
    /// 20 000-byte first slice runs from 16 384 past 32 768, so the second starts at 49 152).
    #[test]
    fn a_universal_dylib_holds_each_slice_at_its_aligned_offset() {
        let thin = |cpu: u32, len: usize| {
            let mut b = vec![0u8; len];
            b[..4].copy_from_slice(&0xfeed_facf_u32.to_le_bytes());
            b[4..8].copy_from_slice(&cpu.to_le_bytes());
            b[len - 1] = 7;
            b
        };
        let (x86, arm) = (thin(0x0100_0007, 20_000), thin(0x0100_000c, 100));
        let fat = universal_dylib(&[x86.clone(), arm.clone()]).unwrap();
        let be = |at: usize| u32::from_be_bytes(fat[at..at + 4].try_into().unwrap());
        assert_eq!((be(0), be(4)), (0xcafe_babe, 2));
        assert_eq!((be(8), be(16), be(20)), (0x0100_0007, 16384, 20_000));
        assert_eq!((be(28), be(36), be(40)), (0x0100_000c, 49152, 100));
        assert_eq!(&fat[16384..36384], x86.as_slice());
        assert_eq!(&fat[49152..49252], arm.as_slice());
        assert_eq!(fat.len(), 49252);
        assert!(universal_dylib(&[vec![0; 8]]).is_err());
    }

    #[test]
    fn the_description_units_carry_their_base_units() {
        let units = units();
        let find = |n: &str| units.iter().find(|u| u.0 == n).map(|u| u.1);
        assert_eq!(find("N.m"), Some([1, 2, -2, 0]));
        let deg = units.iter().find(|u| u.0 == "deg").unwrap();
        assert_eq!((deg.1, deg.2), ([0, 0, 0, 1], std::f64::consts::PI / 180.0));
        assert_eq!(find("rad/s2"), Some([0, 0, -2, 1]));
        assert_eq!(find("1"), Some([0, 0, 0, 0]));
        assert_eq!(units.len(), 13);
    }
}
