//! Opening files that a run writes, safely: never through a symbolic link at the last component
//! (writing would truncate the link's target), never a FIFO or a socket (opening one blocks until
//! a reader appears: the run, or the FMU's host, would hang), a device only where the caller
//! allows it (the CLI's `/dev/null`). Opening never blocks: `O_NONBLOCK` is set for the open
//! and the file type is checked on the opened descriptor, so there is no race with a swap.
//!
//! On Windows (the FMU's win64 binary) the same rules hold where Windows can tell, with std's
//! stable API only (module `platform` holds the differences): an output is opened with
//! `FILE_FLAG_OPEN_REPARSE_POINT`, so a symbolic link or junction at the last component is
//! opened itself, seen on the opened handle and refused before anything is written; devices are
//! recognised by name before anything is opened (`NUL`, `CON`, `COM1`, ... with any extension,
//! and every `\\.\` path, which covers named pipes), and only `NUL` is written where the caller
//! allows a device; opening never waits for a reader there (a named pipe without a server fails
//! at once), so nothing needs `O_NONBLOCK`. Two paths name one file when their canonical paths
//! agree (a new file: its folder's canonical path and its name, compared case-insensitively).
//! What Windows cannot tell through std: two hard links to one file are two files there (no
//! stable link count or file index), so a leftover `NAME.partial` that is a hard link is not
//! removed before it is written, and `check_distinct` does not see two hard links as one file.

use std::fs::File;
use std::path::{Path, PathBuf};

use crate::error::{Error, Result};

/// Opens `path` for writing, creating it if needed, without truncating it (the caller truncates
/// once it holds the file, e.g. after taking a lock). `what` names the file in errors.
pub fn open_output(path: &Path, allow_devices: bool, what: &'static str) -> Result<File> {
    let io = |source| Error::Io { action: what, path: path.display().to_string(), source };
    platform::check_name(path, allow_devices).map_err(io)?;
    let file = platform::no_follow(std::fs::OpenOptions::new().write(true).create(true).truncate(false))
        .open(path)
        .map_err(|e| match platform::explain_open_error(&e) {
            Some(why) => io(std::io::Error::other(why)),
            None => io(e),
        })?;
    check_kind(path, &file, allow_devices).map_err(io)?;
    Ok(file)
}

/// Opens `path` for reading (symbolic links are followed: reading through one harms nothing),
/// refusing a FIFO or a socket, which would block the read.
pub fn open_input(path: &Path, what: &'static str) -> Result<File> {
    open_for_reading(path, what, " (use - for standard input)")
}

/// [`open_input`] with `hint` after the refusal of a FIFO or a socket.
fn open_for_reading(path: &Path, what: &'static str, hint: &str) -> Result<File> {
    let io = |source| Error::Io { action: what, path: path.display().to_string(), source };
    platform::check_name(path, true).map_err(io)?;
    let file = platform::no_block(std::fs::OpenOptions::new().read(true)).open(path).map_err(io)?;
    check_kind(path, &file, true)
        .map_err(|e| if e.to_string().contains("FIFO") { std::io::Error::other(format!("{e}{hint}")) } else { e })
        .map_err(io)?;
    Ok(file)
}

/// A file a command writes, guarded: it is written to `NAME.partial` beside the target (created
/// exclusively, never through a link) and renamed over NAME by [`OutputFile::commit`], so the
/// user's earlier NAME stays as it was until the output is complete, and a failed run (the value
/// dropped without a commit) removes its partial file and leaves NAME untouched. A target that
/// is a symbolic link, a FIFO, a socket or a folder is refused before anything is written; a
/// device is written in place where the caller allows it (the CLI's `/dev/null`).
#[derive(Debug)]
pub struct OutputFile {
    target: PathBuf,
    partial: Option<PathBuf>,
    file: Option<File>,
    what: &'static str,
}

