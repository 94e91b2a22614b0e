//! Delivery of received packets: when a packet arrives, and the packets on their
//! way, in order of arrival.

use std::collections::VecDeque;

/// Speed of light, m/s, for propagation delay.
const LIGHT: f64 = 299_792_458.0;

/// When a packet sent at `sent` (seconds) over `distance_m` metres arrives: after
/// the link's `latency` (seconds) and propagation at the speed of light.
pub(crate) fn arrival(sent: f64, latency: f64, distance_m: f64) -> f64 {
    sent + latency + distance_m / LIGHT
}

/// Received packets on their way, in order of arrival (packets arriving at the
/// same time in order of sending).
#[derive(Debug, Clone)]
pub(crate) struct InFlight<T> {
    queue: VecDeque<(f64, T)>,
}

impl<T> Default for InFlight<T> {
    fn default() -> Self {
        Self { queue: VecDeque::new() }
    }
}

impl<T> InFlight<T> {
    /// Puts `payload` on its way, to arrive at `at` (seconds).
    pub(crate) fn send(&mut self, at: f64, payload: T) {
        let index = self.queue.partition_point(|&(t, _)| t <= at);
        self.queue.insert(index, (at, payload));
    }

    /// The packets that have arrived by `now` (to within a nanosecond), with
    /// their arrival times, in order of arrival; they leave the queue.
    pub(crate) fn arrived(&mut self, now: f64) -> Vec<(f64, T)> {
        let count = self.queue.partition_point(|&(at, _)| at <= now + 1e-9);
        self.queue.drain(..count).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Packets leave in order of arrival, ties in order of sending, and only once
    /// they have arrived.
    #[test]
    fn packets_arrive_in_order() {
        let mut in_flight = InFlight::default();
        in_flight.send(0.3, 'a');
        in_flight.send(0.1, 'b');
        in_flight.send(0.3, 'c');
        in_flight.send(0.2, 'd');
        assert_eq!(in_flight.arrived(0.05), []);
        assert_eq!(in_flight.arrived(0.2), [(0.1, 'b'), (0.2, 'd')]);
        assert_eq!(in_flight.arrived(1.0), [(0.3, 'a'), (0.3, 'c')]);
        assert_eq!(in_flight.arrived(2.0), []);
    }

    /// 300 m at the speed of light adds about a microsecond to the latency.
    #[test]
    fn arrival_adds_latency_and_propagation() {
        let at = arrival(1.0, 0.1, 299.792_458);
        assert!((at - (1.1 + 1e-6)).abs() < 1e-12);
    }
}
