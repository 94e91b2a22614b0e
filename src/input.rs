//! Reading and compiling scenario files, reporting every problem on stderr.

use std::path::{Path, PathBuf};

use sightline_dsl::{Options, Scenario};

/// A compiled scenario file and the bytes it was compiled from.
pub struct Input {
    /// The path as given.
    pub path: PathBuf,
    /// The file's bytes (hashed into the evidence).
    pub bytes: Vec<u8>,
    /// The compiled scenario.
    pub scenario: Scenario,
}

/// Reads and compiles every file. Prints every error (as `file:line:col: error: …`)
/// and returns `None` if any file is invalid.
pub fn load_all(paths: &[PathBuf], options: &Options) -> Option<Vec<Input>> {
    let mut inputs = Vec::new();
    let mut valid = true;
    for path in paths {
        match load(path, options) {
            Ok(input) => inputs.push(input),
            Err(message) => {
                eprintln!("{message}");
                valid = false;
            }
        }
    }
    valid.then_some(inputs)
}

fn load(path: &Path, options: &Options) -> Result<Input, String> {
    let name = path.display().to_string();
    let bytes = std::fs::read(path).map_err(|e| format!("{name}: error: failed to read the file: {e}"))?;
    let text = std::str::from_utf8(&bytes).map_err(|e| {
        let valid = &bytes[..e.valid_up_to()];
        let line_start = valid.iter().rposition(|&b| b == b'\n').map_or(0, |i| i + 1);
        let line = valid.iter().filter(|&&b| b == b'\n').count() + 1;
        // The prefix is valid UTF-8, so its characters can be counted.
        let column = String::from_utf8_lossy(&valid[line_start..]).chars().count() + 1;
        format!("{name}:{line}:{column}: error: the file is not UTF-8 text")
    })?;
    let scenario = sightline_dsl::compile(&name, text, options).map_err(|errors| errors.to_string())?;
    Ok(Input {
        path: path.to_path_buf(),
        bytes,
        scenario,
    })
}
