//! The one place sightline uses `unsafe`: a solid fill of 2-byte pixels
//! that stores two pixels per 32-bit word.
//!
//! ARMv6-M stores one 16-bit pixel per `strh`, so a solid fill costs at
//! least one instruction a pixel plus its loop; the goal for the flat
//! shader is at most one (issue 12's `ipp flat`). Viewing the row's
//! 4-byte-aligned middle as words halves the stores. Safe Rust has no
//! such view of a slice of a foreign pixel type (embedded-graphics'
//! `Rgb565` implements no byte-cast trait), hence this module. On
//! ARMv6-M it took `ipp flat` from 1.36 to 0.77 instructions a pixel and
//! W1/W2 (whose colour clear is such a fill) from 5.08 M / 6.04 M to
//! 5.04 M / 6.00 M instructions a frame, for 100 bytes (`bash
//! tests/mcu/run`).
//!
//! Soundness, for any `C: Copy` with `size_of::<C>() == 2`:
//! - the word is the bytes of `[color, color]`, read as a
//!   `MaybeUninit<u32>`, which may hold any bytes (a padding byte of `C`
//!   stays uninitialized, as it may in `C` itself);
//! - the words are written only where `align_to_mut` found whole,
//!   aligned words inside the row, and every byte written is a copy of a
//!   byte of `color` at the same offset within a pixel, so every pixel
//!   afterwards holds exactly `color`'s bytes: a valid `C`;
//! - nothing else is written through the word view, and it does not
//!   outlive this function.

#![allow(unsafe_code)]

use core::mem::{MaybeUninit, size_of};

/// `row.fill(color)`, two pixels per 32-bit store where `C` is 2 bytes
/// (returns `false`, having written nothing, for any other size). Tested
/// under Miri in CI (`target::tests::pair_fill_writes_exactly_the_row`).
#[inline(always)]
pub(super) fn fill_pairs<C: Copy>(row: &mut [C], color: C) -> bool {
    if size_of::<C>() != 2 || size_of::<[C; 2]>() != size_of::<u32>() {
        return false;
    }
    // SAFETY: `[C; 2]` is 4 bytes (checked above); a `MaybeUninit<u32>`
    // may hold any 4 bytes, initialized or not.
    let word: MaybeUninit<u32> = unsafe { core::mem::transmute_copy(&[color, color]) };
    // SAFETY: see the module docs: only `word` is written through the
    // middle, so each pixel of it ends up with `color`'s bytes.
    let (head, words, tail) = unsafe { row.align_to_mut::<MaybeUninit<u32>>() };
    head.fill(color);
    super::framebuffer::fill_run(words, word);
    tail.fill(color);
    true
}
