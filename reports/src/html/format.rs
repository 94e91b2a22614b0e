//! How the page writes numbers and tables: one number format (four
//! significant digits, thousands separated), units beside values and in
//! column heads, a dash where a value is undefined, and the table shape every
//! section hands the template.

use serde::Serialize;

pub(crate) use crate::results::metric_unit;

#[derive(Serialize)]
pub(super) struct TableView {
    /// What the table shows; empty for none.
    pub(super) caption: String,
    pub(super) head: Vec<String>,
    pub(super) rows: Vec<Vec<String>>,
    /// Leading columns that hold text (labels), not numbers.
    pub(super) text_columns: usize,
}

/// A measured value, or a dash where it is undefined.
pub(crate) fn or_dash(value: Option<f64>) -> String {
    value.map_or_else(|| "—".into(), number)
}

/// A number for people, in the one format of the page: four significant
/// digits with trailing zeros dropped, whole numbers exact, thousands
/// separated by commas, and values below 10⁻³ in scientific notation
/// (`1.25 × 10⁻⁹`).
pub(crate) fn number(value: f64) -> String {
    if !value.is_finite() {
        return value.to_string();
    }
    if value == 0.0 {
        return "0".into();
    }
    let magnitude = value.abs().log10().floor() as i32;
    if magnitude < -3 {
        let mantissa = trimmed(&format!("{:.3}", value / 10f64.powi(magnitude)));
        // Rounding the mantissa may carry into the next power (9.9996 → 10).
        let (mantissa, magnitude) = match mantissa.trim_start_matches('-') {
            "10" => (mantissa.replace("10", "1"), magnitude + 1),
            _ => (mantissa, magnitude),
        };
        return format!("{mantissa} × 10{}", superscript(magnitude));
    }
    let decimals = usize::try_from(3 - magnitude).unwrap_or(0);
    grouped(&trimmed(&format!("{value:.decimals$}")))
}

/// A value with its unit (`1.32 s`; a dimensionless value stands alone), or
/// a dash where it is undefined.
pub(crate) fn with_unit(value: Option<f64>, unit: &str) -> String {
    match value {
        Some(v) if unit != "1" => format!("{} {unit}", number(v)),
        _ => or_dash(value),
    }
}

/// A column head for a quantity in `unit`: `name (unit)`.
pub(crate) fn head(name: &str, unit: &str) -> String {
    format!("{name} ({unit})")
}

/// `text` without the trailing zeros of its fraction (and without a bare point).
fn trimmed(text: &str) -> String {
    if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        text.to_string()
    }
}

/// `text` (a plain decimal) with its whole part's thousands separated by commas.
fn grouped(text: &str) -> String {
    let (sign, digits) = text.strip_prefix('-').map_or(("", text), |rest| ("-", rest));
    let (whole, fraction) = digits.split_once('.').map_or((digits, None), |(w, f)| (w, Some(f)));
    let mut out = String::from(sign);
    for (i, c) in whole.chars().enumerate() {
        if i > 0 && (whole.len() - i) % 3 == 0 {
            out.push(',');
        }
        out.push(c);
    }
    if let Some(fraction) = fraction {
        out.push('.');
        out.push_str(fraction);
    }
    out
}

/// An exponent in superscript digits.
fn superscript(exponent: i32) -> String {
    exponent
        .to_string()
        .chars()
        .map(|c| match c {
            '-' => '⁻',
            d => ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'][d.to_digit(10).expect("a digit") as usize],
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_read_like_the_paper() {
        assert_eq!(number(59862.0), "59,862");
        assert_eq!(number(-1425.0), "-1,425");
        assert_eq!(number(0.97871), "0.9787");
        assert_eq!(number(0.9), "0.9");
        assert_eq!(number(-0.00102), "-0.00102");
        assert_eq!(number(1e-9), "1 × 10⁻⁹");
        assert_eq!(number(-1.2346e-5), "-1.235 × 10⁻⁵");
        assert_eq!(number(9.99996e-5), "1 × 10⁻⁴");
        assert_eq!(number(123.456), "123.5");
        assert_eq!(number(1234.5678), "1,235");
        assert_eq!(number(9.99996), "10");
        assert_eq!(number(0.0), "0");
        assert_eq!(with_unit(Some(1.3249), "s"), "1.325 s");
        assert_eq!(with_unit(Some(0.5), "1"), "0.5");
        assert_eq!(with_unit(None, "s"), "—");
        assert_eq!(metric_unit("channel_load"), "B/s");
    }
}
