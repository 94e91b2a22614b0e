//! What the ego holds of one cooperating agent's grid over the radio: per
//! cell, the newest state a received message gave it, and how old that is.
//!
//! A message's cells overwrite what older messages of the same sender said of
//! them; cells no newer message covers keep their older state until it is
//! `max_age` old (since it was sensed), then they are dropped. With a `decay`
//! time constant τ, evidence of age a weighs exp(−a / τ): fusion discounts its
//! mass toward unknown by that weight.
//!
//! The sender's own footprint ([`Observed::Own`]) is the exception: it says
//! where the sender is, so a newer footprint replaces the older one whole, and
//! an older one arriving late is ignored. Kept until `max_age`, the footprints
//! of a moving sender left a trail behind it, which fusion read as occupied
//! and credited to whoever followed in it (session 21's outside check). Even
//! the newest is where the sender was up to a message period and the latency
//! ago: the measures of the fused grid credit a footprint to its sender only,
//! never as a detection of another road user (`super::fuse`).

use sightline_dsl::Messages;

use super::evidence::Evidence;
use super::message::Run;
use super::observe::Observed;
use crate::math::Point;

/// One generation of a sender's messages (the messages of one step), as the
/// ego holds it.
#[derive(Debug, Clone, Default)]
struct Generation {
    /// Its serial number among the sender's generations.
    serial: u32,
    /// When it was sensed, seconds.
    sensed: f64,
    /// The sender's estimated sensor positions then.
    sensors: Vec<Point>,
    /// Its evidence's weight at the current step.
    weight: f64,
}

/// The ego's copy of one sender's grid.
#[derive(Debug)]
pub(super) struct Held {
    cells: Vec<Observed>,
    /// Per cell: the serial of the generation its state came in.
    from: Vec<u32>,
    touched: Vec<usize>,
    /// The cells of the sender's footprint as held, and the generation it
    /// came in: only the newest footprint received is held.
    own: (Vec<usize>, Option<u32>),
    /// The generations that may still be live, in slot [`slot`]`(serial)`:
    /// more slots than generations fit in `max_age`, so that live ones never
    /// share a slot, and a power of two of them, so that finding a cell's
    /// slot takes a mask, not a division.
    slots: Vec<Option<Generation>>,
    /// Whether a generation left its slot since the held cells were last
    /// checked: some may still name it.
    stale: bool,
    /// Whether evidence keeps its weight as it ages (no `decay`).
    fresh: bool,
}

impl Held {
    /// Nothing held, on a grid of `cells` cells, for messages generated at
    /// `messages.rate_hz` (at most one per step) and dropped at `max_age`.
    pub(super) fn new(cells: usize, messages: &Messages) -> Self {
        let live = ((messages.max_age * messages.rate_hz).floor() as usize + 2).next_power_of_two();
        Self {
            cells: vec![Observed::Unknown; cells],
            from: vec![0; cells],
            touched: Vec::new(),
            own: (Vec::new(), None),
            slots: vec![None; live],
            stale: false,
            fresh: messages.decay.is_none(),
        }
    }

    /// Takes in a received message of generation `serial`, sensed at `sensed`
    /// with sensors at `sensors`: its runs overwrite what the ego held of
    /// their cells.
    pub(super) fn receive(&mut self, serial: u32, sensed: f64, sensors: &[Point], runs: &[Run]) {
        let slot = slot(&self.slots, serial);
        if self.slots[slot].as_ref().is_none_or(|g| g.serial != serial) {
            self.stale |= self.slots[slot].is_some();
            self.slots[slot] = Some(Generation {
                serial,
                sensed,
                sensors: sensors.to_vec(),
                weight: 1.0,
            });
        }
        for run in runs {
            if run.state == Observed::Own && !self.newest_footprint(serial) {
                continue;
            }
            for cell in run.cells() {
                if self.cells[cell] == Observed::Unknown {
                    self.touched.push(cell);
                }
                self.cells[cell] = run.state;
                self.from[cell] = serial;
            }
            if run.state == Observed::Own {
                self.own.0.extend(run.cells());
            }
        }
    }

    /// Whether a footprint of generation `serial` is the newest received; the
    /// held one, when older, is dropped first.
    fn newest_footprint(&mut self, serial: u32) -> bool {
        match self.own.1 {
            Some(held) if serial < held => return false,
            Some(held) if serial == held => return true,
            _ => {}
        }
        let (cells, from) = (&mut self.cells, &self.from);
        let mut dropped = false;
        for &cell in &self.own.0 {
            if cells[cell] == Observed::Own && Some(from[cell]) == self.own.1 {
                cells[cell] = Observed::Unknown;
                dropped = true;
            }
        }
        if dropped {
            self.touched.retain(|&cell| cells[cell] != Observed::Unknown);
        }
        self.own.0.clear();
        self.own.1 = Some(serial);
        true
    }

    /// Ages what is held to `now`: drops the cells whose evidence is older than
    /// `messages.max_age` and weighs the rest by the decay.
    pub(super) fn age(&mut self, now: f64, messages: &Messages) {
        let mut dropped = std::mem::take(&mut self.stale);
        for slot in &mut self.slots {
            let Some(generation) = slot else { continue };
            let age = now - generation.sensed;
            if outlived(age, messages) {
                *slot = None;
                dropped = true;
            } else {
                generation.weight = messages.decay.map_or(1.0, |tau| (-age / tau).exp());
            }
        }
        if !dropped {
            return;
        }
        let (cells, from, slots) = (&mut self.cells, &self.from, &self.slots);
        self.touched.retain(|&cell| {
            let live = slots[slot(slots, from[cell])]
                .as_ref()
                .is_some_and(|g| g.serial == from[cell]);
            if !live {
                cells[cell] = Observed::Unknown;
            }
            live
        });
    }

