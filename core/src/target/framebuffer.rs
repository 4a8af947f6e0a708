//! Framebuffers over caller memory: a whole frame, or one band of it.

use super::layout::{BufferError, Layout};
use super::{Rect, Target};

/// A frame of `C` pixels in a caller-supplied slice, row-major with a
/// stride (elements from one row's start to the next): the [`Band`] that
/// holds frame rows `0..height`, with the frame's names for its size.
///
/// # Guarantees
///
/// The shape is validated once by [`Framebuffer::new`]. After that **no
/// method panics and none writes outside the slice**, whatever its
/// arguments: spans and pixels outside `0..width` × `0..height` are
/// clipped or ignored, and elements between `width` and `stride` (padding)
/// are never written.
///
/// ```
/// use sightline::target::{BufferError, Framebuffer, Target};
///
/// let mut pixels = [b'.'; 4 * 3];
/// let mut fb = Framebuffer::new(&mut pixels, 4, 3, 4).unwrap();
/// fb.fill_solid(1, -1, 3, b'#'); // clipped at the left edge
/// fb.fill_solid(7, 0, 4, b'!'); // below the frame: ignored
/// assert_eq!(&pixels, b"....##......");
/// // A slice too short for the shape is refused up front.
/// let mut small = [0u16; 5];
/// assert_eq!(
///     Framebuffer::new(&mut small, 4, 3, 4).err(),
///     Some(BufferError::TooShort { needed: 12, len: 5 })
/// );
/// ```
#[derive(Debug)]
pub struct Framebuffer<'a, C>(Band<'a, C>);

impl<'a, C: Copy> Framebuffer<'a, C> {
    /// Wraps `buf` as `width`×`height` pixels with `stride` elements per
    /// row.
    ///
    /// # Errors
    /// [`BufferError::StrideTooSmall`] if `stride < width`;
    /// [`BufferError::TooShort`] if `buf.len() < stride·(height−1) + width`;
    /// [`BufferError::Overflow`] if that size overflows `usize`.
    pub fn new(
        buf: &'a mut [C],
        width: u16,
        height: u16,
        stride: usize,
    ) -> Result<Self, BufferError> {
        // A frame is the band that holds rows 0..height.
        Band::new(buf, width, height, stride, 0).map(Self)
    }

    /// Width in pixels.
    #[must_use]
    pub fn width(&self) -> u16 {
        self.0.width()
    }

    /// Height in pixels.
    #[must_use]
    pub fn height(&self) -> u16 {
        self.0.rows()
    }

    /// The pixel at (x, y), or `None` outside the frame.
    #[must_use]
    pub fn pixel(&self, x: i32, y: i32) -> Option<C> {
        self.0.pixel(x, y)
    }

    /// Sets every pixel (not the stride padding) to `color`.
    pub fn clear(&mut self, color: C) {
        self.0.clear(color);
    }

    /// The underlying slice.
    #[must_use]
    pub fn as_slice(&self) -> &[C] {
        self.0.as_slice()
    }
}

impl<C: Copy> Target for Framebuffer<'_, C> {
    type Color = C;

    #[inline]
    fn clip_rect(&self) -> Rect {
        self.0.clip_rect()
    }

    #[inline]
    fn fill_solid(&mut self, y: i32, x: i32, len: u32, color: C) {
        self.0.fill_solid(y, x, len, color);
    }

    #[inline]
    fn fill_with<F: FnMut() -> C>(&mut self, y: i32, x: i32, len: u32, colors: F) {
        self.0.fill_with(y, x, len, colors);
    }

    #[inline(always)]
    fn span_mut(&mut self, y: i32, x: i32, len: u32) -> Option<&mut [C]> {
        self.0.span_mut(y, x, len)
    }

    fn clear(&mut self, color: C) {
        self.0.clear(color);
    }
}