impl OutputFile {
    /// Opens the output for `path`; `what` names it in errors ("cannot create JSON").
    pub fn create(path: &Path, allow_devices: bool, what: &'static str) -> Result<Self> {
        let io = |source| Error::Io { action: what, path: path.display().to_string(), source };
        let Some(partial) = partial_for(path).map_err(io)? else {
            let file = open_output(path, allow_devices, what)?;
            return Ok(OutputFile { target: path.to_path_buf(), partial: None, file: Some(file), what });
        };
        let file = create_exclusive(&partial).map_err(io)?;
        Ok(OutputFile { target: path.to_path_buf(), partial: Some(partial), file: Some(file), what })
    }

    /// The open file.
    pub fn file(&mut self) -> &mut File {
        self.file.as_mut().expect("an OutputFile holds its file until commit")
    }

    /// Completes the output: flushes it and renames the partial file over the target.
    pub fn commit(mut self) -> Result<()> {
        let io = |source| Error::Io { action: self.what, path: self.target.display().to_string(), source };
        if let Some(file) = self.file.take() {
            file.sync_data().or_else(|e| if self.partial.is_none() { Ok(()) } else { Err(e) }).map_err(io)?;
        }
        if let Some(partial) = self.partial.take() {
            std::fs::rename(&partial, &self.target).map_err(|e| {
                let _ = std::fs::remove_file(&partial);
                io(e)
            })?;
        }
        Ok(())
    }
}

impl Drop for OutputFile {
    fn drop(&mut self) {
        if let Some(partial) = self.partial.take() {
            let _ = std::fs::remove_file(partial);
        }
    }
}

impl std::io::Write for OutputFile {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.file().write(buf)
    }
    fn flush(&mut self) -> std::io::Result<()> {
        self.file().flush()
    }
}

impl std::io::Seek for OutputFile {
    fn seek(&mut self, position: std::io::SeekFrom) -> std::io::Result<u64> {
        self.file().seek(position)
    }
}

/// Where an output to `path` is written: `Some(NAME.partial)` for a regular file or a new one,
/// `None` for a device (written in place, if the caller allows it). A target that is a symbolic
/// link, a folder, a FIFO or a socket is an error, before anything is written.
pub fn partial_for(path: &Path) -> std::io::Result<Option<PathBuf>> {
    // `out.mcap/` can only be a folder: refused here, not when the finished file is renamed.
    if path.as_os_str().as_encoded_bytes().ends_with(b"/") {
        return Err(std::io::Error::other("it ends with `/`, a folder's name; give a file name"));
    }
    match std::fs::symlink_metadata(path) {
        _ if platform::device_by_name(path).is_some() => Ok(None),
        Ok(m) if platform::is_device(&m) => Ok(None),
        Ok(m) if !m.is_file() => {
            let kind = if m.file_type().is_symlink() {
                "a symbolic link; give the link's target instead"
            } else if m.is_dir() {
                "a folder"
            } else {
                "a FIFO or a socket, not a regular file"
            };
            Err(std::io::Error::other(format!("it is {kind}")))
        }
        _ => Ok(Some(partial_path(path))),
    }
}

/// `NAME.partial` beside `path`.
pub fn partial_path(path: &Path) -> PathBuf {
    let mut name = path.file_name().map(|n| n.to_os_string()).unwrap_or_default();
    name.push(".partial");
    path.with_file_name(name)
}

