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
    significant(value, 4)
}

/// A value as the scenario gave it (a threshold), in the page's format with
/// as many significant digits as it takes to read back as the same number,
/// four at least: `0.81478`, where [`number`] writes `0.8148`.
pub(crate) fn exact(value: f64) -> String {
    let digits = (4..=17)
        .find(|&digits| format!("{value:.*e}", digits - 1).parse::<f64>() == Ok(value))
        .unwrap_or(17);
    significant(value, digits)
}

/// `value` to `digits` significant digits, in the page's format.
fn significant(value: f64, digits: usize) -> String {
    if !value.is_finite() {
        return value.to_string();
    }
    if value == 0.0 {
        return "0".into();
    }
    let magnitude = value.abs().log10().floor() as i32;
    if magnitude < -3 {
        // Rust's exponent format rounds the decimal digits exactly and
        // carries into the next power (9.99996 × 10⁻⁵ → 1.000e-4).
        let text = format!("{value:.*e}", digits - 1);
        let (mantissa, exponent) = text.split_once('e').expect("an exponent format");
        let exponent: i32 = exponent.parse().expect("an exponent");
        return format!("{} × 10{}", trimmed(mantissa), superscript(exponent));
    }
    let decimals = usize::try_from(digits as i32 - 1 - magnitude).unwrap_or(0);
    grouped(&trimmed(&format!("{value:.decimals$}")))
}

/// A value with its unit (`1.32 s`; a dimensionless value stands alone), or
/// a dash where it is undefined.
pub(crate) fn with_unit(value: Option<f64>, unit: &str) -> String {
    in_unit(value.map(number), unit)
}

/// A threshold with its unit, as the scenario gave it ([`exact`]).
pub(crate) fn exact_with_unit(value: f64, unit: &str) -> String {
    in_unit(Some(exact(value)), unit)
}

/// `text` followed by `unit` (alone when dimensionless), or a dash.
fn in_unit(text: Option<String>, unit: &str) -> String {
    match text {
        Some(text) if unit != "1" => format!("{text} {unit}"),
        Some(text) => text,
        None => "—".into(),
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
        assert_eq!(exact(0.81478), "0.81478");
        assert_eq!(exact(0.8147743055555556), "0.8147743055555556");
        assert_eq!(exact(0.9), "0.9");
        assert_eq!(exact(1234.5678), "1,234.5678");
        assert_eq!(exact(-1.23456e-7), "-1.23456 × 10⁻⁷");
        assert_eq!(exact_with_unit(2.0, "s"), "2 s");
        assert_eq!(with_unit(Some(1.3249), "s"), "1.325 s");
        assert_eq!(with_unit(Some(0.5), "1"), "0.5");
        assert_eq!(with_unit(None, "s"), "—");
        assert_eq!(metric_unit("channel_load"), "B/s");
    }
}
