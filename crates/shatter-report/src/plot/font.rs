//! The font every plot is drawn with, registered once with plotters.
//!
//! plotters' default text rendering asks the system's font library (fontconfig) for a
//! font; we use its `ab_glyph` renderer instead and give it DejaVu Sans, shipped in this
//! crate (`assets/fonts/`, Bitstream Vera licence, see `LICENSE-DejaVu.txt`), so plots
//! look the same on every machine and need no system library.

use std::sync::OnceLock;

use plotters::style::{FontStyle, register_font};

/// The family name plots ask for.
pub(crate) const FAMILY: &str = "sans-serif";

static DEJAVU_SANS: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");

/// Registers the font (once per process). Fails only if the shipped file is not a font.
pub(crate) fn ensure_registered() -> Result<(), String> {
    static REGISTERED: OnceLock<Result<(), String>> = OnceLock::new();
    REGISTERED
        .get_or_init(|| {
            for style in [FontStyle::Normal, FontStyle::Bold] {
                register_font(FAMILY, style, DEJAVU_SANS)
                    .map_err(|_| "the shipped DejaVuSans.ttf is not a valid font".to_string())?;
            }
            Ok(())
        })
        .clone()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_shipped_font_registers() {
        assert_eq!(ensure_registered(), Ok(()));
    }
}