/// Rows `y0..y0+rows` of a taller frame, in a buffer that holds only those
/// rows: render a 320×240 frame as fifteen 320×16 bands, pushing each to
/// the display before rendering the next.
///
/// Coordinates given to [`Target`] methods are *frame* coordinates; the
/// band keeps the rows it holds and clips everything else, so the scan
/// converter produces exactly the pixels a full [`Framebuffer`] would have
/// in those rows.
///
/// # Guarantees
///
/// As for [`Framebuffer`]: validated once by [`Band::new`]; no method
/// panics or writes outside the slice afterwards, including after
/// [`Band::move_to`].
///
/// ```
/// use sightline::target::{Band, Target};
///
/// // A 4×6 frame drawn two rows at a time through a 4×2 buffer.
/// let mut buf = [b'.'; 4 * 2];
/// let mut frame = Vec::new();
/// for y0 in (0..6).step_by(2) {
///     let mut band = Band::new(&mut buf, 4, 2, 4, y0).unwrap();
///     band.clear(b'.');
///     // Draw the whole frame's spans; the band keeps its own rows.
///     for y in 0..6 {
///         band.fill_solid(y, y % 4, 1, b'#');
///     }
///     frame.extend_from_slice(band.as_slice()); // here: send it to the display
/// }
/// let rows: Vec<&[u8]> = frame.chunks(4).collect();
/// assert_eq!(rows, [b"#...", b".#..", b"..#.", b"...#", b"#...", b".#.."]);
/// ```
#[derive(Debug)]
pub struct Band<'a, C> {
    // The depth buffer's hot loops read these directly.
    pub(crate) buf: &'a mut [C],
    pub(crate) layout: Layout,
}

impl<'a, C: Copy> Band<'a, C> {
    /// Wraps `buf` as `rows` rows of `width` pixels, `stride` apart,
    /// holding frame rows `y0..y0+rows`.
    ///
    /// # Errors
    /// As [`Framebuffer::new`]; also [`BufferError::Overflow`] if
    /// `y0 + rows` overflows `i32`.
    pub fn new(
        buf: &'a mut [C],
        width: u16,
        rows: u16,
        stride: usize,
        y0: i32,
    ) -> Result<Self, BufferError> {
        let layout = Layout::new(buf.len(), width, rows, stride, y0)?;
        Ok(Self { buf, layout })
    }

    /// Moves the band to hold frame rows `y0..y0+rows` (the contents are
    /// kept; clear them if needed).
    ///
    /// # Errors
    /// [`BufferError::Overflow`] if `y0 + rows` overflows `i32`; the band
    /// is then unchanged.
    pub fn move_to(&mut self, y0: i32) -> Result<(), BufferError> {
        self.layout = Layout::new(
            self.buf.len(),
            self.layout.width,
            self.layout.height,
            self.layout.stride,
            y0,
        )?;
        Ok(())
    }

    /// Width in pixels.
    #[must_use]
    pub fn width(&self) -> u16 {
        self.layout.width
    }

    /// First frame row held.
    #[must_use]
    pub fn y0(&self) -> i32 {
        self.layout.y0
    }

    /// Number of rows held.
    #[must_use]
    pub fn rows(&self) -> u16 {
        self.layout.height
    }

    /// The pixel at frame position (x, y), or `None` outside the band.
    #[must_use]
    pub fn pixel(&self, x: i32, y: i32) -> Option<C> {
        self.layout
            .index(x, y)
            .and_then(|i| self.buf.get(i).copied())
    }

    /// Sets every pixel of the band to `color` (one pass over the slice
    /// when `stride == width`).
    pub fn clear(&mut self, color: C) {
        self.for_each_run(|run| fill_unrolled(run, color));
    }

    /// Calls `f` on the band's pixels as runs that skip the stride
    /// padding: the whole `width·height` prefix of the slice at once when
    /// the rows lie end to end (`stride == width`), else each row. The
    /// one walk for both clears ([`Self::clear`] and the depth buffer's).
    pub(crate) fn for_each_run(&mut self, mut f: impl FnMut(&mut [C])) {
        let l = self.layout;
        if l.stride == l.width as usize {
            // `Layout::new` checked that the slice holds the rows.
            if let Some(all) = self.buf.get_mut(..l.width as usize * l.height as usize) {
                f(all);
            }
            return;
        }
        for row in 0..l.height as i32 {
            if let Some((_, r)) = l.span(l.y0 + row, 0, l.width as u32) {
                if let Some(run) = self.buf.get_mut(r) {
                    f(run);
                }
            }
        }
    }

    /// The underlying slice (row `y0` first).
    #[must_use]
    pub fn as_slice(&self) -> &[C] {
        self.buf
    }

