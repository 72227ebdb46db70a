//! Input framings: how a program delivers its two eyes to the library.
//!
//! - [`auto`]: automatic stereo of a mono renderer (NVIDIA 3D Vision): one
//!   mono frame, drawn once per eye with a per-eye projection.

pub mod auto;
