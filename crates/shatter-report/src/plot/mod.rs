//! Line plots written as PNG and SVG: one line per series, axis labels, a legend, and an
//! optional min/max band around each line.

mod font;
mod lines;

pub use lines::{LegendPosition, LinePlot, Series, plot_lines};
