//! The panels: state, validation and drawing.

pub mod fields;
pub mod fonts;
pub mod forms;
pub mod panels;
pub mod plugin;
pub mod state;

pub use plugin::{FrameRate, PendingCommands, UiPlugin};
pub use state::{ClickOutcome, UiState};
