//! The roadside unit's local dynamic map: a short history of noisy measurements
//! per object (seed 002, section III-A).

use std::collections::{BTreeMap, VecDeque};

use sightline_dsl::AgentKind;

use crate::idealisation::Idealisation;
use crate::math::Point;

/// Tracks are keyed by identity.
pub(crate) const ASSOCIATION: Idealisation = Idealisation {
    id: "ldm.association",
    text: "The local dynamic map associates every measurement with the right object: tracks are keyed by the \
           object's true identity.",
};

/// One noisy measurement of an object (seed 002, eq. 1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Measurement {
    /// When, seconds.
    pub time: f64,
    /// Centre, metres.
    pub position: Point,
    /// Speed, m/s.
    pub speed: f64,
    /// Heading, radians (not noisy: seed 002 names position, velocity and shape).
    pub heading: f64,
    /// Footprint length, metres.
    pub length: f64,
    /// Footprint width, metres.
    pub width: f64,
    /// The speed limit of its lane, m/s (the map's, not measured).
    pub limit: f64,
}

/// The measurements of one object, oldest first.
#[derive(Debug, Clone, PartialEq)]
pub struct Track {
    /// What the object is.
    pub kind: AgentKind,
    /// Measurements within the history, oldest first (never empty).
    pub history: VecDeque<Measurement>,
}

impl Track {
    /// The newest measurement.
    pub fn latest(&self) -> &Measurement {
        self.history.back().expect("a track holds at least one measurement")
    }

    /// The velocity from the displacement over the history's last `span` seconds
    /// (seed 002: a pedestrian's direction "estimated from recent position
    /// history"); `None` with a single measurement.
    pub fn displacement_velocity(&self, span: f64) -> Option<Point> {
        let latest = self.latest();
        let earliest = self
            .history
            .iter()
            .find(|m| latest.time - m.time <= span + 1e-9)
            .filter(|m| m.time < latest.time)?;
        Some((latest.position - earliest.position) / (latest.time - earliest.time))
    }

    /// Seed 002, eq. 2: the mean violation δ̄ = mean(v − v_max) over the
    /// measurements of the last `window` seconds that exceed the limit; `None`
    /// without a violation.
    pub fn mean_violation(&self, window: f64) -> Option<f64> {
        let now = self.latest().time;
        let (sum, count) = self
            .history
            .iter()
            .filter(|m| m.time >= now - window - 1e-9 && m.speed > m.limit)
            .fold((0.0, 0u32), |(sum, count), m| (sum + (m.speed - m.limit), count + 1));
        (count > 0).then(|| sum / f64::from(count))
    }
}

/// Tracks by agent index.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Ldm {
    tracks: BTreeMap<usize, Track>,
}

impl Ldm {
    /// Adds a measurement of agent `agent`.
    pub fn record(&mut self, agent: usize, kind: AgentKind, measurement: Measurement) {
        self.tracks
            .entry(agent)
            .or_insert_with(|| Track {
                kind,
                history: VecDeque::new(),
            })
            .history
            .push_back(measurement);
    }

    /// Drops measurements older than `history` seconds before `now`, and objects
    /// left without any.
    pub fn forget(&mut self, now: f64, history: f64) {
        self.tracks.retain(|_, track| {
            while track.history.front().is_some_and(|m| m.time < now - history - 1e-9) {
                track.history.pop_front();
            }
            !track.history.is_empty()
        });
    }

    /// Objects measured at `now`, by agent index.
    pub fn current(&self, now: f64) -> impl Iterator<Item = (usize, &Track)> {
        self.tracks
            .iter()
            .filter(move |(_, t)| (t.latest().time - now).abs() < 1e-9)
            .map(|(&agent, track)| (agent, track))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Vector;

    fn at(time: f64, x: f64, speed: f64) -> Measurement {
        Measurement {
            time,
            position: Vector::new(x, 0.0),
            speed,
            heading: 0.0,
            length: 4.5,
            width: 1.8,
            limit: 10.0,
        }
    }

    /// Violations 3 and 1 m/s inside a 5 s window (the 6 m/s excess at t = 0 is
    /// outside it, the compliant 9 m/s does not count): δ̄ = (3 + 1) / 2 = 2.
    #[test]
    fn mean_violation_counts_only_violations_in_the_window() {
        let mut ldm = Ldm::default();
        for (t, v) in [(0.0, 16.0), (2.0, 13.0), (4.0, 9.0), (6.0, 11.0)] {
            ldm.record(3, AgentKind::Car, at(t, 0.0, v));
        }
        let track = ldm.current(6.0).next().unwrap().1;
        assert_eq!(track.mean_violation(5.0), Some(2.0));
        assert_eq!(track.mean_violation(1.0), Some(1.0));
    }

    #[test]
    fn forgetting_keeps_the_window_and_drops_empty_tracks() {
        let mut ldm = Ldm::default();
        ldm.record(1, AgentKind::Car, at(0.0, 0.0, 5.0));
        ldm.record(2, AgentKind::Car, at(0.0, 0.0, 5.0));
        ldm.record(2, AgentKind::Car, at(5.0, 10.0, 5.0));
        ldm.forget(5.0, 2.0);
        assert_eq!(ldm.current(5.0).map(|(a, _)| a).collect::<Vec<_>>(), vec![2]);
        assert_eq!(ldm.current(5.0).next().unwrap().1.history.len(), 1);
    }

    #[test]
    fn displacement_velocity_spans_the_recent_history() {
        let mut ldm = Ldm::default();
        for (t, x) in [(0.0, 0.0), (0.5, 0.7), (1.0, 1.2)] {
            ldm.record(1, AgentKind::Pedestrian, at(t, x, 1.2));
        }
        let track = ldm.current(1.0).next().unwrap().1;
        let over = |span| track.displacement_velocity(span).unwrap();
        assert!((over(1.0) - Vector::new(1.2, 0.0)).length() < 1e-12);
        assert!((over(0.5) - Vector::new(1.0, 0.0)).length() < 1e-12);
    }
}
