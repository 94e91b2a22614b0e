//! One module per family of checks. Each returns (status, value, margin, message).

pub(crate) mod invariant;
pub(crate) mod metric;
pub(crate) mod object;
pub(crate) mod seeds;
pub(crate) mod temporal;

/// What a failure (a violation seen) among fewer samples than a check needs
/// adds to its message; nothing when it has enough.
pub(crate) fn seen_among_too_few(n: u64, min_samples: u64) -> String {
    if n >= min_samples {
        return String::new();
    }
    format!("; a violation seen, judged though n = {n} is fewer than the {min_samples} the check needs")
}

/// A number for messages: six significant digits, no trailing zeros, so that
/// rounding noise (0.00682499999999997) does not reach a log. Full precision stays
/// in the evaluation's fields.
pub(crate) fn short(value: f64) -> String {
    if value == 0.0 || !value.is_finite() {
        return value.to_string();
    }
    let magnitude = value.abs().log10().floor() as i32;
    if (-4..15).contains(&magnitude) {
        let decimals = (5 - magnitude).max(0) as usize;
        let text = format!("{value:.decimals$}");
        if text.contains('.') {
            text.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            text
        }
    } else {
        let text = format!("{value:.5e}");
        let (mantissa, exponent) = text.split_once('e').expect("scientific notation has an exponent");
        let mantissa = mantissa.trim_end_matches('0').trim_end_matches('.');
        format!("{mantissa}e{exponent}")
    }
}

#[cfg(test)]
mod tests {
    use super::short;

    #[test]
    fn six_significant_digits_without_noise() {
        assert_eq!(short(-0.00682499999999997), "-0.006825");
        assert_eq!(short(0.943175), "0.943175");
        assert_eq!(short(1174.0), "1174");
        assert_eq!(short(4.440892098500626e-16), "4.44089e-16");
        assert_eq!(short(1e-9), "1e-9");
        assert_eq!(short(0.0), "0");
        assert_eq!(short(2.5e20), "2.5e20");
    }
}