/// Creates `path` exclusively, never through a link, and locks it (an exclusive advisory lock,
/// held while the file is open). A regular file already there whose lock is free (a name reserved
/// by [`crate::fmi::instance::unique_log`], or a leftover of a killed run) is taken over in place:
/// opened without following links, locked and emptied, so the name never disappears on the way
/// (removing it and creating it anew left a moment in which another process reserving names
/// could take the same one: two FMU processes in one folder, one log lost). A partial file
/// another run still writes (its lock taken: two runs given the same output) is an error, not
/// removed from under it; a link (symbolic or hard) is removed, never followed or written through.
fn create_exclusive(path: &Path) -> std::io::Result<File> {
    if let Ok(m) = std::fs::symlink_metadata(path) {
        if m.is_dir() {
            return Err(std::io::Error::other(format!("{} is a folder", path.display())));
        }
        if m.is_file() {
            let file = platform::no_follow(std::fs::OpenOptions::new().write(true)).open(path)?;
            if file.try_lock().is_err() {
                return Err(std::io::Error::other(format!(
                    "{} is being written by another run (its lock is taken)",
                    path.display()
                )));
            }
            if !has_other_links(&m) {
                file.set_len(0)?;
                return Ok(file);
            }
            // A hard link: writing it would change its other names; removed instead.
        }
        std::fs::remove_file(path)?;
    }
    let file = platform::no_follow(std::fs::OpenOptions::new().write(true).create_new(true)).open(path)?;
    file.try_lock().map_err(|e| std::io::Error::other(format!("{} cannot be locked ({e})", path.display())))?;
    Ok(file)
}

/// Writes a file that a library writes by path (the figures' SVG and PNG backends): `write`
/// gets `NAME.partial.EXT` (any leftover there removed, so no link in the folder is followed), and
/// the result is renamed over NAME, which replaces a link or a FIFO there instead of writing
/// through it.
pub fn write_by_path(target: &Path, what: &'static str, write: impl FnOnce(&Path) -> Result<()>) -> Result<()> {
    let io = |source| Error::Io { action: what, path: target.display().to_string(), source };
    if std::fs::symlink_metadata(target).is_ok_and(|m| m.is_dir()) {
        return Err(io(std::io::Error::other("it is a folder")));
    }
    // `NAME.partial.EXT`: the libraries choose the format from the extension.
    let partial = match (target.file_stem(), target.extension()) {
        (Some(stem), Some(ext)) => {
            let mut name = stem.to_os_string();
            name.push(".partial.");
            name.push(ext);
            target.with_file_name(name)
        }
        _ => partial_path(target),
    };
    drop(create_exclusive(&partial).map_err(io)?);
    let written = write(&partial).and_then(|()| std::fs::rename(&partial, target).map_err(io));
    if written.is_err() {
        let _ = std::fs::remove_file(&partial);
    }
    written
}

/// Creates a folder for outputs (and its parents), refusing a folder that is a symbolic link:
/// a stranger's `log-figures -> ~/` would otherwise take the figures.
pub fn create_output_dir(dir: &Path, what: &'static str) -> Result<()> {
    let io = |source| Error::Io { action: what, path: dir.display().to_string(), source };
    // `link/` and `link/.` name the link's target: look at the link itself.
    let dir: PathBuf = dir.components().collect();
    let dir = dir.as_path();
    if std::fs::symlink_metadata(dir).is_ok_and(|m| m.file_type().is_symlink()) {
        return Err(io(std::io::Error::other("it is a symbolic link; give the link's target instead")));
    }
    std::fs::create_dir_all(dir).map_err(io)
}

/// Checks an output before anything of a command is written, creating nothing: `path` as
/// [`OutputFile::create`] takes it without devices (refused: a symbolic link, a folder, a FIFO, a
/// socket, a device, a name ending in `/`), and each of `folders`, the folders the command
/// creates on its way to it, as [`create_output_dir`] does (refused: a symbolic link, a file). A
/// command with several outputs checks every one first, so that a refused one leaves the others
/// as they were (`pack`: both FMUs and `GangwayOnVessel.ssp`); each is still guarded when written.
pub fn check_output(path: &Path, folders: &[&Path], what: &'static str) -> Result<()> {
    for &folder in folders {
        let io = |why: &str| Error::Io { action: what, path: shown(folder), source: std::io::Error::other(why) };
        // `link/` and `link/.` name the link's target: look at the link itself.
        let folder: PathBuf = folder.components().collect();
        match std::fs::symlink_metadata(&folder) {
            Ok(m) if m.file_type().is_symlink() => {
                return Err(io("it is a symbolic link; give the link's target instead"));
            }
            Ok(m) if !m.is_dir() => return Err(io("it is not a folder")),
            _ => {}
        }
    }
    let io = |source| Error::Io { action: what, path: shown(path), source };
    match partial_for(path).map_err(io)? {
        Some(_) => Ok(()),
        None => Err(io(std::io::Error::other("it is a device, not a regular file"))),
    }
}

