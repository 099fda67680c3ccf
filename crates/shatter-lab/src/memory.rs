//! Process memory figures from `/proc/self/status` (Linux only; `None` elsewhere).
//!
//! These are process-wide: they include the input points, the allocator's slack and
//! everything else the process holds.

/// Resident set size now, in bytes (`VmRSS`).
pub fn current_rss_bytes() -> Option<u64> {
    status_field_kib("VmRSS:").map(|k| k * 1024)
}

/// Peak resident set size since start or since the last [`reset_peak`], in bytes (`VmHWM`).
pub fn peak_rss_bytes() -> Option<u64> {
    status_field_kib("VmHWM:").map(|k| k * 1024)
}

/// Resets the peak (`VmHWM`) to the current RSS by writing `5` to `/proc/self/clear_refs`
/// (Linux ≥ 4.0). Returns whether it worked; when not, the peak stays process-wide.
pub fn reset_peak() -> bool {
    std::fs::write("/proc/self/clear_refs", "5").is_ok()
}

fn status_field_kib(field: &str) -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    parse_status_field_kib(&status, field)
}

fn parse_status_field_kib(status: &str, field: &str) -> Option<u64> {
    let line = status.lines().find(|l| l.starts_with(field))?;
    line[field.len()..].split_whitespace().next()?.parse().ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn status_fields_are_read_in_kib() {
        let status = "Name:\tshatter\nVmHWM:\t  12345 kB\nVmRSS:\t   678 kB\n";
        assert_eq!(parse_status_field_kib(status, "VmHWM:"), Some(12345));
        assert_eq!(parse_status_field_kib(status, "VmRSS:"), Some(678));
        assert_eq!(parse_status_field_kib(status, "VmSwap:"), None);
    }

    #[test]
    fn peak_is_at_least_current_on_linux() {
        // Current first: the peak read afterwards can only be higher.
        let now = current_rss_bytes();
        let peak = peak_rss_bytes();
        if let (Some(peak), Some(now)) = (peak, now) {
            assert!(peak >= now, "peak {peak} < current {now}");
        }
    }
}
