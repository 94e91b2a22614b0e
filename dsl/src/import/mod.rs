//! Readers for the files of other tools that a scenario imports, one module
//! per foreign format: [`sumo`] (the traffic simulator SUMO's floating car
//! data, road networks and polygons) and [`opendrive`] (ASAM OpenDRIVE road
//! networks), and what both share, [`xml`].
//!
//! Each reader takes a file's text and returns plain data in the format's own
//! terms, or an error located by line and column; it never touches the file
//! system. The compile pass (`traces`) reads the files through the caller's
//! [`Loader`](crate::Loader) and turns that data into the scenario's roads,
//! occluders and agents.

pub mod opendrive;
pub mod sumo;
pub mod xml;