/// What a path names, to tell whether two paths are one file: the device and inode of an
/// existing file, or for a file still to be created the device and inode of its folder and its
/// final name. `None` for a device (`/dev/null` takes any number of outputs) and `-`.
fn identity(path: &Path) -> Option<(platform::FileKey, Option<std::ffi::OsString>)> {
    if path.as_os_str() == "-" || platform::device_by_name(path).is_some() {
        return None;
    }
    match std::fs::metadata(path) {
        Ok(m) if platform::is_device(&m) => None,
        Ok(m) => Some((platform::key(path, &m)?, None)),
        Err(_) => {
            let parent = match path.parent() {
                Some(p) if !p.as_os_str().is_empty() => p,
                _ => Path::new("."),
            };
            let m = std::fs::metadata(parent).ok()?;
            Some((platform::key(parent, &m)?, Some(platform::name_key(path.file_name()?))))
        }
    }
}

/// Whether the regular file `m` has other names (hard links), which writing it would change too.
/// Always false on Windows, where std has no stable link count (see the module's notes).
pub fn has_other_links(m: &std::fs::Metadata) -> bool {
    platform::has_other_links(m)
}

/// Refuses two of `files` (role, path: the inputs a command reads and the outputs it writes)
/// that name one file, by device and inode, before anything is opened for writing.
pub fn check_distinct(files: &[(&str, &Path)]) -> Result<()> {
    let ids: Vec<_> = files.iter().map(|(_, p)| identity(p)).collect();
    for (j, b) in ids.iter().enumerate() {
        for (i, a) in ids[..j].iter().enumerate() {
            if a.is_some() && a == b {
                return Err(Error::Other(format!(
                    "{} and {} name the same file {}",
                    files[i].0,
                    files[j].0,
                    files[j].1.display()
                )));
            }
        }
    }
    // An output is written to NAME.partial first: no other file may be that.
    for (j, (role, path)) in files.iter().enumerate() {
        if path.as_os_str() == "-" {
            continue;
        }
        let partial = identity(&partial_path(path));
        if let Some(i) = ids.iter().enumerate().position(|(i, a)| i != j && a.is_some() && *a == partial) {
            return Err(Error::Other(format!(
                "{} {} is the file {role} is written through ({}.partial); give another name",
                files[i].0,
                files[i].1.display(),
                path.display()
            )));
        }
    }
    Ok(())
}

/// Whether `path`'s folder is `dir` (by device and inode; false when either is missing).
pub fn same_folder(path: &Path, dir: &Path) -> bool {
    let parent = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    match (std::fs::metadata(parent), std::fs::metadata(dir)) {
        (Ok(a), Ok(b)) => platform::key(parent, &a).is_some_and(|a| platform::key(dir, &b) == Some(a)),
        _ => false,
    }
}

/// `path` as printed to a terminal or a log: its display form with control characters escaped
/// (`\u{1b}`), so that a hostile file name sends no escape sequence (issue 27).
pub fn shown(path: &Path) -> String {
    escape_controls(&path.display().to_string()).into_owned()
}

/// `text` with its control characters escaped (`\u{1b}`, `\n`), as [`shown`] escapes a path's:
/// for a message that quotes one (the FMU's log lines, issue 40).
pub fn escape_controls(text: &str) -> std::borrow::Cow<'_, str> {
    if !text.chars().any(char::is_control) {
        return std::borrow::Cow::Borrowed(text);
    }
    text.chars().flat_map(|c| if c.is_control() { c.escape_default().collect::<Vec<_>>() } else { vec![c] }).collect()
}

