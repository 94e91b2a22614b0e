//! The units of measured quantities and the values they can take, shared by
//! metrics, signals and per-object properties.

/// The unit of a measured quantity, one source of truth for the evidence
/// (results.json's `check.unit`, the report's columns and values, JUnit).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Unit {
    /// Dimensionless: a share, a rate, a probability, a ratio or a gain (ISO
    /// 80000-1 writes its unit as 1).
    One,
    /// Grid cells.
    Cells,
    /// Seconds.
    Seconds,
    /// Metres.
    Metres,
    /// Metres per second squared (a deceleration).
    MetresPerSecondSquared,
    /// Bytes per second.
    BytesPerSecond,
    /// Road users (a mean over steps is not a whole number).
    Objects,
    /// Road users per run (the mean over a point's pooled runs).
    ObjectsPerRun,
}

impl Unit {
    /// The symbol written after a value: `1` for a dimensionless quantity,
    /// which the report leaves off values and writes in column heads.
    pub fn symbol(self) -> &'static str {
        match self {
            Self::One => "1",
            Self::Cells => "cells",
            Self::Seconds => "s",
            Self::Metres => "m",
            Self::MetresPerSecondSquared => "m/s²",
            Self::BytesPerSecond => "B/s",
            Self::Objects => "objects",
            Self::ObjectsPerRun => "objects/run",
        }
    }

    /// `value` followed by the symbol (none for a dimensionless value).
    pub fn with(self, value: &str) -> String {
        match self {
            Self::One => value.to_string(),
            other => format!("{value} {}", other.symbol()),
        }
    }
}

/// The values a measured quantity can take; every one of them is finite. (A
/// quantity that is not defined for a run is absent, not a value.)
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ValueDomain {
    /// A share, a rate or a probability: [0, 1].
    Fraction,
    /// A number of things: a whole number ≥ 0.
    Count,
    /// Seconds, bytes per second, a mean count or a gain: ≥ 0.
    NonNegative,
    /// A signed quantity (a lead time that may be late): any finite value.
    Real,
}

impl ValueDomain {
    /// Whether `value` lies in the domain (a NaN or an infinity never does).
    pub fn contains(self, value: f64) -> bool {
        value.is_finite()
            && match self {
                Self::Fraction => (0.0..=1.0).contains(&value),
                Self::Count => value >= 0.0 && value.fract() == 0.0,
                Self::NonNegative => value >= 0.0,
                Self::Real => true,
            }
    }
}

impl std::fmt::Display for ValueDomain {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Self::Fraction => "[0, 1]",
            Self::Count => "whole numbers ≥ 0",
            Self::NonNegative => "finite numbers ≥ 0",
            Self::Real => "finite numbers",
        })
    }
}
