//! How the page writes numbers and tables: counts with thousands separators,
//! fractions to four decimals, a dash where a value is undefined, and the table
//! shape every section hands the template.

use serde::Serialize;

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

/// A number for people: counts with thousands separators, fractions to four
/// decimals, tiny values in scientific notation.
pub(crate) fn number(value: f64) -> String {
    if !value.is_finite() {
        return value.to_string();
    }
    if value == value.trunc() && value.abs() < 1e15 {
        let digits = format!("{}", value.abs() as u64);
        let mut grouped = String::new();
        for (i, c) in digits.chars().enumerate() {
            if i > 0 && (digits.len() - i) % 3 == 0 {
                grouped.push(',');
            }
            grouped.push(c);
        }
        return if value < 0.0 { format!("-{grouped}") } else { grouped };
    }
    if value.abs() < 1e-3 {
        format!("{value:.2e}")
    } else if value.abs() < 10.0 {
        format!("{value:.4}")
    } else {
        format!("{value:.2}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_read_like_the_paper() {
        assert_eq!(number(59862.0), "59,862");
        assert_eq!(number(-1425.0), "-1,425");
        assert_eq!(number(0.97871), "0.9787");
        assert_eq!(number(1e-9), "1.00e-9");
        assert_eq!(number(123.456), "123.46");
        assert_eq!(number(0.0), "0");
    }
}
