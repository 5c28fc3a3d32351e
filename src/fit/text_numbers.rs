//! Fitted numbers as a scene file shows them: six significant digits (the
//! fits' relative errors are 10⁻³ and more, so the seventh digit carries
//! nothing), and a colour channel below 10⁻⁶ written as 0 (a weight that
//! small changes no 8-bit pixel: 1/255 ≈ 4·10⁻³). A fit once wrote
//! `k_d = [0.00000000022859258930196802, …]`.

/// Significant digits kept.
const DIGITS: usize = 6;

/// A colour channel below this is written as 0.
const NEGLIGIBLE_CHANNEL: f64 = 1e-6;

/// `table` with every float rounded for reading (module doc), nested
/// tables and arrays included.
pub fn tidy(table: &mut toml::Table) {
    for (_, value) in table.iter_mut() {
        tidy_value(value, false);
    }
}

fn tidy_value(value: &mut toml::Value, channel: bool) {
    match value {
        toml::Value::Float(v) => *v = rounded(*v, channel),
        toml::Value::Array(items) => items.iter_mut().for_each(|i| tidy_value(i, true)),
        toml::Value::Table(t) => tidy(t),
        _ => {}
    }
}

/// `v` to [`DIGITS`] significant digits; a `channel` below
/// [`NEGLIGIBLE_CHANNEL`] to 0.
fn rounded(v: f64, channel: bool) -> f64 {
    if !v.is_finite() || v == 0.0 {
        return v;
    }
    if channel && v.abs() < NEGLIGIBLE_CHANNEL {
        return 0.0;
    }
    format!("{v:.prec$e}", prec = DIGITS - 1)
        .parse()
        .unwrap_or(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_written_short() {
        let mut t: toml::Table =
            "k_d = [2.2859258930196802e-10, 0.123456789, 3.0]\nk_e = 1234.56789\nalpha = 1.23456789e-7"
                .parse()
                .unwrap();
        tidy(&mut t);
        assert_eq!(
            toml::to_string(&t).unwrap(),
            "alpha = 0.000000123457\nk_d = [0.0, 0.123457, 3.0]\nk_e = 1234.57\n"
        );
    }
}
