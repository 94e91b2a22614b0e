//! Self-localization: each connected agent estimates its own pose from noisy
//! self-reported measurements of (x, y, θ) (seed 000).
//!
//! The Kalman filter is an extended one on the state (x, y, θ): the prediction
//! composes the estimate with the agent's own motion since the last step (its
//! odometry, taken as exact) and adds process noise Q = diag(qₚ², qₚ², q_θ²)·dt;
//! the update fuses the measurement z = true pose + N(0, diag(σₚ², σₚ², σ_θ²)),
//! with the heading innovation wrapped to (−π, π]. The first measurement
//! initialises the estimate. With `filter: none`, or when measurements are exact
//! (σ = 0, where the filter's gain is the identity), the estimate is the
//! measurement itself, so zero noise gives exactly the true pose.

use nalgebra::{Matrix3, Vector3};
use rand::rngs::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};
use sightline_dsl::{Localization, PoseFilter};

use crate::idealisation::Idealisation;
use crate::math::{Pose, Vector};

/// Pose measurements are white and Gaussian.
pub(crate) const WHITE_NOISE: Idealisation = Idealisation {
    id: "localization.white-noise",
    text: "Self-reported pose measurements are unbiased Gaussian, independent from step to step: no bias, no \
           drift, no multipath.",
};

/// No localization error at all.
pub(crate) const EXACT: Idealisation = Idealisation {
    id: "localization.exact",
    text: "Localization is exact (`position_sigma` and `heading_sigma_deg` are 0): every agent places its grid \
           with its true pose.",
};

/// The Kalman filter's prediction uses perfect odometry.
pub(crate) const EXACT_ODOMETRY: Idealisation = Idealisation {
    id: "localization.exact-odometry",
    text: "The Kalman filter predicts with the agent's exact motion since the last step (perfect odometry): \
           only the pose measurements are noisy.",
};

/// The idealisations of a pose filter, besides those of the measurements.
pub(crate) fn filter_idealisations(filter: PoseFilter) -> &'static [Idealisation] {
    match filter {
        PoseFilter::Kalman => &[EXACT_ODOMETRY],
        // The estimate is the measurement: nothing is assumed beyond it.
        PoseFilter::None => &[],
    }
}

/// One agent's pose estimate.
#[derive(Debug, Clone)]
pub struct PoseEstimator {
    settings: Localization,
    state: Option<(Vector3<f64>, Matrix3<f64>)>,
    last_true: Option<Pose>,
}

impl PoseEstimator {
    /// An estimator that has seen no measurement yet.
    pub fn new(settings: Localization) -> Self {
        Self {
            settings,
            state: None,
            last_true: None,
        }
    }

    /// Takes the step's measurement of `true_pose` (drawn from `rng`) and returns
    /// the estimate after it. `dt` is the time since the previous call.
    pub fn estimate(&mut self, true_pose: Pose, dt: f64, rng: &mut ChaCha8Rng) -> Pose {
        let s = self.settings;
        let mut noise = || -> f64 { StandardNormal.sample(rng) };
        let truth = pose_vector(true_pose);
        let measurement = truth
            + Vector3::new(
                s.position_sigma * noise(),
                s.position_sigma * noise(),
                s.heading_sigma * noise(),
            );
        let motion = self.last_true.map(|last| last.inverse() * true_pose);
        self.last_true = Some(true_pose);
        let r = Matrix3::from_diagonal(&Vector3::new(
            s.position_sigma.powi(2),
            s.position_sigma.powi(2),
            s.heading_sigma.powi(2),
        ));
        let estimate = match (s.filter, self.state, motion) {
            (PoseFilter::Kalman, Some((x, p)), Some(u)) => {
                let (x, p) = predict(x, p, u, dt, &s);
                update(x, p, measurement, r)
            }
            _ => (measurement, r),
        };
        self.state = Some(estimate);
        // Exact measurements (the noise was still drawn, so that every noise level
        // of a sweep scales the same draws) give the true pose itself, not a copy
        // rounded through (x, y, θ).
        if s.position_sigma == 0.0 && s.heading_sigma == 0.0 {
            true_pose
        } else {
            vector_pose(estimate.0)
        }
    }
}

