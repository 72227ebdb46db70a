//! The period APIs of the seed systems, emulated on glstereo surfaces: HP
//! Starbase's `gescape(STEREO)` (seed 000 §9) and SGI IRIS GL's stereo
//! subset (seed 002). Programs reach them through the compat headers
//! `include/glstereo/starbase.h` and `include/glstereo/irisgl.h`, which map
//! the legacy names onto the `gls_starbase_*` / `gls_irisgl_*` exports.
//!
//! The pure parts (opcode and constant decoding, descriptor tables,
//! buffer-selection rules, viewport and matrix arithmetic) are unit-tested
//! here; the parts that touch a surface go through [`crate::surface`].

pub mod descriptors;
pub mod irisgl;
pub mod screen;
pub mod starbase;
