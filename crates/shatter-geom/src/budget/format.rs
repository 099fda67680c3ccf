//! Counts, byte sizes and durations as a refusal message prints them.

/// `1234567` → `"1,234,567"`.
pub fn format_count(n: u64) -> String {
    let digits = n.to_string();
    let mut out = String::with_capacity(digits.len() + digits.len() / 3);
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(c);
    }
    out
}

/// Bytes in decimal units with two or three significant digits: `"570 GB"`, `"1.5 MB"`.
pub fn format_bytes(bytes: f64) -> String {
    const UNITS: [&str; 7] = ["bytes", "kB", "MB", "GB", "TB", "PB", "EB"];
    let mut value = bytes.max(0.0);
    let mut unit = 0;
    while value >= 1000.0 && unit + 1 < UNITS.len() {
        value /= 1000.0;
        unit += 1;
    }
    if value >= 1000.0 {
        return format!("{bytes:.1e} bytes");
    }
    format!("{} {}", significant(value), UNITS[unit])
}

/// Seconds as a readable duration: `"40 seconds"`, `"3.2 hours"`, `"95 years"`.
pub fn format_duration(seconds: f64) -> String {
    const STEPS: [(f64, &str); 5] = [
        (60.0, "minutes"),
        (3600.0, "hours"),
        (86_400.0, "days"),
        (365.25 * 86_400.0, "years"),
        (f64::INFINITY, ""),
    ];
    // NaN is printed as seconds too.
    if seconds.is_nan() || seconds < 60.0 {
        return format!("{} seconds", significant(seconds.max(0.0)));
    }
    let mut unit = (60.0, "minutes");
    for w in STEPS.windows(2) {
        if seconds >= w[0].0 {
            unit = w[0];
        }
    }
    let value = seconds / unit.0;
    if value >= 1e6 {
        return format!("{value:.1e} {}", unit.1);
    }
    let number = significant(value);
    // "1 hour", not "1 hours".
    let name = if number == "1" {
        unit.1.trim_end_matches('s')
    } else {
        unit.1
    };
    format!("{number} {name}")
}

/// Two significant digits below 100, whole numbers above.
fn significant(v: f64) -> String {
    if v >= 10.0 || v == v.round() {
        format!("{v:.0}")
    } else {
        format!("{v:.1}")
    }
}
