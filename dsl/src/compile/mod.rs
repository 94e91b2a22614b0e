//! YAML text → [`Scenario`](crate::Scenario), in named passes:
//! `yaml::parse` (spanned tree) → `de` (raw serde types, located errors) →
//! `traces` (imported SUMO files, read once through the caller's [`Loader`]) →
//! `setup` (ranges, units, defaults; the keys the scenario's kind ignores, see
//! `kind`) → `sweep` (one tree per combination, one point per distinct
//! configuration; the keys a combination leaves without effect) → `vary` (the
//! space falsify searches) →
//! `requirements` (ids, checks, `where` filters) → `record` (the recorded
//! point and grid rate) → `Scenario`.

mod context;
mod kind;
mod record;
mod requirements;
mod scenario;
mod semantic;
mod setup;
mod sweep;
mod traces;
mod vary;
mod world;

pub use scenario::{Loader, Options, compile};
pub use vary::instantiate;