    /// The part of span `x..x+len` of frame row `y` inside the band:
    /// `(skip, pixels)` where `skip` counts the leading pixels clipped
    /// away; `None` if nothing is inside.
    #[inline]
    pub(crate) fn clipped_span_mut(&mut self, y: i32, x: i32, len: u32) -> Option<(u32, &mut [C])> {
        let (skip, r) = self.layout.span(y, x, len)?;
        // `get_mut` rather than indexing: the range is in bounds by the
        // validation in `Layout::new`, and this keeps the no-panic promise
        // checkable locally.
        self.buf.get_mut(r).map(|row| (skip, row))
    }

    /// The whole span `x..x+len` of frame row `y`, or `None` if any of it
    /// is outside.
    #[inline(always)]
    pub(crate) fn exact_span_mut(&mut self, y: i32, x: i32, len: u32) -> Option<&mut [C]> {
        self.buf.get_mut(self.layout.span_exact(y, x, len)?)
    }
}

impl<C: Copy> Target for Band<'_, C> {
    type Color = C;

    #[inline]
    fn clip_rect(&self) -> Rect {
        self.layout.rect()
    }

    #[inline]
    fn fill_solid(&mut self, y: i32, x: i32, len: u32, color: C) {
        if let Some((_, row)) = self.clipped_span_mut(y, x, len) {
            fill_unrolled(row, color);
        }
    }

    #[inline]
    fn fill_with<F: FnMut() -> C>(&mut self, y: i32, x: i32, len: u32, mut colors: F) {
        if let Some((skip, row)) = self.clipped_span_mut(y, x, len) {
            for _ in 0..skip {
                colors();
            }
            for px in row {
                *px = colors();
            }
        }
    }

    #[inline(always)]
    fn span_mut(&mut self, y: i32, x: i32, len: u32) -> Option<&mut [C]> {
        self.exact_span_mut(y, x, len)
    }

    fn clear(&mut self, color: C) {
        Band::clear(self, color);
    }
}

/// `row.fill(color)`, sixteen stores per loop iteration, out of line: on
/// Cortex-M0, where `slice::fill` of 16-bit pixels compiles to a store
/// plus three instructions of loop per pixel, eight stores inlined
/// roughly halved the flat fill's instructions per pixel (`bash
/// tests/mcu/run`, `ipp flat`); sixteen out of line, which leaves the
/// scan converter its registers, took W1/W2 per frame on ARMv6-M from
/// 5.47 M / 6.43 M to 5.43 M / 6.40 M and on the Cortex-M4 (f32) from
/// 3.58 M / 4.23 M to 3.53 M / 4.20 M, and `ipp flat` on ARMv6-M from
/// 1.64 to 1.46. (x86-64 W1, callgrind: 3 278 675 -> 3 282 018.) Then 32
/// stores per iteration before the 16 (a whole-frame clear is 76 800
/// pixels): W1/W2 on ARMv6-M 5.094 M / 6.054 M -> 5.087 M / 6.046 M, for
/// 96 bytes. Pixels of two bytes take `pairs::fill_pairs` instead (two
/// pixels a store); the loop below serves the other sizes.
#[inline(never)]
pub(crate) fn fill_unrolled<C: Copy>(row: &mut [C], color: C) {
    if super::pairs::fill_pairs(row, color) {
        return;
    }
    fill_run(row, color);
}

/// `s.fill(v)` in unrolled stores: 32 per iteration, then 16, then one
/// by one. The one store loop of the solid fills: pixels
/// ([`fill_unrolled`]), pixel pairs (`pairs::fill_pairs`) and depth-key
/// words (`DepthBuffer::clear`); each caller keeps it out of line.
#[inline(always)]
pub(crate) fn fill_run<T: Copy>(s: &mut [T], v: T) {
    #[inline(always)]
    fn sixteen<T: Copy>(c: &mut [T], v: T) {
        if let [a, b, d, e, f, g, h, i, j, k, l, m, n, o, p, q] = c {
            (*a, *b, *d, *e) = (v, v, v, v);
            (*f, *g, *h, *i) = (v, v, v, v);
            (*j, *k, *l, *m) = (v, v, v, v);
            (*n, *o, *p, *q) = (v, v, v, v);
        }
    }
    let mut chunks = s.chunks_exact_mut(32);
    for c in &mut chunks {
        let (lo, hi) = c.split_at_mut(16);
        sixteen(lo, v);
        sixteen(hi, v);
    }
    let rest = chunks.into_remainder();
    let mut chunks = rest.chunks_exact_mut(16);
    for c in &mut chunks {
        sixteen(c, v);
    }
    chunks.into_remainder().fill(v);
}
