//! Opening files that a run writes, safely: never through a symbolic link at the last component
//! (writing would truncate the link's target), never a FIFO or a socket (opening one blocks until
//! a reader appears: the run, or the FMU's host, would hang), a device only where the caller
//! allows it (the CLI's `/dev/null`). Opening never blocks: `O_NONBLOCK` is set for the open
//! and the file type is checked on the opened descriptor, so there is no race with a swap.

use std::fs::File;
use std::os::unix::fs::{FileTypeExt, OpenOptionsExt};
use std::path::Path;

use crate::error::{Error, Result};

/// Opens `path` for writing, creating it if needed, without truncating it (the caller truncates
/// once it holds the file, e.g. after taking a lock). `what` names the file in errors.
pub fn open_output(path: &Path, allow_devices: bool, what: &'static str) -> Result<File> {
    let io = |source| Error::Io { action: what, path: path.display().to_string(), source };
    let file = std::fs::OpenOptions::new()
        .write(true)
        .create(true)
        .truncate(false)
        .custom_flags(libc::O_NOFOLLOW | libc::O_NONBLOCK)
        .open(path)
        .map_err(|e| match e.raw_os_error() {
            Some(libc::ELOOP) => io(std::io::Error::other("it is a symbolic link; give the link's target instead")),
            Some(libc::ENXIO) => io(std::io::Error::other("it is a FIFO without a reader")),
            _ => io(e),
        })?;
    check_kind(&file, allow_devices).map_err(io)?;
    Ok(file)
}

/// Opens `path` for reading (symbolic links are followed: reading through one harms nothing),
/// refusing a FIFO or a socket, which would block the read.
pub fn open_input(path: &Path, what: &'static str) -> Result<File> {
    let io = |source| Error::Io { action: what, path: path.display().to_string(), source };
    let file = std::fs::OpenOptions::new().read(true).custom_flags(libc::O_NONBLOCK).open(path).map_err(io)?;
    check_kind(&file, true).map_err(io)?;
    Ok(file)
}

fn check_kind(file: &File, allow_devices: bool) -> std::io::Result<()> {
    let kind = file.metadata()?.file_type();
    if kind.is_fifo() || kind.is_socket() {
        return Err(std::io::Error::other("it is a FIFO or a socket, not a regular file (use - for standard input)"));
    }
    if (kind.is_char_device() || kind.is_block_device()) && !allow_devices {
        return Err(std::io::Error::other("it is a device, not a regular file"));
    }
    if kind.is_dir() {
        return Err(std::io::Error::other("it is a directory"));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

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
