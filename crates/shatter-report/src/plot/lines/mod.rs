//! The line plot: ranges, axes, lines, bands and legend, drawn on any plotters backend.

mod legend;

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
    /// The first corner whose legend-sized area no line crosses, in the order upper
    /// left, upper right, lower right, lower left; right of the plot when every corner
    /// is crossed (the default).
    #[default]
    Auto,
    /// Top left corner.
    UpperLeft,
    /// Top right corner.
    UpperRight,
    /// Bottom right corner.
    LowerRight,
    /// Bottom left corner.
    LowerLeft,
    /// Right of the plot area, outside it (the plot gets narrower).
    Outside,
}

/// Font size of the title; a title too wide for the image is drawn smaller, down to
/// [`MIN_TITLE_SIZE`].
const TITLE_SIZE: u32 = 26;
/// Smallest font size a long title is shrunk to.
const MIN_TITLE_SIZE: u32 = 12;
/// Margin around the chart, in pixels.
const MARGIN: u32 = 16;
/// Margin right of the chart: wider, so that the last x tick label, centred on the
/// right edge of the plot, is not cut off (room for about ten characters).
const RIGHT_MARGIN: u32 = 48;
/// Height of the area under the plot for the x tick labels and description.
const X_LABEL_AREA: u32 = 50;
/// Width of the area left of the plot for the y tick labels and description.
const Y_LABEL_AREA: u32 = 70;
/// Font size of the legend.
const LEGEND_SIZE: u32 = 16;
/// Padding inside a legend drawn outside the plot, in pixels.
const LEGEND_PAD: u32 = 8;
/// Where the names start in a legend drawn outside the plot (after the line sample).
const LEGEND_TEXT_X: u32 = 40;

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
            legend: LegendPosition::Auto,
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
        let legend = match self.legend {
            LegendPosition::Auto => {
                let title_size = self.title_size(root, self.size.0).map_err(err)?;
                self.emptiest_corner(x_range, y_range, title_size)
                    .unwrap_or(LegendPosition::Outside)
            }
            fixed => fixed,
        };
        let (chart_area, legend_area) = if legend == LegendPosition::Outside {
            let width = self.outside_legend_width(root).map_err(err)?;
            let (chart_area, legend_area) =
                root.split_horizontally(self.size.0.saturating_sub(width));
            (chart_area, Some(legend_area))
        } else {
            (root.clone(), None)
        };
        let title_size = self
            .title_size(&chart_area, chart_area.dim_in_pixel().0)
            .map_err(err)?;
        let mut chart = ChartBuilder::on(&chart_area)
            .caption(&self.title, (FAMILY, title_size))
            .margin(MARGIN)
            .margin_right(RIGHT_MARGIN)
            .x_label_area_size(X_LABEL_AREA)
            .y_label_area_size(Y_LABEL_AREA)
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

        if let Some(area) = legend_area {
            // Level with the top of the plot area: below the margin and the caption.
            let top = (MARGIN + title_size * 3 / 2) as i32;
            return self.draw_outside_legend(&area, top).map_err(err);
        }
        let position = match legend {
            LegendPosition::UpperLeft | LegendPosition::Auto | LegendPosition::Outside => {
                SeriesLabelPosition::UpperLeft
            }
            LegendPosition::UpperRight => SeriesLabelPosition::UpperRight,
            LegendPosition::LowerRight => SeriesLabelPosition::LowerRight,
            LegendPosition::LowerLeft => SeriesLabelPosition::LowerLeft,
        };
        chart
            .configure_series_labels()
            .position(position)
            .label_font((FAMILY, LEGEND_SIZE))
            .background_style(WHITE.mix(0.85))
            .border_style(RGBColor(160, 160, 160))
            .draw()
            .map_err(err)?;
        Ok(())
    }
}

impl LinePlot<'_> {
    /// The largest title font size (at most [`TITLE_SIZE`]) at which the title fits a
    /// chart `width` pixels wide inside the margins (plotters centres it between them).
    fn title_size<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        width: u32,
    ) -> Result<u32, DrawingAreaErrorKind<DB::ErrorType>> {
        let available = width.saturating_sub(MARGIN + RIGHT_MARGIN);
        let mut size = TITLE_SIZE;
        while size > MIN_TITLE_SIZE {
            let style = TextStyle::from((FAMILY, size).into_font());
            let (width, _) = root.estimate_text_size(&self.title, &style)?;
            if width <= available {
                break;
            }
            size -= 1;
        }
        Ok(size)
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
mod tests;
