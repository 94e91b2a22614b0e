//! The world sections: ids, ranges, geometry resolved into lane polylines, routes
//! checked for connectivity and resolved into one path per vehicle, and seed
//! 002's sections (`semantic`), and what a joint world (both) refuses
//! (`joint`). `assemble` compiles them in order into a [`World`](crate::World).

mod agents;
mod assemble;
mod joint;
mod occluders;
mod perception;
mod roads;
mod routes;
mod semantic;
mod sensors;

pub(super) use assemble::world;
pub(crate) use routes::MAX_ROUTE_ROADS;
