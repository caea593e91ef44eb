//! Axes: value ranges (of the data, with a margin) and tick labels (numbers, class names).

/// The smallest and largest of `values` (∞ and −∞ without any; NaN is passed over).
pub(super) fn extent(values: impl IntoIterator<Item = f64>) -> (f64, f64) {
    values
        .into_iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(v), b.max(v)))
}

/// The range of `values`, at least 1e-9 wide, or `0..1` without any finite one.
pub(super) fn data_range(values: impl IntoIterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = extent(values);
    if lo.is_finite() {
        (lo, hi.max(lo + 1e-9))
    } else {
        (0.0, 1.0)
    }
}

/// `lo..hi` widened by `pad` of its length on each side; a point becomes a small interval and
/// a non-finite range `0..1`.
pub(super) fn nice_range(lo: f64, hi: f64, pad: f64) -> (f64, f64) {
    if !(lo.is_finite() && hi.is_finite()) {
        return (0.0, 1.0);
    }
    if hi - lo < 1e-12 {
        let d = if lo.abs() > 1e-12 { lo.abs() * 0.1 } else { 1.0 };
        return (lo - d, hi + d);
    }
    let d = (hi - lo) * pad;
    (lo - d, hi + d)
}

/// Tick label: short, without trailing zeros; thousands as "k" above 10 000.
pub fn format_tick(v: f64) -> String {
    let a = v.abs();
    if a >= 10_000.0 {
        let k = v / 1000.0;
        if (k - k.round()).abs() < 1e-9 {
            format!("{}k", k.round())
        } else {
            format!("{k:.1}k")
        }
    } else if a < 1e-12 {
        // a tick at 0 that rounding moved off it
        "0".to_string()
    } else if a >= 100.0 {
        format!("{}", v.round())
    } else if a >= 1.0 {
        trim(format!("{v:.2}"))
    } else if a >= 0.01 {
        trim(format!("{v:.3}"))
    } else {
        // small values (rewards per step): two significant digits, never a bare "0"
        let decimals = (-a.log10()).ceil() as usize + 1;
        trim(format!("{v:.decimals$}"))
    }
}

/// Tick label on an axis spanning `span`: as [`format_tick`], with more decimals where its
/// precision would give neighbouring ticks the same label (a narrow range far from 0, e.g.
/// rewards per step of 0.00122 … 0.00134).
pub fn format_tick_within(v: f64, span: f64) -> String {
    let plain = format_tick(v);
    let a = v.abs();
    if !(span.is_finite() && span > 0.0 && (1e-12..10_000.0).contains(&a)) {
        return plain;
    }
    // ticks are at least span/20 apart
    let needed = (-(span / 20.0).log10()).ceil().clamp(0.0, 15.0) as usize;
    let shown = plain.split('.').nth(1).map_or(0, str::len);
    if shown >= needed {
        plain
    } else {
        trim(format!("{v:.needed$}"))
    }
}

fn trim(s: String) -> String {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// The class name at integer tick `v` of a categorical axis (empty between classes).
pub(super) fn class_tick(v: f64, classes: &[String]) -> String {
    let i = v.round();
    if (v - i).abs() < 1e-6 && i >= 0.0 && (i as usize) < classes.len() {
        classes[i as usize].clone()
    } else {
        String::new()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_read_well() {
        assert_eq!(format_tick(30_000.0), "30k");
        assert_eq!(format_tick(12_500.0), "12.5k");
        assert_eq!(format_tick(250.0), "250");
        assert_eq!(format_tick(2.5), "2.5");
        assert_eq!(format_tick(0.125), "0.125");
        assert_eq!(format_tick(0.0), "0");
        assert_eq!(format_tick(0.0004), "0.0004");
        assert_eq!(format_tick(-0.00015), "-0.00015");
        assert_eq!(format_tick(0.005), "0.005");
        assert_eq!(format_tick(-6.8e-21), "0");
    }

    #[test]
    fn ticks_of_a_narrow_range_stay_distinct() {
        let labels: Vec<String> = (0..7)
            .map(|k| format_tick_within(0.00122 + 0.00002 * k as f64, 0.00015))
            .collect();
        let mut distinct = labels.clone();
        distinct.dedup();
        assert_eq!(distinct.len(), 7, "{labels:?}");
        assert_eq!(labels[0], "0.00122");
        assert_eq!(format_tick_within(250.5, 4.0), "250.5");
        // a wide range keeps the short labels
        assert_eq!(format_tick_within(0.0004, 0.01), "0.0004");
        assert_eq!(format_tick_within(30_000.0, 1.0), "30k");
    }
}
