//! Tests of the estimates, the limits and the formats.

#![allow(clippy::unwrap_used)]
use super::limits::meminfo_kib;
use super::*;

fn limits(gb: f64, seconds: Option<f64>) -> Limits {
    Limits {
        memory_bytes: Some((gb * 1e9) as u64),
        seconds,
        memory_source: "test",
    }
}

#[test]
fn the_issue_example_is_refused_with_both_figures() {
    let e = limits(24.0, None)
        .check("3,000,000,000 points", &Estimate::delaunay(3_000_000_000))
        .unwrap_err();
    let text = e.to_string();
    assert!(
        text.starts_with("3,000,000,000 points need about 786 GB"),
        "{text}"
    );
    assert!(
        text.contains(" GB; this machine has 24 GB (test)"),
        "{text}"
    );
    let BudgetError::Memory { needs_bytes, .. } = e else {
        panic!("not a memory refusal: {e}");
    };
    // 3e9 points at about 218 bytes each at most (bench delaunay) and their 24 bytes.
    assert!((7.2e11..8.5e11).contains(&needs_bytes), "{needs_bytes}");
}

#[test]
fn a_request_is_refused_above_the_usable_share_of_the_memory() {
    let l = limits(10.0, None);
    let at = |gb: f64| Estimate {
        bytes: gb * 1e9,
        seconds: 0.0,
    };
    assert!(l.check("it", &at(7.9)).is_ok());
    let e = l.check("it", &at(9.0)).unwrap_err().to_string();
    assert_eq!(
        e,
        "it need about 9 GB; this machine has 10 GB (test), of which a run may use 8 GB"
    );
}

#[test]
fn absurd_counts_are_estimated_without_overflow() {
    for e in [
        Estimate::delaunay(u64::MAX),
        Estimate::tetra_fracture(u64::MAX, u64::MAX),
        Estimate::voronoi_fracture(u64::MAX, u64::MAX),
        Estimate::slice_fracture(u64::MAX, 10),
    ] {
        assert!(e.bytes.is_finite() && e.bytes > 1e20, "{e:?}");
        assert!(limits(24.0, None).check("it", &e).is_err());
    }
}

#[test]
fn a_time_limit_refuses_with_the_duration() {
    let e = Estimate {
        bytes: 1.0,
        seconds: 3.0e9,
    };
    let err = limits(24.0, Some(3600.0))
        .check("the scene", &e)
        .unwrap_err();
    assert_eq!(
        err.to_string(),
        "the scene would take about 95 years; the limit is 1 hour"
    );
    assert!(limits(24.0, None).check("the scene", &e).is_ok());
    assert!(
        Limits::none()
            .check("it", &Estimate::delaunay(u64::MAX))
            .is_ok()
    );
}

#[test]
fn estimates_grow_with_the_request() {
    assert!(Estimate::delaunay(2000).bytes > Estimate::delaunay(1000).bytes);
    let (small, big) = (
        Estimate::voronoi_fracture(10, 1000),
        Estimate::voronoi_fracture(1000, 1000),
    );
    assert!(big.bytes > small.bytes && big.seconds > small.seconds);
    assert!(Estimate::tetra_fracture(100, 0).bytes > Estimate::delaunay(100).bytes);
    assert!(Estimate::tetra_fracture(100, 100).seconds > Estimate::tetra_fracture(100, 0).seconds);
    assert_eq!(slice_pieces_at_most(0), 1.0);
    assert_eq!(slice_pieces_at_most(1), 2.0);
    assert_eq!(slice_pieces_at_most(3), 8.0);
    assert_eq!(slice_pieces(1), 1.6);
    assert_eq!(slice_pieces(48), 0.6 * 48.0 * 48.0 + 48.0);
    assert_eq!(fragments_at_most(4000.0), 4000.0);
    assert_eq!(fragments_at_most(1e9), 10_000.0);
}

#[test]
fn meminfo_fields_are_read_in_kib() {
    let text = "MemTotal:       24576000 kB\nMemFree:  100 kB\nMemAvailable:   20000000 kB\n";
    assert_eq!(meminfo_kib(text, "MemTotal:"), Some(24_576_000));
    assert_eq!(meminfo_kib(text, "MemAvailable:"), Some(20_000_000));
    assert_eq!(meminfo_kib(text, "SwapTotal:"), None);
}

#[test]
fn this_machine_has_a_memory_figure_on_linux() {
    if std::path::Path::new("/proc/meminfo").exists() {
        let m = machine_memory().unwrap();
        assert!(m.limit > 1 << 28, "{m:?}");
        assert!(m.available.is_none_or(|a| a <= m.limit), "{m:?}");
    }
}

#[test]
fn figures_are_formatted_for_people() {
    assert_eq!(format_count(3_000_000_000), "3,000,000,000");
    assert_eq!(format_count(999), "999");
    assert_eq!(format_count(1000), "1,000");
    assert_eq!(format_bytes(570e9), "570 GB");
    assert_eq!(format_bytes(1.5e6), "1.5 MB");
    assert_eq!(format_bytes(24e9), "24 GB");
    assert_eq!(format_bytes(12.0), "12 bytes");
    assert_eq!(format_duration(40.0), "40 seconds");
    assert_eq!(format_duration(2.5), "2.5 seconds");
    assert_eq!(format_duration(3.2 * 3600.0), "3.2 hours");
    assert_eq!(format_duration(90.0), "1.5 minutes");
}
