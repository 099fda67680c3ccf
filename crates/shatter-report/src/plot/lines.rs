//! The line plot: ranges, axes, lines, bands and legend, drawn on any plotters backend.

use std::ops::Range;
use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;

use super::font::{FAMILY, ensure_registered};
use crate::ReportError;

/// Colours of the series, in order (the Okabe–Ito palette, readable by colour-blind
/// people, with black last); a ninth series reuses the first colour.
const COLOURS: [RGBColor; 8] = [
    RGBColor(0, 114, 178),
    RGBColor(230, 159, 0),
    RGBColor(0, 158, 115),
    RGBColor(213, 94, 0),
    RGBColor(204, 121, 167),
    RGBColor(86, 180, 233),
    RGBColor(150, 130, 0),
    RGBColor(0, 0, 0),
];

/// Series with at most this many points also get a dot at every point.
const MAX_POINTS_WITH_MARKERS: usize = 60;

/// One line of a plot.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Name shown in the legend.
    pub name: String,
    /// The points `(x, y)`, drawn in this order.
    pub points: Vec<(f64, f64)>,
    /// Optional band `(x, low, high)` drawn as a light area behind the line (for example
    /// the min and max of repeated runs).
    pub band: Option<Vec<(f64, f64, f64)>>,
}

impl Series {
    /// A series without a band.
    pub fn new(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Self {
            name: name.into(),
            points,
            band: None,
        }
    }

    /// The same series with a band `(x, low, high)`.
    pub fn with_band(mut self, band: Vec<(f64, f64, f64)>) -> Self {
        self.band = Some(band);
        self
    }
}

/// Where the legend goes inside the plot area.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum LegendPosition {
    /// Top left corner (the default: rising curves leave it empty).
    #[default]
    UpperLeft,
    /// Top right corner.
    UpperRight,
    /// Bottom right corner.
    LowerRight,
}

/// A line plot and its settings.
///
/// ```
/// use shatter_report::plot::{LinePlot, Series};
///
/// let dir = tempfile::tempdir()?;
/// let series = [Series::new("cube", vec![(0.0, 1.0), (10.0, 2.0)])];
/// let plot = LinePlot::new(&series, "Creation time", "random points", "ms");
/// plot.write_svg(dir.path().join("plot.svg"))?;
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone)]
pub struct LinePlot<'a> {
    /// The lines.
    pub series: &'a [Series],
    /// Caption above the plot.
    pub title: String,
    /// Label of the horizontal axis.
    pub x_label: String,
    /// Label of the vertical axis.
    pub y_label: String,
    /// Size in pixels (PNG) or user units (SVG).
    pub size: (u32, u32),
    /// Whether the vertical axis starts at zero (when every value is positive).
    pub y_from_zero: bool,
    /// Where the legend goes.
    pub legend: LegendPosition,
}

/// Draws `series` as a line plot and writes it both as PNG and as SVG.
///
/// Fails on an empty plot, a non-finite value, or a file that cannot be written.
pub fn plot_lines(
    series: &[Series],
    title: &str,
    x_label: &str,
    y_label: &str,
    png_path: impl AsRef<Path>,
    svg_path: impl AsRef<Path>,
) -> Result<(), ReportError> {
    let plot = LinePlot::new(series, title, x_label, y_label);
    plot.write_png(png_path)?;
    plot.write_svg(svg_path)
}

impl<'a> LinePlot<'a> {
    /// A 1000×600 plot of `series` whose vertical axis starts at zero.
    pub fn new(series: &'a [Series], title: &str, x_label: &str, y_label: &str) -> Self {
        Self {
            series,
            title: title.to_string(),
            x_label: x_label.to_string(),
            y_label: y_label.to_string(),
            size: (1000, 600),
            y_from_zero: true,
            legend: LegendPosition::UpperLeft,
        }
    }

    /// Writes the plot as a PNG image.
    pub fn write_png(&self, path: impl AsRef<Path>) -> Result<(), ReportError> {
        let path = path.as_ref();
        let ranges = self.ranges()?;
        let root = BitMapBackend::new(path, self.size).into_drawing_area();
        self.draw(&root, &ranges)
            .and_then(|()| root.present().map_err(|e| e.to_string()))
            .map_err(|message| ReportError::Plot {
                path: path.to_path_buf(),
                message,
            })
    }

    /// Writes the plot as an SVG document.
    pub fn write_svg(&self, path: impl AsRef<Path>) -> Result<(), ReportError> {
        let path = path.as_ref();
        let ranges = self.ranges()?;
        let root = SVGBackend::new(path, self.size).into_drawing_area();
        self.draw(&root, &ranges)
            .and_then(|()| root.present().map_err(|e| e.to_string()))
            .map_err(|message| ReportError::Plot {
                path: path.to_path_buf(),
                message,
            })
    }

