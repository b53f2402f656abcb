//! triad: rigid multibody models to FMI 2.0 Co-Simulation FMUs, integrated by an
//! energy–momentum consistent rotationless (director) scheme.
//!
//! Module map (dependencies point left): `math ← mechanics ← spec ← variables ← sim ← fmu ← {ffi, xml}
//! ← package ← main`, `spec ← urdf ← main` (URDF import produces a spec), and `spec ← viewer ←
//! {package, main}` (the 3-D replay reads results and geometry, never the integrator). `mechanics` knows nothing of FMI, XML, zip or serde; `ffi` is the only
//! module with `unsafe` code.
//!
//! The FMU library (what an FMU's binary holds) is everything but `package`, `urdf`, `viewer`
//! and `xml`: those, and the command line, need the `tools` feature (on by default). The FMU
//! runtime of every platform is built with `--no-default-features` (`scripts/platforms.sh`).
#![deny(unsafe_code)]
#![warn(missing_docs)]

pub mod ffi;
pub mod fmu;
#[cfg(feature = "tools")]
mod import;
pub mod math;
pub mod mechanics;
#[cfg(feature = "tools")]
pub mod mjcf;
#[cfg(feature = "tools")]
pub mod package;
#[cfg(feature = "tools")]
pub mod platforms;
pub mod sim;
pub mod spec;
#[cfg(feature = "tools")]
pub mod urdf;
pub mod variables;
#[cfg(feature = "tools")]
pub mod viewer;
#[cfg(feature = "tools")]
pub mod xml;
#[cfg(feature = "tools")]
pub mod xml3;
