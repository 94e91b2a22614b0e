//! Seed 002's infrastructure-assisted ego: generated traffic, roadside units with
//! a local dynamic map and a four-layer semantic pipeline, the V2X link to the
//! ego, and what the ego gains from it.

mod ego;
mod ldm;
mod map;
mod measure;
mod message;
mod metrics;
mod pipeline;
mod radio;
mod relevance;
mod risk;
mod rsu;
mod simulate;
mod traffic;

pub use ego::KNOWN_FOR;
pub use ldm::{Ldm, Measurement, Track};
pub use map::route_map;
pub use message::{EtsiSender, Item, Labels, baseline_bytes, semantic_bytes};
pub use metrics::{DELIVERY_BIN, DENSITY_BIN, DeliveryBin, DensityRow, LabelCounts, SemanticMetrics, Series, quantile};
pub use pipeline::{EgoPlan, Pipeline};
pub use relevance::{Areas, approaches, contains, crosswalk_area};
pub use risk::{
    Conflict, MAX_BRANCHES, MapRoute, RouteMap, Trajectory, along, conflict, hypotheses, lane_routes, straight,
};
pub use simulate::run;
pub use traffic::scene;

pub(crate) use rsu::rsu_sight_idealisations;
pub(crate) use simulate::idealisations;
