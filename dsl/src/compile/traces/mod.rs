//! The `traces` section: SUMO files read once through the caller's
//! [`Loader`](super::Loader) (`files`), parsed, checked against each other, and
//! turned into what every sweep point shares (`load`): the network's roads,
//! interaction areas, crosswalks and walking areas (`network`), the occluders,
//! each traced object's kind and size, and the roadside units of the points of
//! interest (`objects`); [`trace_motion`] and [`imported_agents`] (`replay`)
//! then build the agents.

mod files;
mod load;
mod network;
mod objects;
mod replay;

pub(crate) use load::{Imported, load};
pub(crate) use replay::{imported_agents, trace_motion};
