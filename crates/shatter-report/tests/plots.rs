//! Plot files exist; the PNG decodes at the requested size and shows the lines in their
//! colours; the SVG is well-formed XML carrying the title, the axis labels and the
//! legend.
#![allow(clippy::unwrap_used)]

use std::collections::HashSet;
use std::path::Path;

use shatter_report::ReportError;
use shatter_report::plot::{LegendPosition, LinePlot, Series, plot_lines};

/// RGB pixels of a PNG file, with its size.
fn decode_png(path: &Path) -> (u32, u32, Vec<[u8; 3]>) {
    let file = std::io::BufReader::new(std::fs::File::open(path).unwrap());
    let mut reader = png::Decoder::new(file).read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    let channels = info.color_type.samples();
    assert_eq!(info.bit_depth, png::BitDepth::Eight);
    let pixels = buf[..info.buffer_size()]
        .chunks(channels)
        .map(|p| [p[0], p[1], p[2]])
        .collect();
    (info.width, info.height, pixels)
}

fn two_series() -> Vec<Series> {
    let cube: Vec<(f64, f64)> = (0..=10).map(|i| (i as f64 * 10.0, i as f64)).collect();
    let bird: Vec<(f64, f64)> = (0..=10)
        .map(|i| {
            (
                i as f64 * 10.0,
                5.0 - 0.8 * i as f64 + 0.09 * (i * i) as f64,
            )
        })
        .collect();
    let band = bird.iter().map(|&(x, y)| (x, y - 0.5, y + 0.5)).collect();
    vec![
        Series::new("cube", cube),
        Series::new("bird", bird).with_band(band),
    ]
}

#[test]
fn png_and_svg_are_written_and_show_the_plot() {
    let dir = tempfile::tempdir().unwrap();
    let png_path = dir.path().join("creation.png");
    let svg_path = dir.path().join("creation.svg");
    plot_lines(
        &two_series(),
        "Creation time against random points",
        "random points",
        "time [ms]",
        &png_path,
        &svg_path,
    )
    .unwrap();

    let (w, h, pixels) = decode_png(&png_path);
    assert_eq!((w, h), (1000, 600));
    assert_eq!(pixels.len(), (w * h) as usize);
    let white = pixels.iter().filter(|p| **p == [255, 255, 255]).count();
    assert!(
        white < pixels.len() * 99 / 100,
        "the image is (almost) blank: {white} of {} pixels are white",
        pixels.len()
    );
    let colours: HashSet<[u8; 3]> = pixels.iter().copied().collect();
    // The first two series colours are drawn exactly somewhere (lines and markers).
    assert!(
        colours.contains(&[0, 114, 178]),
        "no pixel in the first series' colour"
    );
    assert!(
        colours.contains(&[230, 159, 0]),
        "no pixel in the second series' colour"
    );
    // Dark text and axes.
    assert!(pixels.iter().any(|p| p.iter().all(|&c| c < 40)));

    let svg = std::fs::read_to_string(&svg_path).unwrap();
    let doc = roxmltree::Document::parse(&svg).unwrap();
    assert_eq!(doc.root_element().tag_name().name(), "svg");
    let texts: Vec<String> = doc
        .descendants()
        .filter(|n| n.has_tag_name("text"))
        .filter_map(|n| n.text().map(|t| t.trim().to_string()))
        .collect();
    for expected in [
        "Creation time against random points",
        "random points",
        "time [ms]",
        "cube",
        "bird",
    ] {
        assert!(
            texts.iter().any(|t| t == expected),
            "no <text> '{expected}' in the SVG (texts: {texts:?})"
        );
    }
    let polylines = doc
        .descendants()
        .filter(|n| n.has_tag_name("polyline"))
        .count();
    assert!(
        polylines >= 2,
        "expected a polyline per series, found {polylines}"
    );
}

#[test]
fn png_size_follows_the_settings() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("small.png");
    let series = two_series();
    let mut plot = LinePlot::new(&series, "small", "x", "y");
    plot.size = (480, 320);
    plot.write_png(&path).unwrap();
    let (w, h, _) = decode_png(&path);
    assert_eq!((w, h), (480, 320));
}

#[test]
fn an_unwritable_path_is_an_error_not_a_panic() {
    let dir = tempfile::tempdir().unwrap();
    let series = two_series();
    let png = dir.path().join("missing/dir/p.png");
    let svg = dir.path().join("missing/dir/p.svg");
    let err = plot_lines(&series, "t", "x", "y", &png, &svg).unwrap_err();
    assert!(matches!(err, ReportError::Plot { .. }), "{err}");
}

