//! The panels' typefaces: egui's own Ubuntu Light (text) and Hack (figures), without the
//! two emoji fonts egui's `default_fonts` adds. The panels draw no emoji, and those fonts
//! were 0.7 MB of the web page's download.

use std::sync::Arc;

use bevy_egui::egui::{FontData, FontDefinitions, FontFamily};

/// Ubuntu Light for proportional text and Hack for monospace, each falling back on the
/// other (Ubuntu Light has the maths signs Hack lacks).
///
/// ```
/// use bevy_egui::egui::FontFamily;
/// let fonts = shatter_app::ui::fonts::panel_fonts();
/// assert_eq!(fonts.families[&FontFamily::Proportional][0], "Ubuntu-Light");
/// assert_eq!(fonts.families[&FontFamily::Monospace][0], "Hack");
/// ```
pub fn panel_fonts() -> FontDefinitions {
    let mut fonts = FontDefinitions::empty();
    fonts.font_data.insert(
        "Ubuntu-Light".to_owned(),
        Arc::new(FontData::from_static(epaint_default_fonts::UBUNTU_LIGHT)),
    );
    fonts.font_data.insert(
        "Hack".to_owned(),
        Arc::new(FontData::from_static(epaint_default_fonts::HACK_REGULAR)),
    );
    fonts.families.insert(
        FontFamily::Proportional,
        vec!["Ubuntu-Light".to_owned(), "Hack".to_owned()],
    );
    fonts.families.insert(
        FontFamily::Monospace,
        vec!["Hack".to_owned(), "Ubuntu-Light".to_owned()],
    );
    fonts
}
