//! The static field experiment of seed 001: ground truth, fixed sensors, a mass model.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// A static occupancy field observed by fixed sensors, each reporting a mass vector
/// (Empty, Occupy, Unknown) for every cell within its range.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Field {
    /// How the ground truth is drawn.
    pub truth: Truth,
    /// Sensing radius R, metres.
    pub range: f64,
    /// Where the sensors are.
    pub layout: Layout,
    /// How each sensor's mass vector is drawn.
    pub masses: Masses,
    /// Upper edges of the distance bands metrics are split by, metres, increasing.
    /// A last band collects everything beyond the last edge.
    pub distance_bands: Vec<f64>,
}

/// The ground-truth generator.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Truth {
    /// Probability that a blob is occupied.
    pub occupied_fraction: f64,
    /// Side of a square blob, in cells (1: every cell independent).
    pub blob_cells: usize,
}

/// Sensor positions.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Layout {
    /// Fixed positions in the world frame, metres.
    Positions(Vec<[f64; 2]>),
    /// `count` positions drawn uniformly over the grid from the scenario seed.
    Random {
        /// Number of sensors.
        count: usize,
    },
}

/// The sensor mass model.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Masses {
    /// Sum of the three Dirichlet parameters (paper: 30 + 1 + 1 = 32).
    pub concentration: f64,
    /// ε0: misdetection at distance 0.
    pub epsilon0: f64,
    /// γ: misdetection grows by γ/100 from the sensor to its range R.
    pub gamma: f64,
    /// How misdetection enters the mass vector.
    pub error_model: ErrorModel,
}

/// How the misdetection ε(d) shapes a sensor's mass vector. The paper says ε is
/// "the probability that a truly empty cell is output as Occupy or Unknown" and
/// that ε0 = 0.0625 "corresponds to" Dirichlet(30, 1, 1); it does not say which
/// of the readings below it means.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum ErrorModel {
    /// The mass vector is drawn from a Dirichlet whose mean puts 1 − ε on the true
    /// state and ε/2 on each other state, with the total concentration fixed
    /// (at d = 0 and concentration 32 this is Dirichlet(30, 1, 1)).
    #[default]
    DirichletMean,
    /// With probability ε the sensor reports a wrong label (truly empty: Occupy or
    /// Unknown, ε/2 each; truly occupied: Empty), otherwise the true one; the mass
    /// vector is Dirichlet(concentration·(1 − ε0), concentration·ε0/2, concentration·ε0/2)
    /// centred on the reported label.
    WrongLabel,
    /// As `dirichlet_mean` for a truly empty cell; for a truly occupied cell the
    /// mean puts ε on Empty, 1 − ε on Occupy and nothing on Unknown (the text's
    /// "misdetection probability toward Empty"): a Beta(concentration·ε,
    /// concentration·(1 − ε)) split between Empty and Occupy, so that an occupied
    /// cell is never reported with Unknown mass.
    DirichletTowardEmpty,
}
