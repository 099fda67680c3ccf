//! The legend: the corner [`LegendPosition::Auto`] picks, and the legend drawn right of
//! the plot.

use std::ops::Range;

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::{
    COLOURS, LEGEND_PAD, LEGEND_SIZE, LEGEND_TEXT_X, LegendPosition, LinePlot, MARGIN,
    RIGHT_MARGIN, X_LABEL_AREA, Y_LABEL_AREA,
};
use crate::plot::font::FAMILY;

impl LinePlot<'_> {
    /// Width in pixels of a legend drawn right of the plot: a sample line and the
    /// longest name, with padding.
    pub(super) fn outside_legend_width<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
    ) -> Result<u32, DrawingAreaErrorKind<DB::ErrorType>> {
        let style = TextStyle::from((FAMILY, LEGEND_SIZE).into_font());
        let mut longest = 0;
        for s in self.series {
            longest = longest.max(root.estimate_text_size(&s.name, &style)?.0);
        }
        Ok(LEGEND_TEXT_X + longest + 2 * LEGEND_PAD)
    }

    /// Draws the legend in `area` (right of the plot), its box starting `top` pixels
    /// down: one row per series, a sample of its line then its name.
    pub(super) fn draw_outside_legend<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        top: i32,
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
        let style = TextStyle::from((FAMILY, LEGEND_SIZE).into_font())
            .pos(Pos::new(HPos::Left, VPos::Center));
        let row = (LEGEND_SIZE * 3 / 2) as i32;
        let pad = LEGEND_PAD as i32;
        let right = area.dim_in_pixel().0 as i32 - pad;
        let bottom = top + 2 * pad + row * self.series.len() as i32;
        area.draw(&Rectangle::new(
            [(0, top), (right, bottom)],
            RGBColor(160, 160, 160).stroke_width(1),
        ))?;
        for (i, s) in self.series.iter().enumerate() {
            let colour = COLOURS[i % COLOURS.len()];
            let y = top + pad + row * i as i32 + row / 2;
            area.draw(&PathElement::new(
                vec![(pad, y), (pad + 24, y)],
                colour.stroke_width(3),
            ))?;
            area.draw(&Text::new(
                s.name.clone(),
                (LEGEND_TEXT_X as i32, y),
                style.clone(),
            ))?;
        }
        Ok(())
    }

    /// The corner for [`LegendPosition::Auto`]: the first whose legend-sized box (in
    /// the plot's own proportions) holds no sample of any line, or `None` when every
    /// corner is crossed.
    pub(super) fn emptiest_corner(
        &self,
        x_range: &Range<f64>,
        y_range: &Range<f64>,
        title_size: u32,
    ) -> Option<LegendPosition> {
        // The plot area in pixels, roughly (the caption takes about 1.5 lines).
        let plot_w = f64::from(
            self.size
                .0
                .saturating_sub(MARGIN + RIGHT_MARGIN + Y_LABEL_AREA),
        )
        .max(1.0);
        let plot_h = f64::from(
            self.size
                .1
                .saturating_sub(2 * MARGIN + X_LABEL_AREA + title_size * 3 / 2),
        )
        .max(1.0);
        // The legend box in pixels: a row per series, a sample line and the longest name,
        // plus plotters' 10 px offset from the corner.
        let longest = self
            .series
            .iter()
            .map(|s| s.name.chars().count())
            .max()
            .unwrap_or(0) as f64;
        let legend_w = 10.0 + 40.0 + longest * 0.6 * f64::from(LEGEND_SIZE);
        let legend_h = 10.0 + 10.0 + self.series.len() as f64 * 1.25 * f64::from(LEGEND_SIZE);
        let (w, h) = ((legend_w / plot_w).min(1.0), (legend_h / plot_h).min(1.0));
        let span = |r: &Range<f64>| (r.end - r.start).max(f64::MIN_POSITIVE);
        // Samples of every line in the unit square (0,0 = lower left), 16 per segment.
        let mut samples = Vec::new();
        for s in self.series {
            let unit: Vec<(f64, f64)> = s
                .points
                .iter()
                .map(|&(x, y)| {
                    (
                        (x - x_range.start) / span(x_range),
                        (y - y_range.start) / span(y_range),
                    )
                })
                .collect();
            samples.extend(unit.first().copied());
            for pair in unit.windows(2) {
                let ((x0, y0), (x1, y1)) = (pair[0], pair[1]);
                samples.extend((1..=16).map(|k| {
                    let t = f64::from(k) / 16.0;
                    (x0 + t * (x1 - x0), y0 + t * (y1 - y0))
                }));
            }
        }
        let corners = [
            (LegendPosition::UpperLeft, 0.0, 1.0 - h),
            (LegendPosition::UpperRight, 1.0 - w, 1.0 - h),
            (LegendPosition::LowerRight, 1.0 - w, 0.0),
            (LegendPosition::LowerLeft, 0.0, 0.0),
        ];
        let crossed = |u0: f64, v0: f64| {
            samples
                .iter()
                .any(|&(u, v)| u >= u0 && u <= u0 + w && v >= v0 && v <= v0 + h)
        };
        corners
            .iter()
            .find(|&&(_, u0, v0)| !crossed(u0, v0))
            .map(|&(corner, _, _)| corner)
    }
}
