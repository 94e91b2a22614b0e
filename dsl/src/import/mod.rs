//! Readers for the files of other tools that a scenario imports, one module
//! per foreign format: [`sumo`] (the traffic simulator SUMO's floating car
//! data, road networks and polygons) and [`opendrive`] (ASAM OpenDRIVE road
//! networks); OpenSCENARIO scenarios are to follow here (issue 19).
//!
//! Each reader takes a file's text and returns plain data in the format's own
//! terms, or an error located by line and column; it never touches the file
//! system. The compile pass (`traces`) reads the files through the caller's
//! [`Loader`](crate::Loader) and turns that data into the scenario's roads,
//! occluders and agents.

pub mod opendrive;
pub mod sumo;

/// A problem a reader found in a file, located in it: what the compile pass
/// needs to report it as `file:line:col: error: message`.
pub(crate) trait Problem {
    /// Where in the file.
    fn location(&self) -> crate::Location;
    /// What is wrong.
    fn message(&self) -> &str;
}

impl Problem for sumo::SumoError {
    fn location(&self) -> crate::Location {
        self.location
    }

    fn message(&self) -> &str {
        &self.message
    }
}

impl Problem for opendrive::OpenDriveError {
    fn location(&self) -> crate::Location {
        self.location
    }

    fn message(&self) -> &str {
        &self.message
    }
}