    /// Whether any evidence of the sender is held: the ego knows of it, its own
    /// footprint included.
    pub(super) fn is_live(&self) -> bool {
        self.slots.iter().any(Option::is_some)
    }

    fn generation(&self, cell: usize) -> &Generation {
        self.slots[slot(&self.slots, self.from[cell])]
            .as_ref()
            .expect("a held cell's generation is live")
    }
}

/// Whether evidence `age` seconds old (since it was sensed) is past
/// `messages.max_age`: dropped, never fused.
pub(super) fn outlived(age: f64, messages: &Messages) -> bool {
    age > messages.max_age + 1e-9
}

/// The slot of generation `serial` among `slots` (a power of two of them).
fn slot(slots: &[Option<Generation>], serial: u32) -> usize {
    serial as usize & (slots.len() - 1)
}

impl Evidence for Held {
    fn get(&self, cell: usize) -> Observed {
        self.cells[cell]
    }

    fn touched(&self) -> &[usize] {
        &self.touched
    }

    fn weight(&self, cell: usize) -> f64 {
        self.generation(cell).weight
    }

    fn sensors(&self, cell: usize) -> &[Point] {
        &self.generation(cell).sensors
    }

    fn fresh(&self) -> bool {
        self.fresh
    }
}

#[cfg(test)]
mod tests {
    use sightline_dsl::Oversize;

    use super::*;

    fn messages(decay: Option<f64>) -> Messages {
        Messages {
            rate_hz: 10.0,
            max_bytes: 1100,
            oversize: Oversize::Split,
            max_age: 0.25,
            decay,
        }
    }

    fn run(start: usize, len: u32, state: Observed) -> Run {
        Run { start, len, state }
    }

    /// The sender's footprint is where its newest message puts it: a newer
    /// footprint drops the older one at once (no trail behind a moving
    /// sender), and an older one arriving late is ignored, while the other
    /// cells of either message are held as any others.
    #[test]
    fn only_the_newest_footprint_is_held() {
        use Observed::{Free, Own, Unknown};
        let messages = messages(None);
        let mut held = Held::new(8, &messages);
        let sensors = [Point::new(0.0, 0.0)];
        held.receive(0, 0.0, &sensors, &[run(0, 2, Own), run(2, 2, Free)]);
        held.receive(1, 0.1, &sensors, &[run(1, 2, Own), run(4, 1, Free)]);
        let states: Vec<Observed> = (0..6).map(|c| held.get(c)).collect();
        assert_eq!(states, [Unknown, Own, Own, Free, Free, Unknown]);
        let mut touched = held.touched().to_vec();
        touched.sort_unstable();
        assert_eq!(touched, [1, 2, 3, 4]);
        // Generation 0 again, late: its free cell is taken, its footprint not.
        held.receive(0, 0.0, &sensors, &[run(5, 1, Free), run(6, 1, Own)]);
        let states: Vec<Observed> = (0..8).map(|c| held.get(c)).collect();
        assert_eq!(states, [Unknown, Own, Own, Free, Free, Free, Unknown, Unknown]);
        assert_eq!(held.touched().len(), 5);
    }

    /// Newer messages overwrite the cells they cover; cells no newer message
    /// covers are dropped once their evidence is older than `max_age`.
    #[test]
    fn newer_overwrites_and_old_expires() {
        let messages = messages(None);
        let mut held = Held::new(10, &messages);
        assert!(!held.is_live());
        held.receive(0, 0.0, &[Point::new(1.0, 0.0)], &[run(0, 4, Observed::Free)]);
        held.receive(1, 0.1, &[Point::new(2.0, 0.0)], &[run(2, 2, Observed::Occupied)]);
        held.age(0.2, &messages);
        assert!(held.is_live());
        let states: Vec<Observed> = (0..5).map(|c| held.get(c)).collect();
        use Observed::{Free, Occupied, Unknown};
        assert_eq!(states, [Free, Free, Occupied, Occupied, Unknown]);
        assert_eq!(held.sensors(0), [Point::new(1.0, 0.0)]);
        assert_eq!(held.sensors(2), [Point::new(2.0, 0.0)]);
        // At 0.3 s the first generation is 0.3 s old: dropped.
        held.age(0.3, &messages);
        assert_eq!(held.touched(), [2, 3]);
        assert_eq!((held.get(0), held.get(2)), (Unknown, Occupied));
        held.age(0.4, &messages);
        assert!(held.touched().is_empty() && !held.is_live());
    }

    /// With a time constant τ, evidence of age a weighs exp(−a/τ).
    #[test]
    fn decay_weighs_by_age() {
        let messages = messages(Some(0.5));
        let mut held = Held::new(4, &messages);
        held.receive(7, 1.0, &[], &[run(0, 1, Observed::Occupied)]);
        held.age(1.2, &messages);
        assert!((held.weight(0) - (-0.4_f64).exp()).abs() < 1e-12);
    }
}
