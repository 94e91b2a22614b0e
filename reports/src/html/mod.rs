//! report.html of a run: one self-contained page (inline CSS, no script, no
//! network) for an assessor, rendered from its template
//! ([`Templates`](crate::Templates)). Numbers are formatted here so the template
//! only lays them out.
//!
//! - `page`: the page's view (banner, provenance, context) and [`html`];
//! - `document`: document control, the self-test, the scenario file verbatim;
//! - `scope`: the scope and operational design domain;
//! - `requirement`: each requirement, its check in words and its points;
//! - `sweep`: the results table of each sweep and the published comparisons;
//! - `point`: each point's sample sizes and counts;
//! - `system`: a system under test's road users, one by one;
//! - `format`: numbers for people, and the tables every section lays out.

pub(crate) use document::{DocumentView, content_id, control};
pub(crate) use format::{number, or_dash};
pub use page::{RunPage, html};
pub(crate) use requirement::describe_check;

mod document;
mod format;
mod page;
mod point;
mod requirement;
mod scope;
mod sweep;
mod system;
