//! Reading and compiling scenario files, reporting every problem on stderr.

use std::path::{Path, PathBuf};

use sightline_dsl::{Options, Scenario};

use crate::files::{DATA_LIMIT, TEXT_LIMIT, read_regular};

/// A compiled scenario file and the bytes it was compiled from.
pub struct Input {
    /// The path as given.
    pub path: PathBuf,
    /// The file's bytes (hashed into the evidence).
    pub bytes: Vec<u8>,
    /// The compiled scenario.
    pub scenario: Scenario,
}

/// Reads and compiles every file (`seed` overriding each one's, `record`
/// recording each one as `--record` does), the files it imports read from disk
/// too. Prints every error (as `file:line:col: error: …`) and returns `None` if
/// any file is invalid.
pub fn load_all(paths: &[PathBuf], seed: Option<u64>, record: bool) -> Option<Vec<Input>> {
    let disk = |path: &Path| read_regular(path, DATA_LIMIT);
    let options = Options {
        seed,
        loader: Some(&disk),
        record,
    };
    let mut inputs = Vec::new();
    let mut valid = true;
    for path in paths {
        match load(path, &options) {
            Ok(input) => inputs.push(input),
            Err(message) => {
                eprintln!("{message}");
                valid = false;
            }
        }
    }
    valid.then_some(inputs)
}

fn load(path: &Path, options: &Options<'_>) -> Result<Input, String> {
    let name = path.display().to_string();
    let bytes = read_regular(path, TEXT_LIMIT).map_err(|e| format!("{name}: error: failed to read the file: {e}"))?;
    let text =
        sightline_dsl::utf8_text(&bytes).map_err(|at| format!("{name}:{at}: error: the file is not UTF-8 text"))?;
    let scenario = sightline_dsl::compile(&name, text, options).map_err(|errors| errors.to_string())?;
    Ok(Input {
        path: path.to_path_buf(),
        bytes,
        scenario,
    })
}
