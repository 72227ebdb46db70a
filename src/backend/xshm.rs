//! Showing CPU pixels in an X window through MIT-SHM (`XShmPutImage`).
//!
//! With a software renderer, glXSwapBuffers itself copies the back buffer
//! into the window with XShmPutImage; writing the composite into the back
//! buffer first costs a full-screen GL pass (≈ 2–4 ms at 1280x1024 on
//! llvmpipe: the window's BGRX format makes every blit a converting draw),
//! while putting the composite straight from memory costs one conversion
//! pass on the CPU (≈ 0.25 ms) and an asynchronous request the server
//! serves on its own core. This is how VirtualGL shows frames too.
//!
//! One shared-memory XImage per window, made on first use at the window's
//! size and remade when the size changes. Before the segment is rewritten,
//! XSync makes sure the server has finished reading the previous frame.
//! Supported: 32-bit LSB-first TrueColor images with 8-bit R, G, B masks
//! in either order (what Xvfb and every local X server give 24-bit
//! visuals); anything else, a remote server or a missing extension leaves
//! the caller on the GL path.

use std::ffi::c_int;
use std::sync::OnceLock;

use x11_dl::xlib::{self, Xlib};
use x11_dl::xshm::{XShmSegmentInfo, Xext};

use super::{PixelLayout as Layout, PixelTarget};
use crate::error::Result;

/// libXext, loaded once for the process and never unloaded: it keeps a
/// record of each display's MIT-SHM extension in its own static data, which
/// must outlive every display (unloading it would strand those records).
fn xext() -> Option<&'static Xext> {
    static XEXT: OnceLock<Option<Xext>> = OnceLock::new();
    XEXT.get_or_init(|| Xext::open().ok()).as_ref()
}

/// The state of the connection an image is destroyed on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Connection {
    /// Working: the segment is detached and the GC freed.
    Open,
    /// Inside XCloseDisplay's extension hooks: only core requests (the GC)
    /// are sent. The MIT-SHM extension's own per-display record may be gone
    /// already, and a call through it would make a new one that outlives
    /// the display (a later display at the same address would inherit it);
    /// the server detaches the segment when the client disconnects.
    Closing,
    /// Gone: only the local mapping is released.
    Lost,
}

/// A window's MIT-SHM image: made on first use, remade when the window's
/// size changes, given up for good when MIT-SHM cannot serve the window.
#[derive(Default)]
pub(crate) enum ShmSlot {
    /// Not tried yet (or released).
    #[default]
    Untried,
    /// MIT-SHM cannot serve this window: its frames take the GL path.
    Unsupported,
    /// An attached image.
    Ready(ShmImage),
}

impl ShmSlot {
    /// Whether MIT-SHM was found unable to serve the window.
    pub(crate) fn unsupported(&self) -> bool {
        matches!(self, ShmSlot::Unsupported)
    }

