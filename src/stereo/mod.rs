//! The emulated quad buffer: a default framebuffer with left and right,
//! front and back colour buffers, built from textures on any GL 3.0 driver.
//!
//! - [`buffers`]: the pure GL rules for selecting buffers;
//! - [`emulated`]: the GL objects and the draw/read state.

pub mod buffers;
pub mod emulated;
pub mod eye_memory;
pub mod outputs;
