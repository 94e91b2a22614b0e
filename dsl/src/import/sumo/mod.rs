//! Readers for the traffic simulator SUMO's files: floating car data
//! ([`parse_fcd`]), road networks ([`parse_net`]) and polygons ([`parse_poly`]).
//!
//! Each takes the file's text and returns plain data in SUMO's network
//! coordinates (metres), or a [`SumoError`] located by line and column.
//! Geographic coordinates are not supported.
//!
//! ```
//! use sightline_dsl::{AgentKind, import::sumo};
//! let fcd = sumo::parse_fcd(r#"<fcd-export><timestep time="0.00">
//!     <vehicle id="v0" x="5.0" y="1.6" angle="90.00" type="bus" speed="8.0" lane="AB_0"/>
//! </timestep></fcd-export>"#).unwrap();
//! assert_eq!(fcd.objects[0].kind, AgentKind::Bus);
//! assert_eq!(fcd.objects[0].samples[0].heading, 0.0); // SUMO's 90° is east, +x
//!
//! let error = sumo::parse_fcd(r#"<fcd-export><timestep time="soon"/></fcd-export>"#).unwrap_err();
//! assert_eq!(error.to_string(), r#"1:29: attribute `time` of <timestep> is not a number: "soon""#);
//! ```

pub use fcd::{Fcd, FcdObject, FcdSample, parse_fcd};
pub use kind::kind_of;
pub use net::{Connection, DEFAULT_LANE_WIDTH, Edge, Lane, Network, parse_net};
pub use poly::{Polygon, parse_poly};
pub use xml::SumoError;

mod fcd;
mod kind;
mod net;
mod poly;
mod xml;
