//! The line plot's ranges, tick labels and automatic legend corner.

#![allow(clippy::unwrap_used)]
use super::*;

#[test]
fn ranges_cover_points_and_bands_and_start_at_zero() {
    let s = [Series::new("a", vec![(1.0, 5.0), (3.0, 7.0)])
        .with_band(vec![(1.0, 4.0, 6.0), (3.0, 6.5, 9.0)])];
    let (x, y) = LinePlot::new(&s, "t", "x", "y").ranges().unwrap();
    assert_eq!(x, 1.0..3.0);
    assert_eq!(y.start, 0.0);
    assert!(y.end >= 9.0);
}

#[test]
fn a_single_point_gets_a_non_empty_range() {
    let s = [Series::new("a", vec![(2.0, 0.0)])];
    let (x, y) = LinePlot::new(&s, "t", "x", "y").ranges().unwrap();
    assert!(x.start < 2.0 && x.end > 2.0);
    assert!(y.start <= 0.0 && y.end > 0.0 && y.start < y.end);
}

#[test]
fn nan_is_refused_with_the_series_and_index() {
    let s = [Series::new("bird", vec![(0.0, 1.0), (1.0, f64::NAN)])];
    let e = LinePlot::new(&s, "t", "x", "y").ranges().unwrap_err();
    assert!(matches!(e, ReportError::NonFinitePoint { ref series, index: 1 } if series == "bird"));
}

#[test]
fn tick_labels_drop_needless_zeros() {
    assert_eq!(tick_label(&10.0), "10");
    assert_eq!(tick_label(&2.5), "2.5");
    assert_eq!(tick_label(&0.125), "0.125");
    assert_eq!(tick_label(&-0.0), "0");
}

fn corner_of(lines: Vec<Vec<(f64, f64)>>) -> LegendPosition {
    let s: Vec<Series> = lines
        .into_iter()
        .enumerate()
        .map(|(i, points)| Series::new(format!("line {i}"), points))
        .collect();
    let plot = LinePlot::new(&s, "t", "x", "y");
    let (x, y) = plot.ranges().unwrap();
    plot.emptiest_corner(&x, &y, TITLE_SIZE)
        .unwrap_or(LegendPosition::Outside)
}

#[test]
fn the_automatic_legend_goes_where_the_lines_are_not() {
    let line = |f: fn(f64) -> f64| (0..=20).map(|i| (i as f64, f(i as f64))).collect();
    // Rising: the upper left corner is empty.
    assert_eq!(corner_of(vec![line(|x| x)]), LegendPosition::UpperLeft);
    // Falling from the top left: the upper right is empty.
    assert_eq!(
        corner_of(vec![line(|x| 20.0 - x)]),
        LegendPosition::UpperRight
    );
    // Along the top, and a short stretch along the bottom at the left: only the
    // lower right is empty.
    let top = line(|_| 20.0);
    let bottom_left = vec![(0.0, 0.0), (2.0, 0.0)];
    assert_eq!(
        corner_of(vec![top.clone(), bottom_left.clone()]),
        LegendPosition::LowerRight
    );
    // The same stretch at the right: only the lower left is empty.
    let bottom_right = vec![(18.0, 0.0), (20.0, 0.0)];
    assert_eq!(
        corner_of(vec![top, bottom_right]),
        LegendPosition::LowerLeft
    );
    // An X crosses every corner: the legend goes outside.
    assert_eq!(
        corner_of(vec![line(|x| x), line(|x| 20.0 - x)]),
        LegendPosition::Outside
    );
}

#[test]
fn an_empty_plot_is_refused() {
    let s = [Series::new("a", vec![])];
    let e = LinePlot::new(&s, "empty", "x", "y").ranges().unwrap_err();
    assert!(matches!(e, ReportError::EmptyPlot { .. }));
}
