//! sightline's scenario language: YAML text in, a typed and validated
//! [`Scenario`] out.
//!
//! This crate owns the language: its syntax (a spanned YAML tree with strict
//! core-schema scalars), its JSON Schema, its checks and its error messages. It
//! does not touch the file system, simulate or print: the CLI hands it text and
//! prints the [`Errors`] it returns, each located as `file:line:col` with a YAML
//! path. A key that would change nothing in its kind of scenario (a radio in
//! collective perception, a grid in a semantic world, a fusion parameter the
//! chosen method ignores) is an error too, [`ErrorKind::NoEffect`], so a
//! verdict never rests on a setting that was silently ignored.
//!
//! The [`import`] tree reads other tools' files the same way, text in and
//! located errors out, one module per format: [`import::sumo`] reads traffic
//! from the simulator SUMO, [`import::opendrive`] road networks in ASAM
//! OpenDRIVE. A scenario that imports files (`traces`, `map`) has them read
//! through the [`Loader`] the caller puts in [`Options`]; the compiled
//! [`Scenario`] keeps their bytes (`imports`) for the evidence.
//!
//! ```
//! let text = "sightline: 1\nname: tiny\ngrid: { size: [10, 10], cell: 1 }\n\
//!             field:\n  truth: { occupied_fraction: 0.2 }\n  sensors: { range: 8, layout: { regular: { rows: 1, cols: 2 } } }\n  masses: { gamma: 10 }\n";
//! let scenario = sightline_dsl::compile("tiny.yaml", text, &Default::default()).unwrap();
//! assert_eq!(scenario.points.len(), 1);
//! assert_eq!(scenario.points[0].setup.occupancy.as_ref().unwrap().grid.cells(), 100);
//!
//! let bad = text.replace("gamma: 10", "gamma: -3");
//! let errors = sightline_dsl::compile("bad.yaml", &bad, &Default::default()).unwrap_err();
//! assert_eq!(errors.to_string(), "bad.yaml:7:20: error: field.masses.gamma: expected a number ≥ 0, found -3");
//! ```
#![warn(missing_docs)]

pub use compile::budget::{MAX_RUN_LOAD, load as point_load};
pub use compile::{Loader, Options, compile, instantiate};
pub use error::{Error, ErrorKind, Errors, Location, Warning, utf8_text};
pub use model::*;
pub use schema::{reference_markdown, schema, setting_unit};

mod compile;
mod de;
mod emit;
mod error;
pub mod geometry;
pub mod import;
mod model;
mod path;
mod raw;
mod schema;
mod yaml;
