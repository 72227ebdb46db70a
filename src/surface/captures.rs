//! Captures that do not stall a frame loop: the pixels are read back into a
//! recycled buffer on the calling thread and written to PNG (or a stereo
//! photo) by the surface's writer threads ([`crate::capture::queue`]).
//! And the stereo photos (MPO, JPS) of the eyes a viewer sees now.

use crate::sync::LockRecover;
use std::path::Path;
use std::sync::{Arc, MutexGuard};

use super::{CaptureImage, Surface};
use crate::capture::queue::{Capture, CaptureQueue, DEFAULT_CAPACITY};
use crate::capture::stereo_photo::{self, StereoPhotoFormat};
use crate::error::{Error, Result};
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
                    unsafe { super::read_eye(gl, st, s.buffer, out.pixels_mut()) }
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
        let guard = self.capture_queue()?;
        let queue = guard.as_ref().expect("made by capture_queue");
        let (ew, eh) = self.eye_size();
        let (w, h) = match which {
            CaptureImage::Composite => composite_size(self.effective_output(), ew, eh),
            _ => (ew, eh),
        };
        let mut img = queue.image(w, h)?;
        self.capture_into(which, &mut img)?;
        queue.submit(Capture::Png(img), path.to_path_buf())
    }

    /// The capture queue, started on first use.
    fn capture_queue(&self) -> Result<MutexGuard<'_, Option<CaptureQueue>>> {
        let mut guard = self.captures.recover();
        if guard.is_none() {
            *guard = Some(CaptureQueue::new(DEFAULT_CAPACITY)?);
        }
        Ok(guard)
    }

    /// The size of each eye once taken apart by the input framing.
    fn eye_size(&self) -> (u32, u32) {
        let (fw, fh) = self.size();
        self.framing().eye_size(fw, fh)
    }

    /// The JPEG quality of stereo photos, 1 … 100. Default:
    /// [`stereo_photo::DEFAULT_JPEG_QUALITY`].
    pub fn jpeg_quality(&self) -> u8 {
        self.state.recover().jpeg_quality
    }

    /// Sets the JPEG quality of stereo photos (1 … 100).
    ///
    /// # Errors
    /// [`Error::InvalidValue`] outside 1 … 100; nothing changes.
    pub fn set_jpeg_quality(&self, quality: u32) -> Result<()> {
        let q = stereo_photo::check_quality(quality)?;
        self.state.recover().jpeg_quality = q;
        Ok(())
    }

    /// Reads the two eyes a viewer sees now into `left` and `right` (as
    /// [`Surface::capture_into`]), exchanged when the surface swaps eyes:
    /// what a stereo photo holds.
    ///
    /// # Errors
    /// [`Error::InvalidOperation`] when both eyes come from the same pixels
    /// (a mono surface in the quad-buffer framing, or STR_TOP/STR_BOT on
    /// mono): that is one image, not a stereo pair. And as
    /// [`Surface::capture_into`].
    pub fn capture_pair_into(self: &Arc<Self>, left: &mut Image, right: &mut Image) -> Result<()> {
        let (framing, shape, (w, h), swap) = {
            let st = self.state.recover();
            (
                st.framing,
                st.fb.shape(),
                st.fb.size(),
                st.options.swap_eyes,
            )
        };
        let [ls, rs] = framing.sources(shape, w, h);
        if ls == rs {
            return Err(Error::invalid_operation(
                "this surface is mono: both eyes are the same image, and a mono MPO or JPS \
                 is not a stereo photo. Create the surface from a stereo configuration \
                 (GLX_STEREO), or set an input framing that holds two eyes \
                 (gls_surface_set_input), or save a PNG instead",
            ));
        }
        let whole = |s: &crate::framing::EyeSource| (s.x, s.y, s.width, s.height) == (0, 0, w, h);
        if whole(&ls) && whole(&rs) {
            // One read-back per eye, into the recycled buffers.
            self.capture_into(CaptureImage::Left, left)?;
            self.capture_into(CaptureImage::Right, right)?;
        } else {
            // Eyes taken apart from one frame: read it once for both.
            (*left, *right) = self.eye_images()?;
        }
        if swap {
            std::mem::swap(left, right);
        }
        Ok(())
    }

    /// Writes the two eyes a viewer sees now as a stereo photo (MPO or
    /// JPS, at [`Surface::jpeg_quality`]) to `path`, atomically.
    ///
    /// # Errors
    /// As [`Surface::capture_pair_into`]; [`Error::Io`] naming the path
    /// when the file cannot be written (no file is left).
    pub fn save_stereo_photo(
        self: &Arc<Self>,
        format: StereoPhotoFormat,
        path: &Path,
    ) -> Result<()> {
        let (mut left, mut right) = (Image::new(1, 1), Image::new(1, 1));
        self.capture_pair_into(&mut left, &mut right)?;
        stereo_photo::write(format, &left, &right, self.jpeg_quality(), path)
    }

    /// [`Surface::save_stereo_photo`] through the capture queue: returns
    /// once the pixels are read (see [`Surface::queue_png`]).
    ///
    /// # Errors
    /// As [`Surface::capture_pair_into`]; and the first earlier queued
    /// capture that failed to be written and was not yet reported (this
    /// capture is queued all the same).
    pub fn queue_stereo_photo(
        self: &Arc<Self>,
        format: StereoPhotoFormat,
        path: &Path,
    ) -> Result<()> {
        let guard = self.capture_queue()?;
        let queue = guard.as_ref().expect("made by capture_queue");
        let (w, h) = self.eye_size();
        let mut left = queue.image(w, h)?;
        let mut right = queue.image(w, h)?;
        self.capture_pair_into(&mut left, &mut right)?;
        let capture = Capture::StereoPhoto {
            format,
            quality: self.jpeg_quality(),
            left,
            right,
        };
        queue.submit(capture, path.to_path_buf())
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
