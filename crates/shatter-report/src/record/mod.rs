//! Recording a simulation run: per-step statistics (`--record run.csv`) and fragment
//! poses for an animated export (`--export run.glb`).

mod recorder;

pub use recorder::{RunRecorder, STATS_HEADER, StepStats};
