//! triad: rigid multibody models to FMI 2.0 Co-Simulation FMUs, integrated by an
//! energy–momentum consistent rotationless (director) scheme.
//!
//! Module map (dependencies point left): `math ← mechanics ← spec ← variables ← sim ← fmu ← {ffi, xml}
//! ← package ← main`, `spec ← urdf ← main` (URDF import produces a spec), and `spec ← viewer ←
//! {package, main}` (the 3-D replay reads results and geometry, never the integrator). `mechanics` knows nothing of FMI, XML, zip or serde; `ffi` is the only
//! module with `unsafe` code.
#![deny(unsafe_code)]
#![warn(missing_docs)]

pub mod ffi;
pub mod fmu;
pub mod math;
pub mod mechanics;
pub mod package;
pub mod sim;
pub mod spec;
pub mod urdf;
pub mod variables;
pub mod viewer;
pub mod xml;
