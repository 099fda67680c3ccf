//! Mesh file import and export.
