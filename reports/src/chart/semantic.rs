//! A semantic point's charts: its anticipation times, the objects the ego
//! knows only through an RSU by traffic density, and the delivery ratio of the
//! RSU's messages by distance.

use sightline_engine::outcome::{DELIVERY_BIN, DENSITY_BIN};

use super::canvas::{Chart, ChartError};
use super::density::anticipation;
use super::lines::{Line, LinesChart};
use crate::results::{DensityRow, SemanticCounts};

/// A semantic point's charts: its anticipation times, the objects the ego knows
/// only through an RSU by traffic density (median and mean per bin), and the
/// delivery ratio of the RSU's messages by distance.
pub(crate) fn semantic_charts(m: &SemanticCounts, rows: &[DensityRow]) -> Result<Vec<Chart>, ChartError> {
    let centre = |from: f64| from + DENSITY_BIN / 2.0;
    let by_density = [
        Line {
            name: "median".into(),
            points: rows.iter().map(|r| (centre(r.from), r.median)).collect(),
        },
        Line {
            name: "mean".into(),
            points: rows.iter().map(|r| (centre(r.from), r.mean)).collect(),
        },
    ];
    let delivery = [Line {
        name: "delivered / sent".into(),
        points: m
            .delivery_by_distance
            .iter()
            .enumerate()
            .filter(|(_, b)| b.sent > 0)
            .map(|(i, b)| ((i as f64 + 0.5) * DELIVERY_BIN, b.received as f64 / b.sent as f64))
            .collect(),
    }];
    let by_density = LinesChart {
        caption: format!(
            "Objects the ego knows only through an RSU, by the scene's density ({DENSITY_BIN} objects/km bins, at their centres)."
        ),
        x_desc: "scene density (objects/km)".into(),
        y_desc: "objects known only through an RSU (objects)".into(),
        lines: by_density.to_vec(),
        published: Vec::new(),
        thresholds: Vec::new(),
    };
    let delivery = LinesChart {
        caption: format!("Share of the RSU's messages that reach the ego, by distance ({DELIVERY_BIN} m bins)."),
        x_desc: "RSU–ego distance (m)".into(),
        y_desc: "delivery ratio (1)".into(),
        lines: delivery.to_vec(),
        published: Vec::new(),
        thresholds: Vec::new(),
    };
    let mut charts: Vec<Chart> = anticipation(&m.anticipation)?.into_iter().collect();
    charts.extend(by_density.draw()?);
    charts.extend(delivery.draw()?);
    Ok(charts)
}