/// Regression: a title wider than the image was drawn at full size, centred, and cut off
/// at both edges (the creation plot "Creation time (fracture + bodies and joints), …").
#[test]
fn a_long_title_is_shrunk_to_fit_inside_the_margins() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("long.png");
    let series = two_series();
    let title = "Creation time (fracture + bodies and joints), interior placement, mean of 5 \
                 runs (band: min–max)";
    let mut plot = LinePlot::new(&series, title, "random points", "time [ms]");
    plot.size = (800, 480);
    plot.write_png(&path).unwrap();
    let (w, _, pixels) = decode_png(&path);
    let at = |x: u32, y: u32| pixels[(y * w + x) as usize];
    // The title band: dark text is there, but none in the 8 outermost columns.
    let band = 0..40;
    let text = band
        .clone()
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .filter(|&(x, y)| at(x, y).iter().all(|&c| c < 100))
        .count();
    assert!(text > 200, "no title drawn ({text} dark pixels)");
    for y in band {
        for x in (0..8).chain(w - 8..w) {
            assert_eq!(
                at(x, y),
                [255, 255, 255],
                "title pixel at the edge ({x}, {y})"
            );
        }
    }
}

/// Regression: with five-digit x values (break forces up to 80000 N) the last tick label,
/// centred on the plot's right edge, ran past the image and was cut to "8000".
#[test]
fn the_last_tick_label_is_not_cut_off_at_the_right_edge() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("wide.png");
    let series = [Series::new(
        "joints",
        (1..=8)
            .map(|i| (i as f64 * 10_000.0, 200.0 / i as f64))
            .collect(),
    )];
    LinePlot::new(&series, "Bonds broken", "break force [N]", "bonds")
        .write_png(&path)
        .unwrap();
    let (w, h, pixels) = decode_png(&path);
    // Nothing is drawn in the 8 rightmost columns.
    for y in 0..h {
        for x in w - 8..w {
            assert_eq!(
                pixels[(y * w + x) as usize],
                [255, 255, 255],
                "pixel drawn at the right edge ({x}, {y})"
            );
        }
    }
}

/// With lines through every corner (an X), the automatic legend goes right of the plot:
/// the series colours appear there (the line samples) and the SVG still names them.
#[test]
fn a_crowded_plot_gets_its_legend_outside_the_plot_area() {
    let dir = tempfile::tempdir().unwrap();
    let rising: Vec<(f64, f64)> = (0..=20).map(|i| (i as f64, i as f64)).collect();
    let falling: Vec<(f64, f64)> = (0..=20).map(|i| (i as f64, 20.0 - i as f64)).collect();
    let series = [
        Series::new("rising line", rising),
        Series::new("falling line", falling),
    ];
    let png = dir.path().join("x.png");
    let svg = dir.path().join("x.svg");
    let plot = LinePlot::new(&series, "An X", "x", "y");
    assert_eq!(plot.legend, LegendPosition::Auto);
    plot.write_png(&png).unwrap();
    plot.write_svg(&svg).unwrap();

    let (w, h, pixels) = decode_png(&png);
    // The legend column: the last 150 pixels, where an inside legend would leave only
    // the plot's right edge (lines end there, at x = 20).
    let in_column = |colour: [u8; 3]| {
        (0..h).any(|y| (w - 150..w - 8).any(|x| pixels[(y * w + x) as usize] == colour))
    };
    assert!(
        in_column([0, 114, 178]),
        "no first-series sample right of the plot"
    );
    assert!(
        in_column([230, 159, 0]),
        "no second-series sample right of the plot"
    );
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.contains("rising line") && text.contains("falling line"));

    // Asked for explicitly, a corner legend leaves that column to the plot alone: no
    // series colour right of the lines' end there.
    let mut inside = LinePlot::new(&series, "An X", "x", "y");
    inside.legend = LegendPosition::UpperLeft;
    inside.write_png(&png).unwrap();
    let (w, h, pixels) = decode_png(&png);
    let any_colour = (0..h).any(|y| {
        (w - 40..w).any(|x| {
            let p = pixels[(y * w + x) as usize];
            p == [0, 114, 178] || p == [230, 159, 0]
        })
    });
    assert!(
        !any_colour,
        "series colour right of the plot with an inside legend"
    );
}
