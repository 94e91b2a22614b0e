//! Self-localization: each connected agent estimates its own pose from noisy
//! self-reported measurements of (x, y, θ) (seed 000).
//!
//! The Kalman filter is an extended one on the state (x, y, θ): the prediction
//! composes the estimate with the agent's motion since the last step as its
//! odometry reports it, and adds process noise Q = diag(qₚ², qₚ², q_θ²)·dt; the
//! update fuses the measurement z = true pose + N(0, diag(σₚ², σₚ², σ_θ²)),
//! with the heading innovation wrapped to (−π, π]. The first measurement
//! initialises the estimate. With `filter: none`, or when measurements are exact
//! (σ = 0, where the filter's gain is the identity), the estimate is the
//! measurement itself, so zero noise gives exactly the true pose.
//!
//! Odometry (`localization.odometry`) is exact (the true motion) or noisy: a
//! speed and a yaw rate read once per step, v̂ = v·(1 + b_v) + σ_v·n₁ and
//! ω̂ = ω + b_ω + σ_ω·n₂, from which the step's motion is re-integrated along
//! the true direction of travel (the chord of the step). The filter adds the
//! readings' white noise to Q (it knows the sensors' noise, not their biases).
//! The draws n₁, n₂ of step k come from block k of the agent's odometry stream,
//! so they depend on the seed, the agent and the step only.

use nalgebra::{Matrix3, Vector2, Vector3};
use rand::rngs::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};
use sightline_dsl::{Localization, Odometry, OdometryModel, OdometryNoise, PoseFilter};

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
    text: "The Kalman filter predicts with the agent's exact motion since the last step (perfect odometry, \
           `odometry.model: exact`): only the pose measurements are noisy.",
};

/// What noisy odometry still takes as given.
pub(crate) const NOISY_ODOMETRY: Idealisation = Idealisation {
    id: "localization.noisy-odometry",
    text: "The Kalman filter predicts with a speed and a yaw rate read once per step with white Gaussian noise \
           and a constant bias (`localization.odometry`), but along the true direction of travel (no side slip, \
           no wheel slip); no reading is missing, late or quantized, the biases do not drift over a run, and \
           the white noise is known to the filter.",
};

/// The idealisations of a pose filter, besides those of the measurements and
/// of its odometry.
pub(crate) fn filter_idealisations(filter: PoseFilter) -> &'static [Idealisation] {
    match filter {
        // The filter is the agent's own estimator: what it assumes of the
        // agent's motion is its odometry's ([`odometry_idealisations`]).
        PoseFilter::Kalman => &[],
        // The estimate is the measurement: nothing is assumed beyond it.
        PoseFilter::None => &[],
    }
}

/// The idealisations of the odometry a Kalman filter predicts with.
pub(crate) fn odometry_idealisations(model: OdometryModel) -> &'static [Idealisation] {
    match model {
        OdometryModel::Exact => &[EXACT_ODOMETRY],
        OdometryModel::Noisy => &[NOISY_ODOMETRY],
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

    /// Takes the step's measurement of `true_pose` (drawn from `measurements`)
    /// and returns the estimate after it. `dt` is the time since the previous
    /// call; `odometry` is the agent's odometry stream, at the step's block.
    pub fn estimate(
        &mut self,
        true_pose: Pose,
        dt: f64,
        measurements: &mut ChaCha8Rng,
        odometry: &mut ChaCha8Rng,
    ) -> Pose {
        let s = self.settings;
        let mut noise = || -> f64 { StandardNormal.sample(measurements) };
        let truth = pose_vector(true_pose);
        let measurement = truth
            + Vector3::new(
                s.position_sigma * noise(),
                s.position_sigma * noise(),
                s.heading_sigma * noise(),
            );
        let motion = self
            .last_true
            .map(|last| read(&s.odometry, last.inverse() * true_pose, dt, odometry));
        self.last_true = Some(true_pose);
        let r = Matrix3::from_diagonal(&Vector3::new(
            s.position_sigma.powi(2),
            s.position_sigma.powi(2),
            s.heading_sigma.powi(2),
        ));
        let estimate = match (s.filter, self.state, motion) {
            (PoseFilter::Kalman, Some((x, p)), Some(reading)) => {
                let (x, p) = predict(x, p, reading, dt, &s);
                update(x, p, measurement, r)
            }
            _ => (measurement, r),
        };
        self.state = Some(estimate);
        // Exact measurements (the noise was still drawn, so that every noise level
        // of a sweep scales the same draws) give the true pose itself, not a copy
        // rounded through (x, y, θ).
        if s.is_exact() {
            true_pose
        } else {
            vector_pose(estimate.0)
        }
    }
}

/// A step's odometry: the motion it reports, in the agent's frame at the last
/// step, and for noisy odometry the direction of travel and its white noise.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Reading {
    motion: Pose,
    noise: Option<ReadingNoise>,
}

