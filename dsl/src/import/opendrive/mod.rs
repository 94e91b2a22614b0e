//! Reader of ASAM OpenDRIVE road networks (`.xodr`, 1.4 to 1.8, read as 1.8):
//! reference lines, lanes, junctions and objects, sampled into the lanes
//! road users travel ([`build`]).
//!
//! [`parse_opendrive`] takes the file's text and returns the network in
//! OpenDRIVE's own terms, or an [`OpenDriveError`] located by line and
//! column; [`build`] samples it into a [`Map`]. What is read and what is
//! left out is in `docs/opendrive.md`: the network is flat (elevation,
//! superelevation and heights are not read).
//!
//! ```
//! use sightline_dsl::import::opendrive;
//! let text = r#"<OpenDRIVE><header revMajor="1" revMinor="8"/>
//!   <road id="1" length="100" junction="-1">
//!     <planView><geometry s="0" x="0" y="0" hdg="0" length="100"><line/></geometry></planView>
//!     <lanes><laneSection s="0"><center><lane id="0" type="none"/></center>
//!       <right><lane id="-1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane></right>
//!     </laneSection></lanes>
//!   </road></OpenDRIVE>"#;
//! let map = opendrive::build(&opendrive::parse_opendrive(text).unwrap()).unwrap();
//! assert_eq!(map.lanes[0].name, "road 1 lane -1");
//! assert_eq!(map.lanes[0].centre, [[0.0, -1.75], [100.0, -1.75]]);
//!
//! let error = opendrive::parse_opendrive(&text.replace("<line/>", "<lien/>")).unwrap_err();
//! assert_eq!(error.to_string(), "3:64: unknown element <lien> in <geometry>: OpenDRIVE 1.8 defines no such \
//!     element there; did you mean <line>?");
//! ```

pub use geometry::{CHAIN_TOLERANCE, Geometry, Pose, Shape};
pub use junctions::{Connection, Contact, Junction};
pub use lanes::{Lane, LaneDirection, LaneSection, LaneUse, Lanes, Poly3, Speed};
pub use map::{JunctionArea, MAX_POINTS, Map, MapLane, MapObject, build};
pub use network::{Element, MAX_COORDINATE, MAX_ROAD_LENGTH, Network, Road, RoadLink, parse_opendrive};
pub use objects::{Corners, Footprint, Object};
pub use xml::{MAX_BYTES, MAX_NODES, OpenDriveError};

mod fresnel;
mod geometry;
mod junctions;
mod lanes;
mod map;
mod network;
mod objects;
mod xml;
