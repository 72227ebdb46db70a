//! Automatic stereo of unmodified mono programs (issue 23): design in
//! progress; see the submodules.

pub mod entry_points;
pub mod fixed;
pub mod glsl;
pub mod link;
pub mod target;
pub mod vertex;

#[cfg(test)]
mod testgl;

/// Declares a table of GL entry points loaded by name through a
/// GetProcAddress, as [`crate::stereo::outputs::LinkFns`] is: a struct of
/// `pub(crate)` function pointers and an `unsafe fn load` that fails
/// (None) when one is missing.
macro_rules! gl_fns {
    ($(#[$meta:meta])* $vis:vis struct $name:ident {
        $( $field:ident = $sym:literal: fn($($ty:ty),*) $(-> $ret:ty)?; )*
    }) => {
        $(#[$meta])*
        #[allow(non_snake_case)]
        $vis struct $name {
            $( pub(crate) $field: unsafe extern "system" fn($($ty),*) $(-> $ret)?, )*
        }

        impl $name {
            /// Looks every function up through `get`; None when one is missing.
            ///
            /// # Safety
            /// `get` must return the named GL function (its Khronos
            /// signature) or NULL.
            #[allow(dead_code)]
            pub unsafe fn load(get: impl Fn(&std::ffi::CStr) -> *const std::ffi::c_void) -> Option<$name> {
                Some($name {
                    $( $field: {
                        let p = get($sym);
                        if p.is_null() {
                            return None;
                        }
                        // SAFETY: the named function, with its Khronos signature.
                        unsafe { std::mem::transmute::<*const std::ffi::c_void, unsafe extern "system" fn($($ty),*) $(-> $ret)?>(p) }
                    }, )*
                })
            }
        }
    };
}
pub(crate) use gl_fns;
