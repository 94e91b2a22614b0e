//! Readers for the traffic simulator SUMO's files: configurations
//! ([`parse_config`]), floating car data ([`parse_fcd`]), road networks
//! ([`parse_net`]), and additional and route files ([`parse_additional`]:
//! polygons, points of interest, vehicle types); and what SUMO's vehicle
//! classes are in sightline ([`vehicle_class`]).
//!
//! Each takes the file's text and returns plain data in SUMO's network
//! coordinates (metres, each within the world's ±1e6 m), or a [`SumoError`]
//! located by line and column.
//! Geographic coordinates are not supported.
//!
//! ```
//! use sightline_dsl::import::sumo;
//! let fcd = sumo::parse_fcd(r#"<fcd-export><timestep time="0.00">
//!     <vehicle id="v0" x="5.0" y="1.6" angle="90.00" type="bus" speed="8.0" lane="AB_0"/>
//! </timestep></fcd-export>"#).unwrap();
//! assert_eq!(fcd.objects[0].vtype, "bus");
//! assert_eq!(fcd.objects[0].samples[0].heading, 0.0); // SUMO's 90° is east, +x
//!
//! let error = sumo::parse_fcd(r#"<fcd-export><timestep time="soon"/></fcd-export>"#).unwrap_err();
//! assert_eq!(error.to_string(), r#"1:29: attribute `time` of <timestep> is not a number: "soon""#);
//! ```

pub use additional::{Additional, Poi, PoiAt, Polygon, VType, parse_additional};
pub use config::{Config, ConfigFile, parse_config};
pub use fcd::{Fcd, FcdObject, FcdSample, Timestep, parse_fcd};
pub use net::{Connection, DEFAULT_LANE_WIDTH, Edge, Junction, Lane, Network, parse_net};
pub use vclass::{CLASSES, Replay, VehicleClass, builtin_class, kind_of, shape_kind, vehicle_class};
pub use xml::{MAX_ATTRIBUTES, MAX_ELEMENTS, SumoError};

mod additional;
mod config;
mod fcd;
mod net;
mod vclass;
mod xml;
