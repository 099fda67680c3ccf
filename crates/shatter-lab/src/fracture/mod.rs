//! Fracture requests: validated configurations ([`FractureConfig`]), their resource
//! estimates, loading the mesh they name, running them, and the `--json` report.

mod report;
mod request;
mod run;
mod source;

pub use report::{BondEntry, EstimateReport, FractureReport};
pub use request::{FractureConfig, MeshSource, check_fracture, fracture_estimate};
pub use run::{fracture, fracture_timed};
pub use source::{
    builtin_shape, load_model, load_source, repair, scaled, scaled_model, validate_model,
    validate_solid,
};
