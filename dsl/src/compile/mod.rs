//! YAML text → [`Scenario`](crate::Scenario), in named passes:
//! `yaml::parse` (spanned tree) → `de` (raw serde types, located errors) →
//! `traces` and `map` (imported SUMO and OpenDRIVE files, read once through the
//! caller's [`Loader`]) →
//! `setup` (ranges, units, defaults; a world's sections in `world`; the keys the
//! scenario's kind ignores, see `kind`) → `sweep` (one tree per combination, one
//! point per distinct configuration; the keys a combination leaves without
//! effect) → `vary` (the space falsify searches) → `requirements` (ids, checks,
//! `where` filters) → `record` (the recorded point and grid rate) → `system` (the system under
//! test, and what a scenario with one may not ask for) → `Scenario`.
//! `context` collects the located errors of every pass (and the declarations
//! that failed, so what names them is not reported as missing), `checks` holds
//! the checks the sections share (unique ids, points within the world, whole
//! steps), and `budget` the resource model every setup must fit
//! (`docs/limits.md`).

pub(crate) mod budget;
mod checks;
mod compare;
mod context;
mod ignored;
mod kind;
mod map;
mod objects;
mod reader;
mod record;
mod requirements;
mod scenario;
mod setup;
mod sweep;
mod system;
mod traces;
mod vary;
mod world;

pub use scenario::{Loader, Options, compile};
pub use vary::instantiate;
pub(crate) use world::MAX_ROUTE_ROADS;