    /// Lets `fill` write a frame of `size` into the window's image and
    /// sends it through `send` (which must call the function it is given
    /// once: the put; it may wrap it, e.g. in an X error trap); the image is
    /// made with `make` first when there is none of that size (None from
    /// `make`: unsupported from now on). Ok(false): nothing shown, MIT-SHM
    /// cannot serve the window.
    ///
    /// # Safety
    /// `display` is the open connection the image is (or `make` makes it)
    /// on, `window` the window it was made for.
    pub(crate) unsafe fn put(
        &mut self,
        xl: &Xlib,
        (display, window): (*mut xlib::Display, xlib::Window),
        size: (u32, u32),
        make: impl FnOnce() -> Option<ShmImage>,
        fill: &mut dyn FnMut(PixelTarget<'_>) -> Result<()>,
        send: &mut dyn FnMut(&mut dyn FnMut()),
    ) -> Result<bool> {
        if matches!(self, ShmSlot::Ready(img) if img.size() != size) {
            // SAFETY: made on this open connection (contract).
            unsafe { self.release(xl, display, Connection::Open) };
        }
        if matches!(self, ShmSlot::Untried) {
            *self = make().map_or(ShmSlot::Unsupported, ShmSlot::Ready);
        }
        let ShmSlot::Ready(img) = self else {
            return Ok(false);
        };
        // SAFETY: made on this open connection for this window (contract).
        unsafe { img.put_with(xl, display, window, fill, send)? };
        Ok(true)
    }

    /// Frees the image, if any (the slot is untried again); what is sent
    /// to the server depends on `connection`.
    ///
    /// # Safety
    /// As [`ShmImage::destroy`].
    pub(crate) unsafe fn release(
        &mut self,
        xl: &Xlib,
        display: *mut xlib::Display,
        connection: Connection,
    ) {
        if let ShmSlot::Ready(img) = std::mem::take(self) {
            // SAFETY: contract.
            unsafe { img.destroy(xl, display, connection) };
        }
    }
}

/// A shared-memory XImage attached to the server.
pub(crate) struct ShmImage {
    xext: &'static Xext,
    /// Boxed: the XImage keeps a pointer to it (`obdata`).
    info: Box<XShmSegmentInfo>,
    image: *mut xlib::XImage,
    gc: xlib::GC,
    layout: Layout,
    width: u32,
    height: u32,
    /// The request number of the last put: the segment may be rewritten
    /// once the server is known to have processed it (any XSync since, the
    /// caller's own included, tells).
    put_serial: Option<std::ffi::c_ulong>,
}

// SAFETY: the image is plain memory plus X resource ids; its owner uses it
// with its connection from one thread at a time (under a lock).
unsafe impl Send for ShmImage {}

impl ShmImage {
    /// Makes and attaches an image of `(width, height)` for `visual` of
    /// `depth`. `trap` runs X calls with protocol errors trapped and returns
    /// the first error code (0: none). None when MIT-SHM is missing or
    /// unusable or the image format is not supported.
    ///
    /// # Safety
    /// `display` is a live connection and `visual`/`depth` one of its visuals.
    pub(crate) unsafe fn create(
        xl: &Xlib,
        display: *mut xlib::Display,
        window: xlib::Window,
        visual: *mut xlib::Visual,
        depth: c_int,
        (width, height): (u32, u32),
        trap: &dyn Fn(&mut dyn FnMut()) -> i32,
    ) -> Option<ShmImage> {
        let xext = xext()?;
        // SAFETY: live display (contract); every pointer below is checked
        // before use and released on every failure path.
        unsafe {
            // libXext makes its MIT-SHM extension record on the first query,
            // unlocked: two threads querying at once each made one, and the
            // loser's was leaked (LeakSanitizer, tests/c/glx_threads.c).
            static QUERY: std::sync::Mutex<()> = std::sync::Mutex::new(());
            let known = {
                let _one_at_a_time = QUERY.lock().unwrap_or_else(|e| e.into_inner());
                (xext.XShmQueryExtension)(display)
            };
            if known == 0 {
                return None;
            }
            let mut info: Box<XShmSegmentInfo> = Box::new(std::mem::zeroed());
            let image = (xext.XShmCreateImage)(
                display,
                visual,
                depth as u32,
                xlib::ZPixmap,
                std::ptr::null_mut(),
                &mut *info,
                width,
                height,
            );
            if image.is_null() {
                return None;
            }
            let im = &*image;
            let layout = match (
                im.bits_per_pixel,
                im.byte_order,
                im.red_mask,
                im.green_mask,
                im.blue_mask,
            ) {
                (32, xlib::LSBFirst, 0xff0000, 0xff00, 0xff) => Some(Layout::Bgrx),
                (32, xlib::LSBFirst, 0xff, 0xff00, 0xff0000) => Some(Layout::Rgbx),
                _ => None,
            };
            let size = im.bytes_per_line as usize * im.height as usize;
            let Some(layout) = layout.filter(|_| im.bytes_per_line as usize >= width as usize * 4)
            else {
                ((*image).funcs.destroy_image?)(image);
                return None;
            };
            info.shmid = libc::shmget(libc::IPC_PRIVATE, size, libc::IPC_CREAT | 0o600);
            if info.shmid < 0 {
                ((*image).funcs.destroy_image?)(image);
                return None;
            }
            let addr = libc::shmat(info.shmid, std::ptr::null(), 0);
            if addr as isize == -1 {
                libc::shmctl(info.shmid, libc::IPC_RMID, std::ptr::null_mut());
                ((*image).funcs.destroy_image?)(image);
                return None;
            }
            info.shmaddr = addr.cast();
            info.readOnly = xlib::False;
            (*image).data = info.shmaddr;
            let mut attached = 0;
            let err = trap(&mut || attached = (xext.XShmAttach)(display, &mut *info));
            // The segment goes away once both sides detach (no leak on a crash).
            libc::shmctl(info.shmid, libc::IPC_RMID, std::ptr::null_mut());
            if err != 0 || attached == 0 {
                (*image).data = std::ptr::null_mut();
                ((*image).funcs.destroy_image?)(image);
                libc::shmdt(addr);
                return None;
            }
            let gc = (xl.XCreateGC)(display, window, 0, std::ptr::null_mut());
            Some(ShmImage {
                xext,
                info,
                image,
                gc,
                layout,
                width,
                height,
                put_serial: None,
            })
        }
    }

