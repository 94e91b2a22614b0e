//! Charts for the report, drawn by plotters to SVG and embedded as `data:` URIs
//! (the page stays self-contained, and nothing in an SVG is interpolated into the
//! HTML unescaped). Every chart is 1 280 px wide, its legend in a box below the
//! plot.
//!
//! - `canvas`: a chart's size and type, the plotting frame, the `data:` URI;
//! - `figure`: a chart drawn: the plot, framed, and the legend below it;
//! - `style`: the palette, line styles and markers that tell series apart;
//! - `legend`: the legend below the plot;
//! - `density`: the distribution of anticipation times (a kernel density
//!   estimate over a histogram);
//! - `lines`: lines with markers, published values and requirement thresholds
//!   over a shared x axis;
//! - `reliability`: a world point's reliability diagram;
//! - `semantic`: a semantic point's charts; `sweep`: a sweep's charts;
//! - `margin`: a falsification's margins in the order tried.

pub use canvas::{Chart, ChartError};
pub use density::{anticipation, kde, silverman_bandwidth};
pub use lines::{Line, LinesChart, Threshold};
pub(crate) use margin::margin_chart;
pub(crate) use reliability::reliability_chart;
pub(crate) use semantic::semantic_charts;
pub(crate) use sweep::sweep_charts;

mod canvas;
mod density;
mod figure;
mod legend;
mod lines;
mod margin;
mod reliability;
mod semantic;
mod style;
#[cfg(test)]
mod svg;
mod sweep;