/// Refuses a file whose size, read from its metadata before a byte of it is read, exceeds
/// `limit` (a 2 GB sparse file costs nothing to refuse this way). Files whose metadata says 0
/// (`/proc` files) are still bounded while read ([`read_bounded`]).
pub fn check_size(file: &File, limit: u64, what: &str) -> std::io::Result<()> {
    let size = file.metadata()?.len();
    if size > limit {
        return Err(std::io::Error::other(format!("{what} is {size} bytes, larger than {limit} bytes (the limit)")));
    }
    Ok(())
}

/// Largest scenario file (or standard input) the CLI reads, bytes.
pub const MAX_SCENARIO_BYTES: u64 = 4 << 20;

/// Reads at most `limit` bytes of UTF-8 text from `reader`, checked while reading: a longer
/// input (`/dev/zero`, an endless pipe) is an error naming the limit, not an exhausted machine.
pub fn read_bounded(reader: impl std::io::Read, limit: u64, what: &str) -> std::io::Result<String> {
    use std::io::Read;
    let mut bytes = Vec::new();
    reader.take(limit + 1).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > limit {
        return Err(std::io::Error::other(format!("{what} is larger than {limit} bytes (the limit)")));
    }
    String::from_utf8(bytes).map_err(|e| std::io::Error::other(format!("{what} is not UTF-8 text ({e})")))
}

/// Refuses an input that lies in `dir` (a figure folder) under a figure's extension: drawing the
/// figures would replace it (`report out/fig6-deflection.svg --out out`).
pub fn check_not_in_figure_folder(role: &str, input: &Path, dir: &Path) -> Result<()> {
    let figure_like = matches!(input.extension().and_then(|e| e.to_str()), Some("svg" | "png"));
    if figure_like && same_folder(input, dir) {
        return Err(Error::Other(format!(
            "{role} {} lies in the figure folder {} under a figure's extension, where the figures are written; \
             give another folder",
            input.display(),
            dir.display()
        )));
    }
    Ok(())
}

/// Opens a log for reading: a regular file only (a device such as /dev/zero never ends).
pub fn open_regular_input(path: &Path, what: &'static str) -> Result<File> {
    let file = open_for_reading(path, what, "")?;
    if !file.metadata().is_ok_and(|m| m.is_file()) {
        return Err(Error::Io {
            action: what,
            path: path.display().to_string(),
            source: std::io::Error::other("it is not a regular file"),
        });
    }
    Ok(file)
}

/// Checks the opened `file` (at `path`): no FIFO or socket, a device only where allowed and only
/// the null device, no folder, no symbolic link (Windows, where the link itself was opened).
fn check_kind(path: &Path, file: &File, allow_devices: bool) -> std::io::Result<()> {
    if platform::device_by_name(path).is_some() {
        // Windows: checked by name before opening (`check_name`); the handle may have no metadata.
        return Ok(());
    }
    let m = file.metadata()?;
    let kind = m.file_type();
    if platform::is_fifo_or_socket(&m) {
        return Err(std::io::Error::other("it is a FIFO or a socket, not a regular file"));
    }
    if platform::is_device(&m) {
        if !allow_devices {
            return Err(std::io::Error::other("it is a device, not a regular file"));
        }
        if !platform::is_null_device(&m) {
            return Err(std::io::Error::other("it is a device other than /dev/null, not a regular file"));
        }
    }
    if kind.is_dir() {
        return Err(std::io::Error::other("it is a directory"));
    }
    if kind.is_symlink() {
        return Err(std::io::Error::other("it is a symbolic link; give the link's target instead"));
    }
    Ok(())
}