    /// The axis ranges covering every point and band, with a little margin.
    fn ranges(&self) -> Result<(Range<f64>, Range<f64>), ReportError> {
        let mut xs = Vec::new();
        let mut ys = Vec::new();
        for s in self.series {
            for (i, &(x, y)) in s.points.iter().enumerate() {
                if !x.is_finite() || !y.is_finite() {
                    return Err(ReportError::NonFinitePoint {
                        series: s.name.clone(),
                        index: i,
                    });
                }
                xs.push(x);
                ys.push(y);
            }
            for (i, &(x, lo, hi)) in s.band.iter().flatten().enumerate() {
                if !x.is_finite() || !lo.is_finite() || !hi.is_finite() {
                    return Err(ReportError::NonFinitePoint {
                        series: format!("{} (band)", s.name),
                        index: i,
                    });
                }
                xs.push(x);
                ys.extend([lo, hi]);
            }
        }
        if xs.is_empty() {
            return Err(ReportError::EmptyPlot {
                title: self.title.clone(),
            });
        }
        let (x_min, x_max) = min_max(&xs);
        let (y_min, y_max) = min_max(&ys);
        let mut y_range = padded(y_min, y_max, 0.05);
        if self.y_from_zero && y_min >= 0.0 {
            y_range.start = 0.0;
        }
        Ok((padded(x_min, x_max, 0.0), y_range))
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        (x_range, y_range): &(Range<f64>, Range<f64>),
    ) -> Result<(), String> {
        ensure_registered()?;
        let err = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
        root.fill(&WHITE).map_err(err)?;
        let mut chart = ChartBuilder::on(root)
            .caption(&self.title, (FAMILY, 26))
            .margin(16)
            .x_label_area_size(50)
            .y_label_area_size(70)
            .build_cartesian_2d(x_range.clone(), y_range.clone())
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc(self.x_label.as_str())
            .y_desc(self.y_label.as_str())
            .label_style((FAMILY, 15))
            .x_label_formatter(&tick_label)
            .y_label_formatter(&tick_label)
            .axis_desc_style((FAMILY, 18))
            .light_line_style(RGBColor(242, 242, 242))
            .draw()
            .map_err(err)?;

        for (i, s) in self.series.iter().enumerate() {
            let colour = COLOURS[i % COLOURS.len()];
            if let Some(band) = s.band.as_ref().filter(|b| !b.is_empty()) {
                let outline: Vec<(f64, f64)> = band
                    .iter()
                    .map(|&(x, _, hi)| (x, hi))
                    .chain(band.iter().rev().map(|&(x, lo, _)| (x, lo)))
                    .collect();
                chart
                    .draw_series(std::iter::once(Polygon::new(outline, colour.mix(0.18))))
                    .map_err(err)?;
            }
            let line_style = colour.stroke_width(2);
            chart
                .draw_series(LineSeries::new(s.points.iter().copied(), line_style))
                .map_err(err)?
                .label(s.name.as_str())
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 24, y)], colour.stroke_width(3))
                });
            if s.points.len() <= MAX_POINTS_WITH_MARKERS {
                chart
                    .draw_series(s.points.iter().map(|&p| Circle::new(p, 3, colour.filled())))
                    .map_err(err)?;
            }
        }

        let position = match self.legend {
            LegendPosition::UpperLeft => SeriesLabelPosition::UpperLeft,
            LegendPosition::UpperRight => SeriesLabelPosition::UpperRight,
            LegendPosition::LowerRight => SeriesLabelPosition::LowerRight,
        };
        chart
            .configure_series_labels()
            .position(position)
            .label_font((FAMILY, 16))
            .background_style(WHITE.mix(0.85))
            .border_style(RGBColor(160, 160, 160))
            .draw()
            .map_err(err)?;
        Ok(())
    }
}

/// A tick label without needless zeros: `10`, `2.5`, `0.125`.
fn tick_label(v: &f64) -> String {
    let text = format!("{v:.4}");
    let text = text.trim_end_matches('0').trim_end_matches('.');
    if text == "-0" {
        "0".to_string()
    } else {
        text.to_string()
    }
}

fn min_max(values: &[f64]) -> (f64, f64) {
    values
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        })
}

/// `lo..hi` widened by `margin` of its length on each side (or by 1 when it is empty).
fn padded(lo: f64, hi: f64, margin: f64) -> Range<f64> {
    let span = hi - lo;
    if span <= 0.0 {
        let pad = if lo == 0.0 { 1.0 } else { lo.abs() * 0.1 };
        return (lo - pad)..(hi + pad);
    }
    (lo - margin * span)..(hi + margin * span)
}

#[cfg(test)]
mod tests {
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
        assert!(
            matches!(e, ReportError::NonFinitePoint { ref series, index: 1 } if series == "bird")
        );
    }

    #[test]
    fn tick_labels_drop_needless_zeros() {
        assert_eq!(tick_label(&10.0), "10");
        assert_eq!(tick_label(&2.5), "2.5");
        assert_eq!(tick_label(&0.125), "0.125");
        assert_eq!(tick_label(&-0.0), "0");
    }

    #[test]
    fn an_empty_plot_is_refused() {
        let s = [Series::new("a", vec![])];
        let e = LinePlot::new(&s, "empty", "x", "y").ranges().unwrap_err();
        assert!(matches!(e, ReportError::EmptyPlot { .. }));
    }
}
