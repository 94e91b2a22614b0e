//! Mass functions on the frame {Empty, Occupy}.

use std::ops::Index;

/// A basic probability assignment over the frame Θ = {Empty, Occupy}: mass on
/// {Empty}, on {Occupy}, and on Θ itself ("Unknown"). A mass function has every
/// mass in [0, 1] and the three summing to 1.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mass {
    /// m({Empty}).
    pub empty: f64,
    /// m({Occupy}).
    pub occupied: f64,
    /// m(Θ): belief committed to neither state.
    pub unknown: f64,
}

/// The three focal elements, in the order masses are listed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
pub enum State {
    /// {Empty}.
    Empty,
    /// {Occupy}.
    Occupied,
    /// Θ.
    Unknown,
}

impl State {
    /// All states in order.
    pub const ALL: [State; 3] = [State::Empty, State::Occupied, State::Unknown];
}

impl Mass {
    /// Complete ignorance: all mass on Θ. The identity of Dempster's rule.
    pub const VACUOUS: Mass = Mass::new(0.0, 0.0, 1.0);

    /// A mass from its three components (not checked).
    pub const fn new(empty: f64, occupied: f64, unknown: f64) -> Self {
        Self {
            empty,
            occupied,
            unknown,
        }
    }

    /// All mass on one state (tests build certain sources with it).
    #[cfg(test)]
    pub const fn certain(state: State) -> Self {
        match state {
            State::Empty => Self::new(1.0, 0.0, 0.0),
            State::Occupied => Self::new(0.0, 1.0, 0.0),
            State::Unknown => Self::VACUOUS,
        }
    }

    /// Shafer's discounting by a source's `reliability` α in [0, 1]: α of every
    /// mass is kept, the rest moves to Θ (m'(A) = α m(A) for A ≠ Θ,
    /// m'(Θ) = 1 − α + α m(Θ)). Its pignistic probability moves toward 1/2 in
    /// proportion: BetP' = 1/2 + α (BetP − 1/2).
    pub fn discounted(self, reliability: f64) -> Self {
        Self::new(
            reliability * self.empty,
            reliability * self.occupied,
            1.0 - reliability * (self.empty + self.occupied),
        )
    }

    /// The sum of the three masses.
    pub fn total(&self) -> f64 {
        self.empty + self.occupied + self.unknown
    }

    /// Components as an array in [`State::ALL`] order.
    pub fn to_array(self) -> [f64; 3] {
        [self.empty, self.occupied, self.unknown]
    }

    /// Whether every mass is finite and in [0, 1] and they sum to 1, within
    /// `tolerance` (the invariant the tests check fusion against).
    #[cfg(test)]
    pub fn is_mass_function(&self, tolerance: f64) -> bool {
        self.to_array()
            .iter()
            .all(|m| m.is_finite() && (-tolerance..=1.0 + tolerance).contains(m))
            && (self.total() - 1.0).abs() <= tolerance
    }
}

impl Index<State> for Mass {
    type Output = f64;

    fn index(&self, state: State) -> &f64 {
        match state {
            State::Empty => &self.empty,
            State::Occupied => &self.occupied,
            State::Unknown => &self.unknown,
        }
    }
}
