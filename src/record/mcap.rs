//! MCAP recorder. STUB: the API is fixed, the body is to be written (issue 4).

use std::path::{Path, PathBuf};

use super::{Recorder, RunInfo};
use crate::error::{Error, Result};
use crate::results::{ContactEvent, StepResult};

/// Writes every step of a run to an MCAP file.
#[derive(Debug)]
pub struct McapRecorder {
    path: PathBuf,
}

impl McapRecorder {
    /// Creates (truncates) the file at `path`; the error names the path.
    pub fn create(path: &Path) -> Result<Self> {
        std::fs::File::create(path).map_err(|source| Error::Io {
            action: "cannot create MCAP log",
            path: path.display().to_string(),
            source,
        })?;
        Ok(McapRecorder { path: path.to_path_buf() })
    }

    /// Adds an attachment (the FMU's modelDescription.xml, for example).
    pub fn attach(&mut self, _name: &str, _media_type: &str, _data: &[u8]) -> Result<()> {
        Ok(())
    }

    /// The file being written.
    pub fn path(&self) -> &Path {
        &self.path
    }
}

impl Recorder for McapRecorder {
    fn start(&mut self, _info: &RunInfo<'_>) -> Result<()> {
        Ok(())
    }
    fn step(&mut self, _result: &StepResult, _modal_coordinates: &[f64]) -> Result<()> {
        Ok(())
    }
    fn contact_event(&mut self, _event: &ContactEvent) -> Result<()> {
        Ok(())
    }
    fn finish(&mut self) -> Result<()> {
        Ok(())
    }
}
