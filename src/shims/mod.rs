//! Legacy and vendor APIs expressed through the library: each module holds
//! one API's state and rules, pure where it can be.

pub mod nv3dvision;