/// The white noise of a noisy reading, which the filter adds to its process noise.
#[derive(Debug, Clone, Copy, PartialEq)]
struct ReadingNoise {
    /// Unit direction of travel in the agent's frame at the last step.
    direction: Vector,
    /// Variance of the travelled distance, m².
    distance: f64,
    /// Variance of the heading change, rad².
    turn: f64,
}

/// Reads the true motion `u` over `dt` with `odometry`, drawing its noise
/// from `rng`.
fn read(odometry: &Odometry, u: Pose, dt: f64, rng: &mut ChaCha8Rng) -> Reading {
    let OdometryNoise {
        speed_sigma,
        speed_bias,
        yaw_rate_sigma,
        yaw_rate_bias,
    } = match odometry {
        Odometry::Exact => return Reading { motion: u, noise: None },
        Odometry::Noisy(noise) => *noise,
    };
    let distance = u.translation.length();
    // The chord of the step; at a standstill, the heading halfway through the turn.
    let direction = if distance > 0.0 {
        u.translation / distance
    } else {
        let (sin, cos) = (u.rotation.angle() / 2.0).sin_cos();
        Vector::new(cos, sin)
    };
    let (n1, n2): (f64, f64) = (StandardNormal.sample(&mut *rng), StandardNormal.sample(&mut *rng));
    let distance_error = speed_bias * distance + speed_sigma * n1 * dt;
    let turn_error = (yaw_rate_bias + yaw_rate_sigma * n2) * dt;
    Reading {
        motion: Pose::new(
            u.translation + direction * distance_error,
            u.rotation.angle() + turn_error,
        ),
        noise: Some(ReadingNoise {
            direction,
            distance: (speed_sigma * dt).powi(2),
            turn: (yaw_rate_sigma * dt).powi(2),
        }),
    }
}

fn pose_vector(pose: Pose) -> Vector3<f64> {
    Vector3::new(pose.translation.x, pose.translation.y, pose.rotation.angle())
}

fn vector_pose(v: Vector3<f64>) -> Pose {
    Pose::new(Vector::new(v.x, v.y), v.z)
}

