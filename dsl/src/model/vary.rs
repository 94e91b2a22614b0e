//! The space `sightline falsify` searches: the `vary` section, compiled.

use serde::Serialize;

/// How many values a `vary` range of a real-valued setting takes: the range is
/// cut into this many equal steps, so that a search draws and shrinks on an
/// integer grid (index 0 is the range's low end).
pub const RANGE_STEPS: u64 = 1000;

/// The largest magnitude of an end of a whole-number `vary` range, 2^53: a
/// range holds its ends as 64-bit floats, which hold every whole number up to
/// there and not all beyond, so `check` refuses an end beyond it.
pub const MAX_WHOLE_END: f64 = 9_007_199_254_740_992.0;

/// One varied setting and the values it may take.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Vary {
    /// Dotted path of the setting (`v2x.channel.sensitivity_dbm`).
    pub path: String,
    /// The values it may take.
    pub domain: Domain,
}

/// The values of one varied setting.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Domain {
    /// Every number from `lo` to `hi` (inclusive) on a grid: whole numbers when
    /// the setting is an integer (both ends then within ±[`MAX_WHOLE_END`]),
    /// else [`RANGE_STEPS`] equal steps.
    Range {
        /// The low end.
        lo: f64,
        /// The high end (at least `lo`).
        hi: f64,
        /// Whether the setting takes whole numbers only.
        integer: bool,
    },
    /// One of the listed values, as written (`one_of`).
    Choices(Vec<serde_json::Value>),
}

impl Vary {
    /// How many values the setting takes (at least 1): grid indices run from 0
    /// (the low end, or the first choice) to `count() − 1`.
    pub fn count(&self) -> u64 {
        match &self.domain {
            Domain::Range { lo, hi, integer: true } => ((hi - lo) as u64).saturating_add(1),
            Domain::Range { lo, hi, .. } if lo == hi => 1,
            Domain::Range { .. } => RANGE_STEPS + 1,
            Domain::Choices(values) => values.len() as u64,
        }
    }

    /// Each setting of `vary` with its value at its grid index in `indices`: one
    /// case, as [`instantiate`](crate::instantiate) takes it.
    pub fn settings(vary: &[Vary], indices: &[u64]) -> Vec<(String, serde_json::Value)> {
        vary.iter()
            .zip(indices)
            .map(|(v, &i)| (v.path.clone(), v.value(i)))
            .collect()
    }

    /// The value at grid index `index` (clamped to the last one).
    pub fn value(&self, index: u64) -> serde_json::Value {
        let index = index.min(self.count() - 1);
        match &self.domain {
            // Within ±2^53 every whole number is exact, and `lo + index` ≤ `hi`.
            Domain::Range { lo, integer: true, .. } => serde_json::Value::from(*lo as i64 + index as i64),
            Domain::Range { lo, hi, .. } => {
                let steps = (self.count() - 1).max(1) as f64;
                // Round to 13 significant digits so that grid values print as
                // written (−72.5, not −72.49999999999999), and keep the
                // rounded value within the ends however many digits they have.
                let value = lo + (hi - lo) * index as f64 / steps;
                let value = format!("{value:.12e}").parse::<f64>().unwrap_or(value).clamp(*lo, *hi);
                serde_json::Number::from_f64(value).map_or(serde_json::Value::Null, serde_json::Value::Number)
            }
            Domain::Choices(values) => values[index as usize].clone(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integer_ranges_take_every_whole_number() {
        let vary = Vary {
            path: "perception.cooperating".into(),
            domain: Domain::Range {
                lo: 1.0,
                hi: 6.0,
                integer: true,
            },
        };
        assert_eq!(vary.count(), 6);
        assert_eq!(vary.value(0), serde_json::json!(1));
        assert_eq!(vary.value(5), serde_json::json!(6));
        assert_eq!(vary.value(99), serde_json::json!(6));
    }

    #[test]
    fn the_widest_integer_range_takes_every_whole_number_exactly() {
        let vary = Vary {
            path: "seed".into(),
            domain: Domain::Range {
                lo: -MAX_WHOLE_END,
                hi: MAX_WHOLE_END,
                integer: true,
            },
        };
        assert_eq!(vary.count(), (1 << 54) + 1);
        assert_eq!(vary.value(0), serde_json::json!(-(1_i64 << 53)));
        assert_eq!(vary.value((1 << 53) + 1), serde_json::json!(1));
        assert_eq!(vary.value(1 << 54), serde_json::json!(1_i64 << 53));
        assert_eq!(vary.value(u64::MAX), serde_json::json!(1_i64 << 53));
    }

    #[test]
    fn a_real_range_rounded_for_print_stays_within_its_ends() {
        let vary = Vary {
            path: "decision.threshold".into(),
            domain: Domain::Range {
                lo: 0.0,
                hi: 0.123_456_789_012_36,
                integer: false,
            },
        };
        // Thirteen significant digits would print the high end as 0.1234567890124.
        assert_eq!(vary.value(RANGE_STEPS), serde_json::json!(0.123_456_789_012_36));
    }

    #[test]
    fn real_ranges_take_a_grid_from_low_to_high() {
        let vary = Vary {
            path: "v2x.channel.sensitivity_dbm".into(),
            domain: Domain::Range {
                lo: -95.0,
                hi: -60.0,
                integer: false,
            },
        };
        assert_eq!(vary.count(), RANGE_STEPS + 1);
        assert_eq!(vary.value(0), serde_json::json!(-95.0));
        assert_eq!(vary.value(500), serde_json::json!(-77.5));
        assert_eq!(vary.value(RANGE_STEPS), serde_json::json!(-60.0));
        assert_eq!(vary.value(1), serde_json::json!(-94.965));
    }
}
