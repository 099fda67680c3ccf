//! Plot files exist; the PNG decodes at the requested size and shows the lines in their
//! colours; the SVG is well-formed XML carrying the title, the axis labels and the
//! legend.
#![allow(clippy::unwrap_used)]

use std::collections::HashSet;
use std::path::Path;

use shatter_report::ReportError;
use shatter_report::plot::{LinePlot, Series, plot_lines};

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