/// A Windows device's name if `path` names one: a reserved DOS device name as the last component
/// (`NUL`, `CON`, `PRN`, `AUX`, `COM0`-`COM9`, `LPT0`-`LPT9`, `CONIN$`, `CONOUT$`, with any
/// extension or trailing spaces, any case) or a `\\.\` path (named pipes, volumes, devices).
/// Plain string logic, so that it is tested on every platform; used on Windows only.
#[cfg_attr(not(windows), allow(dead_code))]
fn windows_device_name(path: &str) -> Option<String> {
    let upper = path.to_ascii_uppercase();
    if let Some(rest) = upper.strip_prefix("\\\\.\\").or_else(|| upper.strip_prefix("//./")) {
        return Some(rest.to_string());
    }
    let name = upper.rsplit(['/', '\\']).next()?;
    let name = name.rsplit_once(':').map_or(name, |(drive, rest)| if drive.len() == 1 { rest } else { name });
    let stem = name.split('.').next()?.trim_end_matches(' ');
    let numbered = |prefix: &str| {
        stem.strip_prefix(prefix).is_some_and(|n| {
            matches!(n, "0" | "1" | "2" | "3" | "4" | "5" | "6" | "7" | "8" | "9" | "\u{b9}" | "\u{b2}" | "\u{b3}")
        })
    };
    let reserved =
        matches!(stem, "CON" | "PRN" | "AUX" | "NUL" | "CONIN$" | "CONOUT$") || numbered("COM") || numbered("LPT");
    reserved.then(|| stem.to_string())
}

/// What opening and identifying files needs that differs between Unix and Windows.
#[cfg(unix)]
mod platform {
    use std::ffi::{OsStr, OsString};
    use std::fs::{Metadata, OpenOptions};
    use std::os::unix::fs::{FileTypeExt, MetadataExt, OpenOptionsExt};
    use std::path::Path;

    /// Opening never follows a symbolic link at the last component and never blocks.
    pub fn no_follow(options: &mut OpenOptions) -> &mut OpenOptions {
        options.custom_flags(libc::O_NOFOLLOW | libc::O_NONBLOCK)
    }

    /// Opening never blocks (a FIFO without a writer).
    pub fn no_block(options: &mut OpenOptions) -> &mut OpenOptions {
        options.custom_flags(libc::O_NONBLOCK)
    }

    /// The refusal in words for what [`no_follow`] makes the open fail with.
    pub fn explain_open_error(e: &std::io::Error) -> Option<&'static str> {
        match e.raw_os_error() {
            Some(libc::ELOOP) => Some("it is a symbolic link; give the link's target instead"),
            Some(libc::ENXIO) => Some("it is a FIFO without a reader"),
            _ => None,
        }
    }

    /// Devices are told by their file type on Unix, never by name.
    pub fn check_name(_path: &Path, _allow_devices: bool) -> std::io::Result<()> {
        Ok(())
    }

    pub fn device_by_name(_path: &Path) -> Option<String> {
        None
    }

    pub fn is_device(m: &Metadata) -> bool {
        m.file_type().is_char_device() || m.file_type().is_block_device()
    }

    pub fn is_fifo_or_socket(m: &Metadata) -> bool {
        m.file_type().is_fifo() || m.file_type().is_socket()
    }

    /// Whether `m` is the null device (the one device outputs may name).
    pub fn is_null_device(m: &Metadata) -> bool {
        m.file_type().is_char_device() && std::fs::metadata("/dev/null").is_ok_and(|null| null.rdev() == m.rdev())
    }

    /// A file's identity: device and inode.
    pub type FileKey = (u64, u64);

    pub fn key(_path: &Path, m: &Metadata) -> Option<FileKey> {
        Some((m.dev(), m.ino()))
    }

    pub fn name_key(name: &OsStr) -> OsString {
        name.to_os_string()
    }

    pub fn has_other_links(m: &Metadata) -> bool {
        m.nlink() > 1
    }
}

/// What opening and identifying files needs that differs between Unix and Windows.
#[cfg(windows)]
mod platform {
    use std::ffi::{OsStr, OsString};
    use std::fs::{Metadata, OpenOptions};
    use std::os::windows::fs::OpenOptionsExt;
    use std::path::{Path, PathBuf};

    /// `FILE_FLAG_OPEN_REPARSE_POINT`: a link at the last component is opened itself, not followed.
    const FILE_FLAG_OPEN_REPARSE_POINT: u32 = 0x0020_0000;