/// x ← x ∘ u, P ← F P Fᵀ + Q dt + the odometry's white noise.
fn predict(
    x: Vector3<f64>,
    p: Matrix3<f64>,
    reading: Reading,
    dt: f64,
    s: &Localization,
) -> (Vector3<f64>, Matrix3<f64>) {
    let u = reading.motion;
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
    let mut p = f * p * f.transpose() + q;
    if let Some(noise) = reading.noise {
        // The distance's noise lies along the direction of travel, in the world frame.
        let d = noise.direction;
        let along = Vector2::new(cos * d.x - sin * d.y, sin * d.x + cos * d.y);
        let distance = along * along.transpose() * noise.distance;
        let mut position = p.fixed_view_mut::<2, 2>(0, 0);
        position += distance;
        p[(2, 2)] += noise.turn;
    }
    (predicted, p)
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
    use proptest::test_runner::{Config, RngAlgorithm, RngSeed, TestRunner};

    use super::*;
    use crate::rng::{Purpose, stream};

    fn settings(filter: PoseFilter, sigma: f64, odometry: Odometry) -> Localization {
        Localization {
            position_sigma: sigma,
            heading_sigma: 0.0,
            filter,
            process_position_sigma: 0.1,
            process_heading_sigma: 0.01,
            odometry,
        }
    }

    fn noisy(speed_sigma: f64, speed_bias: f64, yaw_rate_sigma: f64, yaw_rate_bias: f64) -> Odometry {
        Odometry::Noisy(OdometryNoise {
            speed_sigma,
            speed_bias,
            yaw_rate_sigma,
            yaw_rate_bias,
        })
    }

    /// RMS position error of the estimates of an agent driving 10 m/s along a
    /// circle of radius 50 m (0.2 rad/s) for 200 s at 10 Hz, first 10 s aside.
    fn rms_error(localization: Localization, seed: u64) -> f64 {
        let mut estimator = PoseEstimator::new(localization);
        let mut measurements = stream(seed, Purpose::Localization, 0);
        let mut odometry = stream(seed, Purpose::Odometry, 0);
        let n = 2000;
        let mut sum = 0.0;
        for k in 0..n {
            let angle = 0.02 * k as f64;
            let truth = Pose::new(Vector::new(angle.sin(), 1.0 - angle.cos()) * 50.0, angle);
            odometry.set_block_pos(k);
            let estimate = estimator.estimate(truth, 0.1, &mut measurements, &mut odometry);
            if k >= 100 {
                sum += (estimate.translation - truth.translation).length_squared();
            }
        }
        (sum / (n - 100) as f64).sqrt()
    }

    #[test]
    fn without_noise_the_estimate_is_exactly_the_truth() {
        for odometry in [Odometry::Exact, Odometry::Noisy(OdometryNoise::default())] {
            let mut estimator = PoseEstimator::new(settings(PoseFilter::Kalman, 0.0, odometry));
            let (mut measurements, mut readings) =
                (stream(1, Purpose::Localization, 0), stream(1, Purpose::Odometry, 0));
            for k in 0..20 {
                let truth = Pose::new(Vector::new(k as f64, 0.5 * k as f64), 0.1 * k as f64);
                assert_eq!(estimator.estimate(truth, 0.1, &mut measurements, &mut readings), truth);
            }
        }
    }

    /// The raw measurement has an RMS position error of σ√2 (two axes); the filter,
    /// which also knows the motion, does markedly better.
    #[test]
    fn the_filter_reduces_the_measurement_error() {
        let raw = rms_error(settings(PoseFilter::None, 0.5, Odometry::Exact), 9);
        assert_relative_eq!(raw, 0.5 * 2.0_f64.sqrt(), max_relative = 0.08);
        for odometry in [Odometry::Exact, Odometry::Noisy(OdometryNoise::default())] {
            let filtered = rms_error(settings(PoseFilter::Kalman, 0.5, odometry), 9);
            assert!(filtered < 0.5 * raw, "{odometry:?}: filtered {filtered} vs raw {raw}");
        }
    }

    /// Exact odometry is the true motion itself, and draws nothing: the filter
    /// predicts as it did before odometry had a model.
    #[test]
    fn exact_odometry_reads_the_true_motion_and_draws_nothing() {
        let u = Pose::new(Vector::new(0.8, 0.03), 0.02);
        let mut rng = stream(3, Purpose::Odometry, 0);
        assert_eq!(
            read(&Odometry::Exact, u, 0.1, &mut rng),
            Reading { motion: u, noise: None }
        );
        assert_eq!(rng.get_word_pos(), 0);
    }

    /// Biases alone, by hand: 1 m straight ahead in 0.1 s (10 m/s) read 5 % fast
    /// is 1.05 m; a yaw-rate offset of 0.2 rad/s turns it by 0.02 rad. Without
    /// white noise the filter adds nothing to its process noise along the way.
    #[test]
    fn noisy_odometry_scales_the_distance_and_offsets_the_turn() {
        let u = Pose::new(Vector::new(1.0, 0.0), 0.0);
        let reading = read(
            &noisy(0.0, 0.05, 0.0, 0.2),
            u,
            0.1,
            &mut stream(3, Purpose::Odometry, 0),
        );
        assert_relative_eq!(reading.motion.translation.x, 1.05, epsilon = 1e-12);
        assert_relative_eq!(reading.motion.translation.y, 0.0, epsilon = 1e-12);
        assert_relative_eq!(reading.motion.rotation.angle(), 0.02, epsilon = 1e-12);
        let noise = reading.noise.expect("noisy odometry states its noise");
        assert_eq!(
            (noise.direction, noise.distance, noise.turn),
            (Vector::new(1.0, 0.0), 0.0, 0.0)
        );
    }

    /// At a standstill the speed's noise moves the agent along its heading.
    #[test]
    fn noisy_odometry_at_a_standstill_moves_along_the_heading() {
        let reading = read(
            &noisy(1.0, 0.0, 0.0, 0.0),
            Pose::IDENTITY,
            0.1,
            &mut stream(4, Purpose::Odometry, 0),
        );
        assert_eq!(reading.motion.translation.y, 0.0);
        assert!(reading.motion.translation.x != 0.0);
        assert_relative_eq!(reading.noise.unwrap().distance, 0.01, epsilon = 1e-15);
    }

    /// Over seeds: the same draws scaled up, the estimate's error grows with the
    /// odometry's noise (exact, then σ 0.5 m/s and 2 °/s, then four times that).
    #[test]
    fn the_estimate_error_grows_with_the_odometry_noise() {
        let config = Config {
            cases: 16,
            failure_persistence: None,
            rng_algorithm: RngAlgorithm::ChaCha,
            rng_seed: RngSeed::Fixed(16),
            ..Config::default()
        };
        TestRunner::new(config)
            .run(&(0u64..10_000), |seed| {
                let errors: Vec<f64> = [0.0, 1.0, 4.0]
                    .iter()
                    .map(|&k| {
                        let odometry = noisy(0.5 * k, 0.0, 2.0_f64.to_radians() * k, 0.0);
                        rms_error(settings(PoseFilter::Kalman, 0.5, odometry), seed)
                    })
                    .collect();
                proptest::prop_assert!(errors.windows(2).all(|w| w[0] < w[1]), "{errors:?}");
                Ok(())
            })
            .unwrap();
    }
}
