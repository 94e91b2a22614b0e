//! Reading an imported file (a SUMO file of `traces`, the OpenDRIVE map of
//! `map`) through the caller's [`Loader`]: each read once, parsed, recorded
//! for the evidence, and every failure reported where the file is named or
//! where in it the parser stopped.

use std::path::Path as FsPath;

use sha2::{Digest, Sha256};

use crate::compile::Loader;
use crate::compile::context::Context;
use crate::error::{Error, ErrorKind, Location, utf8_text};
use crate::import::xml::XmlError;
use crate::model::{Import, ImportKind};
use crate::path::Path;

/// A file failed to load or parse; the error is recorded.
pub(crate) struct Failed;

/// Where a file is named: a key of the scenario, or a value in the configuration.
#[derive(Clone)]
pub(crate) enum Named {
    /// At this key of the scenario.
    Scenario(Path),
    /// In another file (a SUMO configuration) at this path, at this location.
    Config(String, Location),
}

/// Reads imported files, recording each and every failure.
pub(crate) struct Reader<'c, 'a, 'f> {
    pub(crate) ctx: &'c mut Context<'a>,
    pub(crate) loader: Option<&'f dyn Loader>,
    /// Every file read, for the evidence.
    pub(crate) imports: Vec<Import>,
}

impl Reader<'_, '_, '_> {
    /// Reads the file at `path` and parses it; a failure to read is an error
    /// where it is named, a malformed file an error in it. `by_scenario`: the
    /// scenario names it itself (so `falsify` rewrites its path).
    pub(crate) fn read<T>(
        &mut self,
        named: &Named,
        path: &FsPath,
        kind: ImportKind,
        by_scenario: bool,
        parse: impl Fn(&str) -> Result<T, XmlError>,
    ) -> Result<T, Failed> {
        let file = path.display().to_string();
        let bytes = match self.loader.map(|loader| loader.load(path)) {
            Some(Ok(bytes)) => bytes,
            failed => {
                let reason = match failed {
                    Some(Err(error)) => error.to_string(),
                    _ => "this compilation was given no file loader".into(),
                };
                let kind = ErrorKind::Io { file, reason };
                match named {
                    Named::Scenario(at) => self.ctx.error(at, kind),
                    Named::Config(config, location) => self.ctx.errors.push(Error {
                        file: config.clone(),
                        location: *location,
                        path: String::new(),
                        kind,
                    }),
                }
                return Err(Failed);
            }
        };
        let parsed = match utf8_text(&bytes) {
            Ok(text) => parse(text).map_err(|e| (e.location, e.message)),
            Err(location) => Err((location, "the file is not UTF-8 text".into())),
        };
        match parsed {
            Ok(value) => {
                self.imports.push(Import {
                    kind,
                    path: file,
                    sha256: Sha256::digest(&bytes).into(),
                    bytes,
                    named: by_scenario,
                });
                Ok(value)
            }
            Err((location, message)) => {
                self.ctx.errors.push(Error {
                    file,
                    location,
                    path: String::new(),
                    kind: ErrorKind::Import(message),
                });
                Err(Failed)
            }
        }
    }
}
