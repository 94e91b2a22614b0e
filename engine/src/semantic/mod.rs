//! Seed 002's infrastructure-assisted ego: generated traffic, roadside units with
//! a local dynamic map and a four-layer semantic pipeline, the V2X link to the
//! ego, and what the ego gains from it.

mod criticality;
mod ego;
mod ldm;
mod map;
mod measure;
mod message;
mod metrics;
mod objects;
mod pipeline;
mod radio;
mod relevance;
mod risk;
mod rsu;
mod selection;
mod simulate;
mod traffic;

pub use message::{Item, Labels};
pub use metrics::{DELIVERY_BIN, DENSITY_BIN, DeliveryBin, DensityRow, LabelCounts, SemanticMetrics};
pub use objects::{Category, CloseApproach, Closest, ObjectRecord};
pub use risk::Conflict;
pub use simulate::{first_run, run};

/// The pipeline's pieces, for the engine's benches (feature `internals`).
#[cfg(feature = "internals")]
pub use {
    ldm::{Ldm, Measurement},
    map::route_map,
    pipeline::{EgoPlan, Pipeline},
    relevance::Areas,
};

pub(crate) use criticality::{Criticality, OrientedBox, post_encroachment};
pub(crate) use relevance::{Region, contains, regions};
pub(crate) use rsu::rsu_sight_idealisations;
pub(crate) use selection::keeps;
pub(crate) use simulate::{Ground, Layer, idealisations};
pub(crate) use traffic::scene;
