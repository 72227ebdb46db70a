//! The period and vendor APIs of the seed systems, emulated on glstereo
//! surfaces: HP Starbase's `gescape(STEREO)` (seed 000 §9), SGI IRIS GL's
//! stereo subset (seed 002) and NVIDIA's 3D Vision settings (seed 004).
//! Programs reach them through the compat headers in `include/glstereo/`,
//! which map the legacy names onto the `gls_*` exports.
//!
//! The pure parts (opcode and constant decoding, descriptor tables,
//! buffer-selection rules, parameter validation) are unit-tested here; the
//! parts that touch a surface go through [`crate::surface`].

pub mod descriptors;
pub mod irisgl;
pub mod nv3dvision;
pub mod screen;
pub mod starbase;