    /// The image's size.
    pub(crate) fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    /// Lets `fill` write a frame into the segment and sends it to `window`
    /// (unless `fill` fails) through `send`, as [`ShmSlot::put`] says.
    ///
    /// # Safety
    /// `display` is the live connection the image was made on.
    pub(crate) unsafe fn put_with(
        &mut self,
        xl: &Xlib,
        display: *mut xlib::Display,
        window: xlib::Window,
        fill: &mut dyn FnMut(PixelTarget<'_>) -> Result<()>,
        send: &mut dyn FnMut(&mut dyn FnMut()),
    ) -> Result<()> {
        // SAFETY: live display (contract); the segment holds
        // bytes_per_line × height bytes, mapped until drop; the server only
        // reads it between a put and the reply that shows it processed it.
        unsafe {
            if self
                .put_serial
                .is_some_and(|put| (xl.XLastKnownRequestProcessed)(display) < put)
            {
                crate::profile::span(crate::profile::Stage::XSync, || {
                    (xl.XSync)(display, xlib::False)
                });
            }
            let stride = (*self.image).bytes_per_line as usize;
            let data = std::slice::from_raw_parts_mut(
                self.info.shmaddr.cast::<u8>(),
                stride * self.height as usize,
            );
            fill(PixelTarget {
                data,
                stride,
                size: (self.width, self.height),
                layout: self.layout,
            })?;
            self.put_serial = Some((xl.XNextRequest)(display));
            send(&mut || {
                crate::profile::span(crate::profile::Stage::Put, || {
                    (self.xext.XShmPutImage)(
                        display,
                        window,
                        self.gc,
                        self.image,
                        0,
                        0,
                        0,
                        0,
                        self.width,
                        self.height,
                        xlib::False,
                    );
                    (xl.XFlush)(display);
                })
            });
        }
        Ok(())
    }

    /// Detaches and frees the image; what is sent to the server depends on
    /// the state of the connection.
    ///
    /// # Safety
    /// `display` is the connection the image was made on, in the state
    /// `connection` says.
    pub(crate) unsafe fn destroy(
        mut self,
        xl: &Xlib,
        display: *mut xlib::Display,
        connection: Connection,
    ) {
        // SAFETY: contract; the image's data pointer is cleared before
        // XDestroyImage so that Xlib does not free() the shared memory.
        unsafe {
            match connection {
                Connection::Open => {
                    (self.xext.XShmDetach)(display, &mut *self.info);
                    (xl.XFreeGC)(display, self.gc);
                    (xl.XSync)(display, xlib::False);
                }
                Connection::Closing => {
                    (xl.XFreeGC)(display, self.gc);
                }
                Connection::Lost => {}
            }
            (*self.image).data = std::ptr::null_mut();
            if let Some(destroy) = (*self.image).funcs.destroy_image {
                destroy(self.image);
            }
            libc::shmdt(self.info.shmaddr.cast());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::convert_row;
    use super::*;

    #[test]
    fn rows_convert_to_the_visuals_byte_order_with_an_opaque_x_byte() {
        let src = [10u8, 20, 30, 0, 200, 100, 50, 7];
        let mut dst = [0u8; 8];
        convert_row(&src, &mut dst, Layout::Bgrx);
        assert_eq!(dst, [30, 20, 10, 255, 50, 100, 200, 255]);
        convert_row(&src, &mut dst, Layout::Rgbx);
        assert_eq!(dst, [10, 20, 30, 255, 200, 100, 50, 255]);
        // Unaligned rows take the byte path, with the same result.
        let mut wide = [0u8; 9];
        convert_row(&src, &mut wide[1..], Layout::Bgrx);
        assert_eq!(wide[1..], [30, 20, 10, 255, 50, 100, 200, 255]);
    }
}