fn pose_vector(pose: Pose) -> Vector3<f64> {
    Vector3::new(pose.translation.x, pose.translation.y, pose.rotation.angle())
}

fn vector_pose(v: Vector3<f64>) -> Pose {
    Pose::new(Vector::new(v.x, v.y), v.z)
}

/// x ← x ∘ u, P ← F P Fᵀ + Q dt.
fn predict(x: Vector3<f64>, p: Matrix3<f64>, u: Pose, dt: f64, s: &Localization) -> (Vector3<f64>, Matrix3<f64>) {
    let (sin, cos) = x.z.sin_cos();
    let (ux, uy) = (u.translation.x, u.translation.y);
    let predicted = Vector3::new(
        x.x + cos * ux - sin * uy,
        x.y + sin * ux + cos * uy,
        x.z + u.rotation.angle(),
    );
    let f = Matrix3::new(
        1.0,
        0.0,
        -sin * ux - cos * uy,
        0.0,
        1.0,
        cos * ux - sin * uy,
        0.0,
        0.0,
        1.0,
    );
    let q = Matrix3::from_diagonal(&Vector3::new(
        s.process_position_sigma.powi(2),
        s.process_position_sigma.powi(2),
        s.process_heading_sigma.powi(2),
    )) * dt;
    (predicted, f * p * f.transpose() + q)
}

/// The measurement update with H = I.
fn update(x: Vector3<f64>, p: Matrix3<f64>, z: Vector3<f64>, r: Matrix3<f64>) -> (Vector3<f64>, Matrix3<f64>) {
    let mut innovation = z - x;
    innovation.z = innovation.z.sin().atan2(innovation.z.cos());
    // P + R is positive definite: Q > 0 (the dsl keeps the process noise positive).
    let gain = p * (p + r).try_inverse().expect("P + R is invertible");
    (x + gain * innovation, (Matrix3::identity() - gain) * p)
}

#[cfg(test)]
mod tests {
    use approx::assert_relative_eq;

    use super::*;
    use crate::rng::{Purpose, stream};

    fn settings(filter: PoseFilter, sigma: f64) -> Localization {
        Localization {
            position_sigma: sigma,
            heading_sigma: 0.0,
            filter,
            process_position_sigma: 0.1,
            process_heading_sigma: 0.01,
        }
    }

    /// RMS position error of the estimate of an agent driving 10 m/s along x.
    fn rms_error(filter: PoseFilter, sigma: f64) -> f64 {
        let mut estimator = PoseEstimator::new(settings(filter, sigma));
        let mut rng = stream(9, Purpose::Localization, 0);
        let n = 2000;
        let mut sum = 0.0;
        for k in 0..n {
            let truth = Pose::new(Vector::new(k as f64, 3.0), 0.0);
            let estimate = estimator.estimate(truth, 0.1, &mut rng);
            if k >= 100 {
                sum += (estimate.translation - truth.translation).length_squared();
            }
        }
        (sum / (n - 100) as f64).sqrt()
    }

    #[test]
    fn without_noise_the_estimate_is_exactly_the_truth() {
        let mut estimator = PoseEstimator::new(settings(PoseFilter::Kalman, 0.0));
        let mut rng = stream(1, Purpose::Localization, 0);
        for k in 0..20 {
            let truth = Pose::new(Vector::new(k as f64, 0.5 * k as f64), 0.1 * k as f64);
            assert_eq!(estimator.estimate(truth, 0.1, &mut rng), truth);
        }
    }

    /// The raw measurement has an RMS position error of σ√2 (two axes); the filter,
    /// which also knows the motion, does markedly better.
    #[test]
    fn the_filter_reduces_the_measurement_error() {
        let raw = rms_error(PoseFilter::None, 0.5);
        assert_relative_eq!(raw, 0.5 * 2.0_f64.sqrt(), max_relative = 0.08);
        let filtered = rms_error(PoseFilter::Kalman, 0.5);
        assert!(filtered < 0.5 * raw, "filtered {filtered} vs raw {raw}");
    }
}
