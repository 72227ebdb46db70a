//! A GL call as automatic stereo receives it: what the preload library's
//! generated wrappers report of each command of the families of
//! [`crate::auto::entry_points`] ([`crate::interpose::draws`] passes them
//! on), and what the hook may give back for a call it answers itself.

use crate::auto::entry_points::Family;

/// What a generated wrapper reports of its command.
#[derive(Clone, Copy, Debug)]
pub struct Call<'a> {
    /// The command's family.
    pub family: Family,
    /// Its name.
    pub name: &'static str,
    /// Its arguments, in gl.xml's order, each as 64 bits: integers and
    /// enums widened (`as u64`), floats by their bits (`to_bits`),
    /// pointers by address.
    pub args: &'a [u64],
}

impl Call<'_> {
    /// Argument `i` as a GLenum / GLuint (0 when missing).
    pub fn u32(&self, i: usize) -> u32 {
        self.args.get(i).map_or(0, |&a| a as u32)
    }

    /// Argument `i` as a GLfloat.
    pub fn f32(&self, i: usize) -> f32 {
        self.args.get(i).map_or(0.0, |&a| f32::from_bits(a as u32))
    }

    /// Argument `i` as a pointer.
    pub fn ptr<T>(&self, i: usize) -> *mut T {
        self.args
            .get(i)
            .map_or(std::ptr::null_mut(), |&a| a as usize as *mut T)
    }
}

/// A return type of a generated wrapper: what the hook gives back for a
/// call it answers itself (glIsEnabled of GL_3DVISION_STEREO_NV).
pub trait Returned: Sized {
    /// The value from its 64 bits (the integer widened, as
    /// [`Call::args`] has arguments).
    fn from_bits(bits: u64) -> Self;
}

macro_rules! returned {
    ($($t:ty),*) => {$(
        impl Returned for $t {
            fn from_bits(bits: u64) -> Self {
                bits as $t
            }
        }
    )*};
}
returned!(u8, i8, u16, i16, u32, i32, u64, i64, usize, isize);

impl Returned for () {
    fn from_bits(_: u64) -> Self {}
}

impl Returned for f32 {
    fn from_bits(bits: u64) -> Self {
        f32::from_bits(bits as u32)
    }
}

impl Returned for f64 {
    fn from_bits(bits: u64) -> Self {
        f64::from_bits(bits)
    }
}

impl<T> Returned for *mut T {
    fn from_bits(bits: u64) -> Self {
        bits as usize as *mut T
    }
}

impl<T> Returned for *const T {
    fn from_bits(bits: u64) -> Self {
        bits as usize as *const T
    }
}
