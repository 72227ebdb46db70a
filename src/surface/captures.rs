//! Captures that do not stall a frame loop: the pixels are read back into a
//! recycled buffer on the calling thread and written to PNG by the
//! surface's writer thread ([`crate::capture::queue`]).

use crate::sync::LockRecover;
use std::path::Path;
use std::sync::Arc;

use super::{CaptureImage, Surface};
use crate::capture::queue::{DEFAULT_CAPACITY, PngQueue};
use crate::error::Result;
use crate::image::Image;
use crate::output::layout::composite_size;

impl Surface {
    /// Reads one of the images a viewer sees now into `out` (resized when
    /// needed, its buffer reused otherwise): what
    /// [`Surface::save_png`] writes, alpha 255.
    pub fn capture_into(self: &Arc<Self>, which: CaptureImage, out: &mut Image) -> Result<()> {
        let (framing, shape, (w, h)) = {
            let st = self.state.recover();
            (st.framing, st.fb.shape(), st.fb.size())
        };
        let [ls, rs] = framing.sources(shape, w, h);
        let source = match which {
            CaptureImage::Left => Some(ls),
            CaptureImage::Right => Some(rs),
            CaptureImage::Composite => None,
        };
        match source {
            // An eye that is a whole buffer: one read-back into `out`.
            Some(s) if (s.x, s.y, s.width, s.height) == (0, 0, w, h) => {
                out.resize(w, h, "image")?;
                self.with_compositor(|gl, st| {
                    // SAFETY: the compositor context is current; `out` holds w×h×4 bytes.
                    unsafe { st.fb.read_pixels(gl, s.buffer, out.pixels_mut()) }
                })?;
            }
            Some(_) => {
                let (l, r) = self.eye_images()?;
                *out = if which == CaptureImage::Left { l } else { r };
            }
            None => {
                let mode = self.effective_output();
                // The eyes into the compositor's reused buffers, the
                // composite into `out` (see GlCompositor::capture_into).
                let done = self.with_compositor(|gl, st| {
                    let job = super::gl_job(st, mode);
                    // SAFETY: the compositor context is current; the job's
                    // textures are this surface's.
                    unsafe { st.compositor.capture_into(gl, &job, out) }
                })?;
                if !done {
                    *out = self.composite_image()?;
                }
            }
        }
        out.make_opaque();
        Ok(())
    }

    /// Queues a PNG capture of one of the images a viewer sees now: returns
    /// once the pixels are read, and the surface's writer thread writes the
    /// file (atomically, as [`Surface::save_png`]). At most
    /// [`DEFAULT_CAPACITY`] captures wait; beyond that this call waits for
    /// the oldest to be written.
    ///
    /// # Errors
    /// As [`Surface::capture_into`]; and the first earlier queued capture
    /// that failed to be written and was not yet reported (this capture is
    /// queued all the same).
    pub fn queue_png(self: &Arc<Self>, which: CaptureImage, path: &Path) -> Result<()> {
        let mut guard = self.captures.recover();
        if guard.is_none() {
            *guard = Some(PngQueue::new(DEFAULT_CAPACITY)?);
        }
        let queue = guard.as_ref().expect("just made");
        let (fw, fh) = self.size();
        let (ew, eh) = self.framing().eye_size(fw, fh);
        let (w, h) = match which {
            CaptureImage::Composite => composite_size(self.effective_output(), ew, eh),
            _ => (ew, eh),
        };
        let mut img = queue.image(w, h)?;
        self.capture_into(which, &mut img)?;
        queue.submit(img, path.to_path_buf())
    }

    /// Waits until every queued capture is written.
    ///
    /// # Errors
    /// The first queued capture that failed and was not yet reported
    /// ([`crate::error::Error::Io`], naming the path and the reason).
    pub fn finish_captures(&self) -> Result<()> {
        match self.captures.recover().as_ref() {
            Some(q) => q.flush(),
            None => Ok(()),
        }
    }
}
