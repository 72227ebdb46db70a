//! Link settings of libglstereo_preload.so.
fn main() {
    // Only the interposed GL/GLX names are exported: the glstereo code linked
    // in keeps its gls_ symbols local, so a program that also links
    // libglstereo.so binds those to the library, not to this copy.
    println!("cargo:rustc-cdylib-link-arg=-Wl,--exclude-libs,ALL");
    // Its own soname (the glstereo dependency's build script names libglstereo.so.0).
    println!("cargo:rustc-cdylib-link-arg=-Wl,-soname,libglstereo_preload.so");
}