    /// Opening does not follow a symbolic link or junction at the last component: the link itself
    /// is opened, and `check_kind` refuses it before anything is written.
    pub fn no_follow(options: &mut OpenOptions) -> &mut OpenOptions {
        options.custom_flags(FILE_FLAG_OPEN_REPARSE_POINT)
    }

    /// Opening a file, a device or a named pipe does not wait for a peer on Windows.
    pub fn no_block(options: &mut OpenOptions) -> &mut OpenOptions {
        options
    }

    pub fn explain_open_error(_e: &std::io::Error) -> Option<&'static str> {
        None
    }

    /// Refuses a device named by `path` before it is opened, except `NUL` where devices are allowed.
    pub fn check_name(path: &Path, allow_devices: bool) -> std::io::Result<()> {
        match device_by_name(path) {
            None => Ok(()),
            Some(name) if allow_devices && name == "NUL" => Ok(()),
            Some(_) if allow_devices => Err(std::io::Error::other("it is a device other than NUL, not a regular file")),
            Some(_) => Err(std::io::Error::other("it is a device, not a regular file")),
        }
    }

    pub fn device_by_name(path: &Path) -> Option<String> {
        super::windows_device_name(&path.to_string_lossy())
    }

    /// Devices are told by name on Windows ([`device_by_name`]).
    pub fn is_device(_m: &Metadata) -> bool {
        false
    }

    pub fn is_fifo_or_socket(_m: &Metadata) -> bool {
        false
    }

    pub fn is_null_device(_m: &Metadata) -> bool {
        false
    }

    /// A file's identity: its canonical path (links and `..` resolved, the file system's case).
    pub type FileKey = PathBuf;

    pub fn key(path: &Path, _m: &Metadata) -> Option<FileKey> {
        std::fs::canonicalize(path).ok()
    }

    /// File names compare case-insensitively on Windows.
    pub fn name_key(name: &OsStr) -> OsString {
        name.to_string_lossy().to_lowercase().into()
    }

    /// Not known through std on Windows (no stable link count): see the module's notes.
    pub fn has_other_links(_m: &Metadata) -> bool {
        false
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn windows_device_names() {
        for device in ["NUL", "nul", "C:\\out\\NUL.mcap", "dir/con", "COM1", "lpt9.txt", "NUL ", "c:nul", "AUX.tar.gz"]
        {
            assert!(windows_device_name(device).is_some(), "{device}");
        }
        assert_eq!(windows_device_name("out\\Nul.mcap").as_deref(), Some("NUL"));
        assert_eq!(windows_device_name("\\\\.\\pipe\\log").as_deref(), Some("PIPE\\LOG"));
        for file in ["null", "nul_x.mcap", "C:\\NUL\\x.mcap", "COM10", "console", "run.mcap", "\\\\?\\C:\\x"] {
            assert_eq!(windows_device_name(file), None, "{file}");
        }
    }

    #[cfg(unix)]
    #[test]
    fn symlinks_fifos_and_devices_are_refused_where_they_must_be() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("target.txt");
        std::fs::write(&target, "keep me").unwrap();
        let link = dir.path().join("link.mcap");
        std::os::unix::fs::symlink(&target, &link).unwrap();
        let message = open_output(&link, true, "cannot create").unwrap_err().to_string();
        assert!(message.contains("symbolic link"), "{message}");
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "keep me");
        let fifo = dir.path().join("fifo");
        let c = std::ffi::CString::new(fifo.to_str().unwrap()).unwrap();
        // SAFETY: a valid NUL-terminated path.
        assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0);
        assert!(open_output(&fifo, true, "cannot create").unwrap_err().to_string().contains("FIFO"));
        assert!(open_input(&fifo, "cannot read").unwrap_err().to_string().contains("FIFO"));
        assert!(open_output(Path::new("/dev/null"), true, "cannot create").is_ok());
        assert!(open_output(Path::new("/dev/null"), false, "cannot create")
            .unwrap_err()
            .to_string()
            .contains("device"));
        assert!(open_output(&dir.path().join("new.json"), false, "cannot create").is_ok());
    }
}
