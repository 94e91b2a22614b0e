//! Charts for the report, drawn by plotters to SVG and embedded as `data:` URIs
//! (the page stays self-contained, and nothing in an SVG is interpolated into the
//! HTML unescaped).
//!
//! - `canvas`: a chart's size, palette, plotting frame and `data:` URI;
//! - `density`: the distribution of anticipation times (a kernel density
//!   estimate over a histogram);
//! - `lines`: lines with markers and published values over a shared x axis;
//! - `reliability`: a world point's reliability diagram;
//! - `semantic`: a semantic point's charts; `sweep`: a sweep's charts;
//! - `margin`: a falsification's margins in the order tried.

pub use canvas::{Chart, ChartError};
pub use density::{anticipation, kde, silverman_bandwidth};
pub use lines::{Line, lines_chart};
pub(crate) use margin::margin_chart;
pub(crate) use reliability::reliability_chart;
pub(crate) use semantic::semantic_charts;
pub(crate) use sweep::sweep_charts;

mod canvas;
mod density;
mod lines;
mod margin;
mod reliability;
mod semantic;
mod sweep;
