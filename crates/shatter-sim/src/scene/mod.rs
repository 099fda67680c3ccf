//! Scenes as TOML files: world settings, breakable objects, timed projectiles and
//! explosions. The schema is documented in `docs/scene-format.md`.

pub mod budget;
mod checks;
mod entries;
pub mod file;
pub mod load;
mod save;
pub mod values;

pub use budget::{ObjectEstimate, SceneEstimate};
pub use checks::line_col;
pub use file::SceneFile;
pub use load::Scene;
