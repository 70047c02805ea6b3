//! Every choice the kernel makes by target, in one place.
//!
//! The rest of the crate asks named questions ([`SOFT_MUL64`],
//! [`hardware_div32`], …) and calls named operations ([`pack_planes`],
//! [`keep_loop_rolled`]); the `cfg`s on the target, the
//! inline assembly, the routines of assembly (`global_asm!`: the ARMv7-M
//! row loop, Gouraud set-up and triangle loop, which call each other) and
//! the optimisation barriers that answer them live here only. Every answer is a constant, so the branch not taken is
//! removed at compile time and each target's code is what it would be with
//! the `cfg` written at the call site.
//!
//! The frames do not depend on any of these choices: each names two forms
//! of the same values (unit tests hold the forms to each other, and CI runs
//! the test suite on the host with `fixshade_soft_mul64` and
//! `fixshade_soft_div32` set, `FIXSHADE_LIMBS=1`: `build.rs`); only the
//! instructions differ.

use crate::planes::{Planes, Row};

/// `asm!` for a routine that may change every high register `asm!` can
/// name (r8–r12, lr; Thumb-1 takes none of them as an operand): the
/// caller's template and operands (every low one it uses among them), a
/// comma after the last, and those registers marked as changed, written
/// once here.
#[cfg(fixshade_thumb1)]
macro_rules! asm_high_registers {
    ($($t:tt)*) => {
        core::arch::asm!(
            $($t)*
            out("r8") _,
            out("r9") _,
            out("r10") _,
            out("r11") _,
            out("r12") _,
            out("lr") _,
        )
    };
}

/// `asm_high_registers!` for a routine that takes its argument in r0
/// and may change every other register `asm!` can name (r1–r5 too; r6 and
/// r7 it saves itself).
#[cfg(fixshade_thumb1)]
macro_rules! asm_every_register {
    ($($t:tt)*) => {
        asm_high_registers!(
            $($t)*
            out("r1") _,
            out("r2") _,
            out("r3") _,
            out("r4") _,
            out("r5") _,
        )
    };
}

/// The core has no 32 × 32 → 64-bit multiply instruction (ARMv6-M: the
/// Cortex-M0 and M0+, the RP2040's core; ARMv8-M Baseline: the Cortex-M23),
/// so a product of two `i64`s is a call to `__aeabi_lmul`, a 64 × 64-bit
/// product of 37 instructions. Where this holds, the wide products are
/// built from 16 × 16 → 32-bit ones (one `muls` each). The build script
/// sets `fixshade_soft_mul64` from the target's name: stable Rust has no
/// `target_feature` for the instruction.
pub(crate) const SOFT_MUL64: bool = cfg!(fixshade_soft_mul64);

/// The core divides 32-bit numbers in one instruction: every target but
/// ARMv6-M (the Cortex-M0 and M0+), where the build script sets
/// `fixshade_soft_div32`; elsewhere a division is a library call of some
/// 30 to 100 instructions, and [`Divisor`](crate::num::division::Divisor)
/// takes a reciprocal instead.
#[inline(always)]
pub(crate) const fn hardware_div32() -> bool {
    !cfg!(fixshade_soft_div32)
}

/// The core divides 64-bit numbers itself: a 64-bit target. On a 32-bit
/// one a 64-bit division is a library routine of about a kilobyte of
/// flash, and the kernel's few (the rare path's, once a draw's) take
/// 32-bit divisions instead ([`div_rem_u64`](crate::num::division::div_rem_u64)),
/// as they do on the host under `--cfg fixshade_soft_div32` (the test
/// suite and the fuzz target run them so).
pub(crate) const NATIVE_DIV64: bool =
    cfg!(target_pointer_width = "64") && !cfg!(fixshade_soft_div32);

/// Whether a triangle of a few samples tests each against its edge
/// functions rather than walking its edges (`src/setup.rs`): where the
/// core divides in software, the three edges' quotients cost more than a
/// handful of samples' tests; where it divides in hardware, less. Both
/// give the same spans.
pub(crate) const TEST_SAMPLES: bool = !hardware_div32();

/// Whether an edge of a gentle slope whose first sample row lies at most a
/// row below its top finds its small quotients by steps rather than a
/// division (`src/walk.rs`): where the core divides in software, a few
/// steps cost less than a reciprocal and two corrected products.
pub(crate) const STEP_QUOTIENTS: bool = !hardware_div32();

/// The crate's `clip` feature (a default one): the rare path
/// (`src/clip.rs`, 8.5 KB of flash in S1's configuration on ARMv6-M)
/// clips triangles against the near plane and the guard band. Without it
/// a draw whose mesh is not contained (`vertex::Rows::contained`) is
/// refused before any pixel is written, so no triangle ever takes that
/// path and none of it is linked. A choice of the build, not of the
/// target, answered here with the others.
pub(crate) const CLIP: bool = cfg!(feature = "clip");

/// The target stores integers little-endian, the byte order of the mesh
/// layout: where this holds, a mesh's arrays are read in place as `i16` and
/// `u16` values.
#[inline(always)]
pub(crate) const fn little_endian() -> bool {
    cfg!(target_endian = "little")
}

/// Bytes from one of the vertex stage's rows to the next
/// ([`fourteen_rows`]; only its assembly reads rows by this stride).
#[cfg_attr(not(any(fixshade_thumb1, fixshade_thumb2)), allow(dead_code))]
pub(crate) const ROW_BYTES: usize = 56;

/// Where a row's split coefficients start ([`fourteen_rows`] on ARMv6-M):
/// `gₕ` (three `i32`s) and `tₕ`, then `gₗ` and `tₗ`, eight words.
#[cfg_attr(not(fixshade_thumb1), allow(dead_code))]
pub(crate) const ROW_SPLIT: usize = 20;

/// `⌊V/2¹⁴⌋` of the vertex stage's four rows at position `q` (`V = t +
/// Σ g·q`, below 2⁴⁵; the floor below 2³¹ in magnitude: the low 32 bits
/// of the 64-bit shift), in assembly:
/// - on ARMv7-M a row is one `ldm` (`t` and `g` at once), three `smlal`
///   and the shift;
/// - on ARMv6-M, which has no 64-bit product, a row is its split halves
///   (`V = 2¹⁴·(Σ gₕq + tₕ) + (Σ gₗq + tₗ)`, both sums within `i32`: the
///   vertex stage's `Row::fourteen`), two `ldm` of four words, six `muls`
///   and the sums: 19 instructions a row.
///
/// Compiled, the rows' words did not fit the registers beside the vertex
/// loop's and were reloaded one by one (on ARMv6-M, 127 instructions a
/// vertex for the four rows). `None` elsewhere: the caller's Rust takes
/// them.
///
/// # Safety
/// `rows` points to four readable rows [`ROW_BYTES`] apart, each starting
/// with `t` (an `i64`) and then `g` (three `i32`s), with the split
/// coefficients at [`ROW_SPLIT`].
#[inline(always)]
pub(crate) unsafe fn fourteen_rows(rows: *const u8, q: [i16; 3]) -> Option<[i32; 4]> {
    #[cfg(fixshade_thumb2)]
    {
        let (x, y, z, w): (i32, i32, i32, i32);
        // One row into output `o`: `t` and `g` loaded (the pointer moved
        // on by 20 bytes), the three products added to `t`, the floor of
        // the 64-bit sum over 2¹⁴ kept in 32 bits.
        macro_rules! row {
            ($o:literal) => {
                concat!(
                    "ldm {p}!, {{r4, r5, r8, r12, lr}}\n",
                    "smlal r4, r5, r8, {q0}\n",
                    "smlal r4, r5, r12, {q1}\n",
                    "smlal r4, r5, lr, {q2}\n",
                    "lsrs r4, r4, #14\n",
                    "orr {",
                    $o,
                    "}, r4, r5, lsl #18",
                )
            };
        }
        // SAFETY: the caller's contract: each `ldm` reads a row's first
        // five words (`t` low and high, little-endian, then `g`), and the
        // pointer moves on by `ROW_BYTES` (20 and the rest) a row.
        unsafe {
            core::arch::asm!(
                row!("x"),
                "add {p}, #{skip}",
                row!("y"),
                "add {p}, #{skip}",
                row!("z"),
                "add {p}, #{skip}",
                row!("w"),
                p = inout(reg) rows => _,
                skip = const ROW_BYTES - 20,
                q0 = in(reg) q[0] as i32,
                q1 = in(reg) q[1] as i32,
                q2 = in(reg) q[2] as i32,
                x = out(reg) x,
                y = out(reg) y,
                z = out(reg) z,
                w = lateout(reg) w,
                out("r4") _,
                out("r5") _,
                out("r8") _,
                out("r12") _,
                out("lr") _,
                options(pure, readonly, nostack),
            );
        }
        Some([x, y, z, w])
    }
    #[cfg(fixshade_thumb1)]
    {
        let (x, y, z, w): (i32, i32, i32, i32);
        // One split half of a row into r4: three coefficients and the
        // constant loaded (the pointer moved on by 16 bytes), `Σ g·q + t`.
        macro_rules! half {
            () => {
                concat!(
                    "ldm r0!, {{r4, r5, r6, r7}}\n",
                    "muls r4, r1, r4\n",
                    "muls r5, r2, r5\n",
                    "muls r6, r3, r6\n",
                    "adds r4, r4, r5\n",
                    "adds r4, r4, r6\n",
                    "adds r4, r4, r7\n",
                )
            };
        }
        // One row into register `o`: the high sum kept in r12 while the low
        // one is made, then `hi + (lo >> 14)`; the pointer on to the next
        // row's split coefficients.
        macro_rules! row {
            ($o:literal) => {
                concat!(
                    half!(),
                    "mov r12, r4\n",
                    half!(),
                    "asrs r4, r4, #14\n",
                    "add r4, r12\n",
                    "mov ",
                    $o,
                    ", r4\n",
                    "adds r0, #{skip}",
                )
            };
        }
        // SAFETY: the caller's contract: each `ldm` pair reads a row's
        // eight split words, and the pointer moves on by `ROW_BYTES` a
        // row. r6 and r7, which `asm!` may not name, are pushed and popped
        // around their use; sp is restored.
        unsafe {
            core::arch::asm!(
                "push {{r6, r7}}",
                "adds r0, #{split}",
                row!("r8"),
                row!("r9"),
                row!("r10"),
                row!("r11"),
                // The four floors out in r0–r3 (high registers may not be
                // an operand in Thumb-1 code).
                "mov r0, r8",
                "mov r1, r9",
                "mov r2, r10",
                "mov r3, r11",
                "pop {{r6, r7}}",
                split = const ROW_SPLIT,
                skip = const ROW_BYTES - 32,
                inout("r0") rows => x,
                inout("r1") q[0] as i32 => y,
                inout("r2") q[1] as i32 => z,
                inout("r3") q[2] as i32 => w,
                out("r4") _,
                out("r5") _,
                out("r8") _,
                out("r9") _,
                out("r10") _,
                out("r11") _,
                out("r12") _,
                options(readonly),
            );
        }
        Some([x, y, z, w])
    }
    #[cfg(not(any(fixshade_thumb1, fixshade_thumb2)))]
    {
        let _ = (rows, q);
        None
    }
}

/// `x.leading_zeros()`. ARMv6-M and ARMv8-M Baseline have no
/// count-leading-zeros instruction (nor a 32 × 32 → 64-bit multiply, whose
/// flag tells them apart), and the library's (`__clzsi2`) is a call of
/// about 30 instructions: there, three inline halving steps and a table
/// of the top nibble's.
#[inline(always)]
pub(crate) const fn leading_zeros(x: u32) -> u32 {
    if SOFT_MUL64 {
        leading_zeros_halving(x)
    } else {
        x.leading_zeros()
    }
}

/// Leading zeros of a nibble.
const NIBBLE: [u8; 16] = [4, 3, 2, 2, 1, 1, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0];

/// [`leading_zeros`] of `x ∈ [2²², 2³¹)` (a vertex's `W` in the vertex
/// stage's 32-bit form: 1 to 9). On ARMv6-M one step of five and the top
/// nibble's table: `x` is then in `[2²⁷, 2³²)`, whose leading zeros (0 to
/// 4) the nibble above bit 27 gives.
#[inline(always)]
pub(crate) const fn leading_zeros_of_w(x: u32) -> u32 {
    debug_assert!(x >= 1 << 22 && x < 1 << 31);
    if SOFT_MUL64 {
        leading_zeros_of_w_step(x)
    } else {
        x.leading_zeros()
    }
}

/// [`leading_zeros_of_w`] in one step and the nibble's table.
#[inline(always)]
const fn leading_zeros_of_w_step(x: u32) -> u32 {
    let (x, n) = if x >> 27 == 0 { (x << 5, 5) } else { (x, 0) };
    n + NIBBLE[(x >> 28) as usize] as u32
}

/// [`leading_zeros`] in three halving steps and a table of the top
/// nibble's (`NIBBLE[0]` not read: the top nibble is not 0 once the steps
/// are done, `x` being non-zero).
#[inline(always)]
const fn leading_zeros_halving(x: u32) -> u32 {
    if x == 0 {
        return 32;
    }
    let (mut x, mut n) = (x, 0);
    // 16, 8, 4 (a `while`, as a `const fn` takes no `for`).
    let mut k = 16;
    while k >= 4 {
        if x >> (32 - k) == 0 {
            n += k;
            x <<= k;
        }
        k >>= 1;
    }
    n + NIBBLE[(x >> 28) as usize] as u32
}

/// The RGB565 pixel `(r >> 20) << 11 | (g >> 20) << 5 | (b >> 20)` of
/// three colour planes (`Q.20` channels: `0 ≤ r, b < 2²⁵`, `0 ≤ g < 2²⁶`).
///
/// On ARMv7-M five instructions of inline assembly, no constant: each
/// channel's `>> 20` is its value, and the shifts ride on the `orr`s.
/// Written in Rust, LLVM turns the shifts into masks whose constants take
/// registers in the span loop. Elsewhere the expression in Rust (the same
/// value).
#[inline(always)]
pub(crate) fn pack_planes(r: i32, g: i32, b: i32) -> u16 {
    #[cfg(fixshade_thumb2)]
    {
        let w: u32;
        // SAFETY: register arithmetic only.
        unsafe {
            core::arch::asm!(
                "lsrs {t}, {g}, #20",
                "lsrs {w}, {r}, #20",
                "orr {w}, {t}, {w}, lsl #6",
                "lsrs {t}, {b}, #20",
                "orr {w}, {t}, {w}, lsl #5",
                r = in(reg) r,
                g = in(reg) g,
                b = in(reg) b,
                w = out(reg) w,
                t = out(reg) _,
                options(pure, nomem, nostack),
            );
        }
        w as u16
    }
    #[cfg(not(fixshade_thumb2))]
    {
        let c = |v: i32| (v >> 20) as u32;
        ((c(r) << 11) | (c(g) << 5) | c(b)) as u16
    }
}

/// Two pixels from three lane words (red and blue `Q5.11`, green `Q6.10`,
/// in each 16-bit half; see `src/span.rs`'s `Pairs`), the first in the low
/// half.
///
/// On ARMv7-M the masks are immediates of `and` and the shifts ride on the
/// `orr`s: five instructions. Elsewhere the expression in Rust.
#[inline(always)]
pub(crate) fn pack_pair(l: [u32; 3]) -> u32 {
    #[cfg(fixshade_thumb2)]
    {
        let w: u32;
        // SAFETY: register arithmetic only.
        unsafe {
            core::arch::asm!(
                "and {t}, {g}, #0xFC00FC00",
                "and {w}, {r}, #0xF800F800",
                "orr {w}, {w}, {t}, lsr #5",
                "and {t}, {b}, #0xF800F800",
                "orr {w}, {w}, {t}, lsr #11",
                r = in(reg) l[0],
                g = in(reg) l[1],
                b = in(reg) l[2],
                w = out(reg) w,
                t = out(reg) _,
                options(pure, nomem, nostack, preserves_flags),
            );
        }
        w
    }
    #[cfg(not(fixshade_thumb2))]
    {
        (l[0] & 0xF800_F800) | ((l[1] >> 5) & 0x07E0_07E0) | ((l[2] >> 11) & 0x001F_001F)
    }
}

/// Pixel pairs from lanes `l` stepped by `s` into `row`, two pixels a
/// pair (an odd last pixel left alone); returns the lanes after the last
/// pair.
///
/// On ARMv7-M a loop of assembly, two pairs an iteration: 20
/// instructions for four pixels (two [`pack_pair`]s, six adds, two
/// stores, the count). The stores are words at any halfword address,
/// which ARMv7-M allows. In Rust, LLVM keeps the steps on the stack and
/// copies the lanes (29 instructions). Elsewhere the loop in Rust.
#[inline(always)]
pub(crate) fn pair_run(l: [u32; 3], s: [u32; 3], row: &mut [u16]) -> [u32; 3] {
    let mut l = l;
    #[cfg(fixshade_thumb2)]
    let row = {
        let quads = row.len() / 4;
        if quads > 0 {
            // SAFETY: `quads` iterations store 8 bytes each from the row's
            // first pixel on: `4·quads ≤ row.len()` pixels.
            unsafe {
                // One pair: pack its two pixels into a word, step the
                // three channels, store.
                macro_rules! pair {
                    () => {
                        concat!(
                            "and {t}, {g}, #0xFC00FC00\n",
                            "and {w}, {r}, #0xF800F800\n",
                            "orr {w}, {w}, {t}, lsr #5\n",
                            "and {t}, {b}, #0xF800F800\n",
                            "orr {w}, {w}, {t}, lsr #11\n",
                            "add {r}, {sr}\n",
                            "add {g}, {sg}\n",
                            "add {b}, {sb}\n",
                            "str {w}, [{at}], #4",
                        )
                    };
                }
                core::arch::asm!(
                    "1:",
                    pair!(),
                    pair!(),
                    "subs {n}, #1",
                    "bne 1b",
                    r = inout(reg) l[0],
                    g = inout(reg) l[1],
                    b = inout(reg) l[2],
                    sr = in(reg) s[0],
                    sg = in(reg) s[1],
                    sb = in(reg) s[2],
                    at = inout(reg) row.as_mut_ptr() => _,
                    n = inout(reg) quads => _,
                    w = out(reg) _,
                    t = out(reg) _,
                    options(nostack),
                );
            }
        }
        &mut row[4 * quads..]
    };
    for p in row.chunks_exact_mut(2) {
        let w = pack_pair(l);
        p.copy_from_slice(&[w as u16, (w >> 16) as u16]);
        l = [0, 1, 2].map(|k| l[k].wrapping_add(s[k]));
    }
    l
}

/// A table of a triangle's rows ready for a row loop: the triangle's
/// planes (read in place), the rows' spans, and where each row's column 0
/// lies in the colour and depth stores (the same index in both).
/// `repr(C)`: the loops in assembly read and update it at the offsets
/// named in [`gouraud_depth_rows`].
#[repr(C)]
pub(crate) struct Rows<'a> {
    /// The planes at column 0 of the current row (the loops' own).
    rowv: [i32; 4],
    planes: *const Planes<4>,
    /// The first row's distance from the planes' first.
    dy: i32,
    /// The next row's span, and the table's end.
    table: *const Row,
    end: *const Row,
    cbase: *mut u16,
    /// Bytes from a row to the next.
    stride: u32,
    zbase: *mut u16,
    covered: u32,
    failed: u32,
    _stores: core::marker::PhantomData<(&'a Planes<4>, &'a [Row], &'a mut [u16])>,
}

impl<'a> Rows<'a> {
    /// The rows of `table` (at least one), the first `dy` rows below the
    /// `planes`' first, in `buf` and `zbuf`, row-major `width` pixels a
    /// row, column 0 of the first row at index `first`.
    ///
    /// The caller has checked that every row's span lies in both stores:
    /// the loops write exactly those pixels.
    pub(crate) fn new(
        planes: &'a Planes<4>,
        dy: i32,
        table: &'a [Row],
        buf: &'a mut [u16],
        zbuf: &'a mut [u16],
        first: i64,
        width: u32,
    ) -> Self {
        let (colour, depth) = (buf.as_mut_ptr(), zbuf.as_mut_ptr());
        let at = |p: *mut u16| p.wrapping_offset(first as isize);
        // SAFETY: the stores are borrowed for `'a`; that every row's span
        // lies in them is the caller's check (above), `at`'s contract.
        unsafe { Rows::at(planes, dy, table, at(colour), at(depth), 2 * width) }
    }

    /// [`Rows::new`] from the stores' column 0 of the first row, `colour`
    /// and `depth`, and the bytes from a row to the next.
    ///
    /// # Safety
    /// Every row's span, at `colour` and `depth` moved `stride` bytes a
    /// row, lies in a store valid for writes for `'a`, and `planes` and
    /// `table` live that long.
    pub(crate) unsafe fn at(
        planes: &'a Planes<4>,
        dy: i32,
        table: &'a [Row],
        colour: *mut u16,
        depth: *mut u16,
        stride: u32,
    ) -> Self {
        Rows {
            rowv: [0; 4],
            planes,
            dy,
            table: table.as_ptr(),
            end: table.as_ptr_range().end,
            cbase: colour,
            stride,
            zbase: depth,
            covered: 0,
            failed: 0,
            _stores: core::marker::PhantomData,
        }
    }
}

// ARMv7-M: `gouraud_depth_rows`' loop as a routine of the procedure
// call standard (`r0` the `Rows`, the pixels written returned in `r0`,
// r4–r11 kept), so that `gouraud_set_up`'s routine calls it too.
#[cfg(fixshade_thumb2)]
core::arch::global_asm!(
    ".section .text.fixshade_gouraud_rows,\"ax\",%progbits",
    ".global fixshade_gouraud_rows",
    ".type fixshade_gouraud_rows, %function",
    ".p2align 2",
    ".thumb_func",
    "fixshade_gouraud_rows:",
    "push {{r4, r5, r6, r7, r8, r9, r10, r11, lr}}",
    "mov r7, r0",
    // The planes at column 0 of the first row: at + gy·dy; the
    // steps down a row copied into `rowv` (one `ldm` a row).
    "ldrd r12, r1, [r7, #16]",
    "ldm r12!, {{r3, r4, r5, r6}}",
    "ldm r12!, {{r8, r9, r10, r11}}",
    "ldm r12, {{r0, r2, r12, lr}}",
    "stm r7, {{r0, r2, r12, lr}}",
    "mla r3, r0, r1, r3",
    "mla r4, r2, r1, r4",
    "mla r5, r12, r1, r5",
    "mla r6, lr, r1, r6",
    // `zbase` becomes the depth store's distance from the colour
    // store: one pointer a span, the depth at `[r2, r0]`.
    "ldr r0, [r7, #32]",
    "ldr r1, [r7, #40]",
    "sub r1, r1, r0",
    "str r1, [r7, #40]",
    // The table's cursor in r12 from row to row (saved over a span).
    "ldr r12, [r7, #24]",
    "1:",
    "ldm r12!, {{r0, r1}}",
    "cmp r1, #0",
    "ble 6f",
    "ldr lr, [r7, #44]",
    "add lr, r1",
    "str lr, [r7, #44]",
    "push {{r3, r4, r5, r6, r12}}",
    "mla r3, r8, r0, r3",
    "mla r4, r9, r0, r4",
    "mla r5, r10, r0, r5",
    "mla r6, r11, r0, r6",
    "ldr r2, [r7, #32]",
    "add r2, r2, r0, lsl #1",
    "ldr r0, [r7, #40]",
    "2:",
    "ldrh r12, [r2, r0]",
    "usat lr, #16, r3, asr #12",
    "cmp lr, r12",
    "bhs 4f",
    "strh lr, [r2, r0]",
    "lsrs r12, r5, #20",
    "lsrs lr, r4, #20",
    "orr lr, r12, lr, lsl #6",
    "lsrs r12, r6, #20",
    "orr lr, r12, lr, lsl #5",
    "strh lr, [r2], #2",
    "3:",
    "add r3, r8",
    "add r4, r9",
    "add r5, r10",
    "add r6, r11",
    "subs r1, #1",
    "bne 2b",
    "pop {{r3, r4, r5, r6, r12}}",
    "6:",
    "ldm r7, {{r0, r1, r2, lr}}",
    "add r3, r0",
    "add r4, r1",
    "add r5, r2",
    "add r6, lr",
    "ldrd r0, r1, [r7, #32]",
    "add r0, r1",
    "str r0, [r7, #32]",
    "ldr r0, [r7, #28]",
    "cmp r12, r0",
    "bne 1b",
    "b 9f",
    "4:",
    "adds r2, #2",
    "ldr r12, [r7, #48]",
    "adds r12, #1",
    "str r12, [r7, #48]",
    "b 3b",
    "9:",
    "ldrd r0, r1, [r7, #44]",
    "sub r0, r0, r1",
    "pop {{r4, r5, r6, r7, r8, r9, r10, r11, pc}}",
    ".size fixshade_gouraud_rows, . - fixshade_gouraud_rows",
);

#[cfg(fixshade_thumb2)]
extern "C" {
    /// [`gouraud_depth_rows`]' loop (the `global_asm!` above).
    fn fixshade_gouraud_rows(run: *mut Rows) -> u32;
}

/// The Gouraud rows of `run` through the depth test: each pixel's depth is
/// `clamp(z >> 12, 0, 65535)`, written with the pixel's colour
/// ([`pack_planes`]) where it is below the stored one; returns the pixels
/// written.
///
/// On Cortex-M cores the whole table is one loop of assembly (17
/// instructions a written pixel on ARMv7-M, `usat` clamping and the colour
/// in five; 22 on ARMv6-M, where a depth above 65535 fails the unsigned
/// comparison as its clamp would and a negative one becomes 0), the four
/// steps held in registers from row to row and each row's start made
/// from the row's planes with four multiply-accumulates. In Rust, LLVM
/// keeps the four planes, their steps and two pointers in too few
/// registers: the steps are reloaded at every pixel, and a row's span is
/// wrapped in spills (the counts of that form are in
/// `docs/PERFORMANCE_LOG.md`). On ARMv7-M a routine of the procedure
/// call standard, which [`gouraud_set_up`]'s routine calls too (27
/// instructions a row with a span: the steps down a row copied beside
/// the table, one pointer a span with the depth store at a fixed
/// distance, the table's cursor in a register); on ARMv6-M inline
/// assembly, the frame pointer `r7` and `r6`, which `asm!` may not name,
/// saved and used. Elsewhere the same loop in Rust.
///
/// [`Rows`]' offsets: `rowv` 0, `planes` 16, `dy` 20, `table` 24, `end`
/// 28, `cbase` 32, `stride` 36, `zbase` 40, `covered` 44, `failed` 48;
/// [`Planes`]': `at` 0, `gx` 16, `gy` 32.
#[inline(never)]
pub(crate) fn gouraud_depth_rows(run: &mut Rows) -> u32 {
    #[cfg(fixshade_thumb2)]
    // SAFETY: `Rows::new`'s contract; the routine keeps the registers the
    // procedure call standard asks it to.
    unsafe {
        fixshade_gouraud_rows(run)
    }
    #[cfg(not(fixshade_thumb2))]
    {
        gouraud_rows_here(run)
    }
}

/// Whether [`edge_rows`] steps a walk's edges here (ARMv6-M); elsewhere
/// the walk's Rust loop does.
pub(crate) const EDGE_ROWS: bool = cfg!(fixshade_thumb1);

/// The walk's spans between two edges for `n` rows from `rows` on, each
/// `x0` the left edge's column and `n` the right's less it, both edges
/// stepped a row after each (`walk::Edge`'s step: `q += step`, `rem +=
/// rstep`, then one carry where `rem ≥ d`). Each edge is given as its
/// `[q, rem, d, step, rstep]`; returned are both edges' `q` and `rem`
/// stepped past the rows (left, then right). On ARMv6-M inline assembly,
/// the edges in registers: the remainders kept less their divisors, so
/// that the carry's test is a sign, the steps and the negated divisors in
/// r8–r12 and lr; 12 instructions a row without a carry (compiled, the
/// ten words did not fit the low registers: 33). Elsewhere the edges as
/// given ([`EDGE_ROWS`] is false and the caller does not ask).
///
/// # Safety
/// `rows` is valid for `n` writes of [`Row`]; `0 ≤ rem < d` and every
/// row's sums lie within `i32` (`walk::Edge`'s ranges).
#[inline(always)]
pub(crate) unsafe fn edge_rows(rows: *mut Row, n: usize, l: [i32; 5], r: [i32; 5]) -> [i32; 4] {
    #[cfg(fixshade_thumb1)]
    {
        let [mut lq, mut lrem, ld, lstep, lrstep] = l;
        let [mut rq, mut rrem, rd, rstep, rrstep] = r;
        // What the loop keeps in high registers (which Thumb-1 `asm!` may
        // not take as operands): the end, then each edge's divisor and
        // steps.
        let rest = [
            rows.wrapping_add(n) as i32,
            ld,
            lstep,
            lrstep,
            rd,
            rstep,
            rrstep,
        ];
        // SAFETY: the caller's contract; r6 and r7, which `asm!` may not
        // name, are pushed and popped around their use; sp is restored.
        unsafe {
            asm_high_registers!(
                "push {{r6, r7}}",
                "ldm r3!, {{r6, r7}}",
                // −d of each edge into r10 and lr; each remainder less its d.
                "rsbs r7, r7, #0",
                "mov r10, r7",
                "add r2, r10",
                "ldm r3!, {{r7}}",
                "mov r8, r7",
                "ldm r3!, {{r7}}",
                "mov r9, r7",
                "ldm r3!, {{r7}}",
                "rsbs r7, r7, #0",
                "mov lr, r7",
                "add r5, lr",
                "ldm r3!, {{r7}}",
                "mov r11, r7",
                "ldr r7, [r3]",
                "mov r12, r7",
                "cmp r0, r6",
                "beq 4f",
                "1:",
                "subs r3, r4, r1",
                "stm r0!, {{r1, r3}}",
                "add r1, r8",
                "add r2, r9",
                "cmp r2, #0",
                "blt 2f",
                "add r2, r10",
                "subs r1, #1",
                "2:",
                "add r4, r11",
                "add r5, r12",
                "cmp r5, #0",
                "blt 3f",
                "add r5, lr",
                "subs r4, #1",
                "3:",
                "cmp r0, r6",
                "bne 1b",
                "4:",
                // The remainders with their divisors added back.
                "mov r7, r10",
                "subs r2, r2, r7",
                "mov r7, lr",
                "subs r5, r5, r7",
                "pop {{r6, r7}}",
                inout("r0") rows => _,
                inout("r1") lq,
                inout("r2") lrem,
                inout("r3") rest.as_ptr() => _,
                inout("r4") rq,
                inout("r5") rrem,
            );
        }
        [lq, lrem, rq, rrem]
    }
    #[cfg(not(fixshade_thumb1))]
    {
        let _ = (rows, n);
        [l[0], l[1], r[0], r[1]]
    }
}

/// [`gouraud_depth_rows`] where it is not a routine of its own: inline
/// assembly on ARMv6-M, Rust elsewhere.
#[cfg(not(fixshade_thumb2))]
#[inline(always)]
fn gouraud_rows_here(run: &mut Rows) -> u32 {
    #[cfg(fixshade_thumb1)]
    // SAFETY: `Rows::new`'s contract: the table has at least one row, each
    // span within both stores; `run` and its planes are read (and `run`
    // updated) at the offsets of their `repr(C)` layouts. r6 and r7 are
    // pushed and popped around their use; sp is restored. lr holds `run`
    // through the loop, r12 a row's end;
    // `rowv` holds the current row's planes.
    unsafe {
        asm_every_register!(
            "push {{r6, r7}}",
            "mov lr, r0",
            // The steps into r8–r11, the first row's planes into rowv.
            "ldr r7, [r0, #16]",
            "adds r7, #16",
            "ldm r7!, {{r2, r3, r4, r5}}",
            "mov r8, r2",
            "mov r9, r3",
            "mov r10, r4",
            "mov r11, r5",
            "ldm r7!, {{r2, r3, r4, r5}}",
            "ldr r1, [r0, #20]",
            "subs r7, #48",
            "ldm r7!, {{r0, r6}}",
            "muls r2, r1, r2",
            "adds r2, r0",
            "muls r3, r1, r3",
            "adds r3, r6",
            "ldm r7!, {{r0, r6}}",
            "muls r4, r1, r4",
            "adds r4, r0",
            "muls r5, r1, r5",
            "adds r5, r6",
            "mov r7, lr",
            "stm r7!, {{r2, r3, r4, r5}}",
            // `zbase` becomes the depth store's distance from the colour
            // store: one pointer a span, the depth at `[r1, r0]`.
            "ldr r0, [r7, #16]",
            "ldr r1, [r7, #24]",
            "subs r1, r1, r0",
            "str r1, [r7, #24]",
            "1:",
            "mov r7, lr",
            "ldr r6, [r7, #24]",
            "ldm r6!, {{r0, r1}}",
            "str r6, [r7, #24]",
            "cmp r1, #0",
            "ble 6f",
            "ldr r6, [r7, #44]",
            "adds r6, r6, r1",
            "str r6, [r7, #44]",
            "ldm r7!, {{r2, r3, r4, r5}}",
            "mov r6, r8",
            "muls r6, r0, r6",
            "adds r2, r2, r6",
            "mov r6, r9",
            "muls r6, r0, r6",
            "adds r3, r3, r6",
            "mov r6, r10",
            "muls r6, r0, r6",
            "adds r4, r4, r6",
            "mov r6, r11",
            "muls r6, r0, r6",
            "adds r5, r5, r6",
            "lsls r0, r0, #1",
            "ldr r6, [r7, #16]",
            "adds r6, r6, r0",
            "ldr r0, [r7, #24]",
            "lsls r7, r1, #1",
            "adds r7, r7, r6",
            "mov r12, r7",
            "mov r1, r6",
            "2:",
            "ldrh r6, [r1, r0]",
            "asrs r7, r2, #12",
            "bmi 8f",
            "7:",
            "cmp r7, r6",
            "bhs 4f",
            "strh r7, [r1, r0]",
            "lsrs r6, r3, #20",
            "lsls r6, r6, #11",
            "lsrs r7, r4, #20",
            "lsls r7, r7, #5",
            "orrs r6, r7",
            "lsrs r7, r5, #20",
            "orrs r6, r7",
            "strh r6, [r1]",
            "3:",
            "add r2, r8",
            "add r3, r9",
            "add r4, r10",
            "add r5, r11",
            "adds r1, #2",
            "cmp r1, r12",
            "bne 2b",
            "6:",
            // rowv += gy; the bases down a row; on to the next span.
            "mov r7, lr",
            "ldr r6, [r7, #16]",
            "adds r6, #32",
            "ldm r6!, {{r4, r5}}",
            "ldm r7!, {{r0, r1, r2, r3}}",
            "adds r0, r4",
            "adds r1, r5",
            "ldm r6!, {{r4, r5}}",
            "adds r2, r4",
            "adds r3, r5",
            "subs r7, #16",
            "stm r7!, {{r0, r1, r2, r3}}",
            "ldr r0, [r7, #16]",
            "ldr r1, [r7, #20]",
            "adds r0, r0, r1",
            "str r0, [r7, #16]",
            "ldr r0, [r7, #8]",
            "ldr r1, [r7, #12]",
            "cmp r0, r1",
            "bne 1b",
            "b 9f",
            "4:",
            "mov r7, lr",
            "ldr r6, [r7, #48]",
            "adds r6, #1",
            "str r6, [r7, #48]",
            "b 3b",
            "8:",
            "movs r7, #0",
            "b 7b",
            "9:",
            "pop {{r6, r7}}",
            inout("r0") run as *mut Rows => _,
        );
    }
    #[cfg(not(any(fixshade_thumb1, fixshade_thumb2)))]
    {
        // SAFETY: `Rows::new`'s contract: the planes and the table are
        // borrowed for `run`'s life; each row's span lies in both stores,
        // at `base + x0 ..` for that row's bases.
        let p = unsafe { &*run.planes };
        let spans = unsafe {
            core::slice::from_raw_parts(run.table, run.end.offset_from(run.table) as usize)
        };
        run.rowv = core::array::from_fn(|k| p.at[k].wrapping_add(p.gy[k].wrapping_mul(run.dy)));
        for r in spans {
            if r.n > 0 {
                run.covered += r.n as u32;
                let (row, zrow) = unsafe {
                    (
                        core::slice::from_raw_parts_mut(
                            run.cbase.wrapping_offset(r.x0 as isize),
                            r.n as usize,
                        ),
                        core::slice::from_raw_parts_mut(
                            run.zbase.wrapping_offset(r.x0 as isize),
                            r.n as usize,
                        ),
                    )
                };
                let mut a: [i32; 4] =
                    core::array::from_fn(|k| run.rowv[k].wrapping_add(p.gx[k].wrapping_mul(r.x0)));
                for (px, z) in row.iter_mut().zip(zrow.iter_mut()) {
                    let d16 = (a[0] >> 12).clamp(0, 0xFFFF);
                    if d16 < *z as i32 {
                        *z = d16 as u16;
                        *px = pack_planes(a[1], a[2], a[3]);
                    } else {
                        run.failed += 1;
                    }
                    for (v, s) in a.iter_mut().zip(&p.gx) {
                        *v = v.wrapping_add(*s);
                    }
                }
            }
            for (v, s) in run.rowv.iter_mut().zip(&p.gy) {
                *v = v.wrapping_add(*s);
            }
            run.cbase = run.cbase.wrapping_add(run.stride as usize / 2);
            run.zbase = run.zbase.wrapping_add(run.stride as usize / 2);
        }
    }
    run.covered - run.failed
}

/// Whether a kept Gouraud triangle (colour and depth, four attributes) is
/// set up by [`gouraud_set_up`]'s one routine of assembly instead of the
/// set-up's stages in Rust: on ARMv7-M, where the Rust stages hand the
/// triangle from one to the next through memory (its corners, its
/// walk, its planes): with the routine, S1's set-up and walk on the M4F
/// went from 933 to 734 instructions a drawn triangle (report/firmware.md's
/// stage table, `scripts/firmware.sh`), before the routine drew the rows
/// itself and [`gouraud_run`] took the triangle loop.
pub(crate) const GOURAUD_SET_UP: bool = cfg!(fixshade_thumb2);

/// What [`gouraud_set_up`] reads and writes: a kept triangle's three
/// vertex-cache entries (16 bytes each: `x` and `y` as `i16` in the first
/// word, the depth attribute in the second, the lit colour's three 17-bit
/// channels from bit 0 of the third word), its doubled area, its rows of
/// samples, where the planes and the rows' spans go, and where the rows
/// are drawn, if the routine is to draw them. `repr(C)`: the assembly
/// reads it at these offsets (0, 12, 16, 20, 24, 28, 32, 36, 40, 44).
#[repr(C)]
pub(crate) struct GouraudSetUp {
    pub(crate) entries: [*const u32; 3],
    pub(crate) area: i32,
    pub(crate) first_row: i32,
    pub(crate) last_row: i32,
    /// The reciprocals' table of `num::division::recip_fast`.
    pub(crate) nodes: *const u32,
    pub(crate) planes: *mut Planes<4>,
    pub(crate) table: *mut Row,
    /// Column 0 of the first row in the colour store, or null: the rows
    /// are then left to the caller.
    pub(crate) cbase: *mut u16,
    /// Bytes from a row to the next, in both stores.
    pub(crate) stride: u32,
    /// Column 0 of the first row in the depth store.
    pub(crate) zbase: *mut u16,
}

/// ARMv7-M, [`gouraud_set_up`]'s sort of the corners: corners `a` and
/// `b` swapped, and their `y`s `ya` and `yb`, through r12.
#[cfg(fixshade_thumb2)]
#[rustfmt::skip]
macro_rules! thumb2_swap_corners {
    ($a:literal, $b:literal, $ya:literal, $yb:literal) => {
        concat!(
            "mov r12, ", $a, "\n",
            "mov ", $a, ", ", $b, "\n",
            "mov ", $b, ", r12\n",
            "mov r12, ", $ya, "\n",
            "mov ", $ya, ", ", $yb, "\n",
            "mov ", $yb, ", r12\n",
        )
    };
}

/// ARMv7-M, [`gouraud_set_up`]: the edge from the packed position in r1
/// down to the one in r2 at sample row r0 (`walk::Edge::new` with a
/// hardware division: `q = ⌈⌈n/16⌉/dy⌉`, `step = ⌈dx/dy⌉`, each ceiling
/// `−⌊−x/dy⌋` from the truncating `sdiv` and its remainder's sign), its
/// five words (`q`, `rem`, `d`, `step`, `rstep`) stored at r3. Keeps r0–r3
/// and r7.
#[cfg(fixshade_thumb2)]
macro_rules! thumb2_edge {
    () => {
        concat!(
            "sxth r4, r1\n",
            "asr r5, r1, #16\n",
            "sxth r6, r2\n",
            "asr r8, r2, #16\n",
            "sub r6, r6, r4\n",
            "sub r8, r8, r5\n",
            "sub r9, r4, #8\n",
            "mul r9, r9, r8\n",
            "sub r10, r0, r5\n",
            "mla r9, r6, r10, r9\n",
            "add r10, r9, #15\n",
            "asr r10, r10, #4\n",
            "rsb r10, r10, #0\n",
            "sdiv r4, r10, r8\n",
            "mls r10, r4, r8, r10\n",
            "rsb r4, r4, r10, lsr #31\n",
            "rsb r10, r6, #0\n",
            "sdiv r11, r10, r8\n",
            "mls r10, r11, r8, r10\n",
            "rsb r11, r11, r10, lsr #31\n",
            "lsl r10, r8, #4\n",
            "mul r5, r4, r10\n",
            "sub r5, r5, r9\n",
            "mul r12, r11, r8\n",
            "sub r12, r12, r6\n",
            "lsl r12, r12, #4\n",
            "stm r3, {{r4, r5, r10, r11, r12}}\n",
        )
    };
}

/// ARMv7-M, [`gouraud_set_up`]: one barycentric gradient `Λ` from the
/// side in `$s` (signed by the area) and the reciprocal in r4, into `$s`:
/// `shr_to_i32(s·r, 31 − n)` with `31 − n` in r3 and `n + 1` in r2; to
/// label 90 where it does not fit `i32`.
#[cfg(fixshade_thumb2)]
macro_rules! thumb2_lambda {
    ($s:literal) => {
        concat!(
            "umull r0, r1, ",
            $s,
            ", r4\n",
            "asr r8, ",
            $s,
            ", #31\n",
            "mla r1, r8, r4, r1\n",
            "lsr r8, r0, r3\n",
            "lsl r9, r1, r2\n",
            "orr ",
            $s,
            ", r8, r9\n",
            "asr r8, r1, r3\n",
            "cmp r8, ",
            $s,
            ", asr #31\n",
            "bne 90f\n",
        )
    };
}

/// ARMv7-M, [`gouraud_set_up`]: attribute `k`'s plane from its value at
/// vertex 0 (r0) and its differences at vertices 1 and 2 (r1, r2), with
/// the `Λ` in r12, r11 (vertex 1's x and y) and r6, r5 (vertex 2's): the
/// gradients `⌊(d₁Λ₁ + d₂Λ₂ + 2²³)/2²⁴⌋` (to label 90 where one does not
/// fit `i32`), and the plane at column 0 of the first row, `16·a₀ +
/// ⌊(gx·X + gy·Y + 8)/16⌋` with `X = 8 − x₀`, `Y = 8 − y₀ + 16·r_top` at
/// sp + 32 (the set-up's `a₀·16 + offset − gx·c₀ + gy·(r_top − r₀)` in
/// one floor: the integer terms come out of it). Stored at the planes'
/// `at`, `gx`, `gy` offsets given.
#[cfg(fixshade_thumb2)]
macro_rules! thumb2_attribute {
    ($at:literal, $gx:literal, $gy:literal) => {
        concat!(
            "smull r3, r4, r1, r12\n",
            "smlal r3, r4, r2, r6\n",
            "adds r3, r3, #0x800000\n",
            "adc r4, r4, #0\n",
            "lsr r3, r3, #24\n",
            "orr r8, r3, r4, lsl #8\n",
            "asr r3, r4, #24\n",
            "cmp r3, r8, asr #31\n",
            "bne 90f\n",
            "smull r3, r4, r1, r11\n",
            "smlal r3, r4, r2, r5\n",
            "adds r3, r3, #0x800000\n",
            "adc r4, r4, #0\n",
            "lsr r3, r3, #24\n",
            "orr r9, r3, r4, lsl #8\n",
            "asr r3, r4, #24\n",
            "cmp r3, r9, asr #31\n",
            "bne 90f\n",
            "ldrd r1, r2, [sp, #32]\n",
            "smull r3, r4, r8, r1\n",
            "smlal r3, r4, r9, r2\n",
            "adds r3, r3, #8\n",
            "adc r4, r4, #0\n",
            "lsr r3, r3, #4\n",
            "orr r3, r3, r4, lsl #28\n",
            "add r3, r3, r0, lsl #4\n",
            "ldr r4, [r7, #28]\n",
            "str r3, [r4, #",
            $at,
            "]\n",
            "str r8, [r4, #",
            $gx,
            "]\n",
            "str r9, [r4, #",
            $gy,
            "]\n",
        )
    };
}

/// ARMv7-M, [`gouraud_set_up`]: a colour channel's values at the three
/// vertices from their 17 bits in r0–r2, as the set-up's attributes
/// `v·m + 2¹⁵` (`m` = 31 for red and blue, 63 for green: `$sh` 5 or 6):
/// r0 vertex 0's, r1 and r2 the differences from it (the ½ cancels).
#[cfg(fixshade_thumb2)]
macro_rules! thumb2_channel {
    ($sh:literal) => {
        concat!(
            "sub r1, r1, r0\n",
            "sub r2, r2, r0\n",
            "rsb r1, r1, r1, lsl #",
            $sh,
            "\n",
            "rsb r2, r2, r2, lsl #",
            $sh,
            "\n",
            "rsb r0, r0, r0, lsl #",
            $sh,
            "\n",
            "add r0, r0, #32768\n",
        )
    };
}

// ARMv7-M: `gouraud_set_up`'s routine, of the procedure call standard
// (`r0` the `GouraudSetUp`, its result in `r0`, r4–r11 kept), so that
// the lean triangle loop (`gouraud_run`) calls it too. A scratch of 76
// bytes on the stack (72 used; sp stays 8-byte aligned for the row
// loop's call).
#[cfg(fixshade_thumb2)]
core::arch::global_asm!(
    ".section .text.fixshade_gouraud_set_up,\"ax\",%progbits",
    ".global fixshade_gouraud_set_up",
    ".type fixshade_gouraud_set_up, %function",
    ".p2align 2",
    ".thumb_func",
    "fixshade_gouraud_set_up:",
    "push {{r4, r5, r6, r7, r8, r9, r10, r11, lr}}",
    "sub sp, #76",
    "mov r7, r0",
    // Rows: at most 32.
    "ldrd r0, r1, [r7, #16]",
    "sub r1, r1, r0",
    "cmp r1, #31",
    "bhi 90f",
    // The corners sorted by y: t r3, m r4, b r5; their y in
    // r8, r9, r10.
    "ldm r7, {{r8, r9, r10}}",
    "ldr r3, [r8]",
    "ldr r4, [r9]",
    "ldr r5, [r10]",
    "asr r8, r3, #16",
    "asr r9, r4, #16",
    "cmp r9, r8",
    "bge 1f",
    thumb2_swap_corners!("r3", "r4", "r8", "r9"),
    "1:",
    "asr r10, r5, #16",
    "cmp r10, r9",
    "bge 2f",
    thumb2_swap_corners!("r4", "r5", "r9", "r10"),
    "cmp r9, r8",
    "bge 2f",
    thumb2_swap_corners!("r3", "r4", "r8", "r9"),
    "2:",
    "str r3, [sp, #12]",
    "strd r4, r5, [sp, #4]",
    // The middle vertex's side of the long edge: the cross
    // product at sp.
    "sxth r11, r3",
    "sxth r12, r4",
    "sxth lr, r5",
    "sub r1, lr, r11",
    "sub r2, r9, r8",
    "mul r1, r1, r2",
    "sub r2, r10, r8",
    "sub r6, r12, r11",
    "mls r1, r2, r6, r1",
    "str r1, [sp, #0]",
    // The first sample row, and the long edge t → b at sp + 16.
    "lsl r0, r0, #4",
    "add r0, r0, #8",
    "ldr r1, [sp, #12]",
    "ldr r2, [sp, #8]",
    "add r3, sp, #16",
    thumb2_edge!(),
    // The short edge at sp + 36: t → m where m lies below the
    // first sample row (then the switch to m → b at the row
    // of m), else m → b (no switch).
    "ldr r1, [sp, #4]",
    "asr r2, r1, #16",
    "cmp r2, r0",
    "ble 3f",
    "add r2, r2, #7",
    "asr r2, r2, #4",
    "str r2, [sp, #56]",
    "mov r2, r1",
    "ldr r1, [sp, #12]",
    "add r3, sp, #36",
    thumb2_edge!(),
    "b 4f",
    "3:",
    "mvn r2, #0x80000000",
    "str r2, [sp, #56]",
    "ldr r2, [sp, #8]",
    "add r3, sp, #36",
    thumb2_edge!(),
    "4:",
    // Left edge into r0–r4, right into r5, r6, r8–r10: the
    // long one on the left where the cross product is negative.
    "ldr r1, [sp, #0]",
    "add r11, sp, #36",
    "add r3, sp, #16",
    "cmp r1, #0",
    "itt lt",
    "addlt r11, sp, #16",
    "addlt r3, sp, #36",
    "ldm r3, {{r5, r6, r8, r9, r10}}",
    "ldm r11, {{r0, r1, r2, r3, r4}}",
    // Each remainder kept less its divisor, so that the add's
    // sign is the carry's test.
    "sub r1, r1, r2",
    "sub r6, r6, r8",
    // The rows up to the switch or the last: r11 the next
    // row's span, r12 their end.
    "ldr lr, [r7, #20]",
    "add lr, lr, #1",
    "ldr r12, [sp, #56]",
    "cmp r12, lr",
    "it lt",
    "movlt lr, r12",
    "ldr r12, [r7, #16]",
    "sub lr, lr, r12",
    "ldr r11, [r7, #32]",
    "add r12, r11, lr, lsl #3",
    "5:",
    "sub lr, r5, r0",
    "strd r0, lr, [r11], #8",
    "add r0, r0, r3",
    "adds r1, r1, r4",
    "itt pl",
    "subpl r1, r1, r2",
    "subpl r0, r0, #1",
    "add r5, r5, r9",
    "adds r6, r6, r10",
    "itt pl",
    "subpl r6, r6, r8",
    "subpl r5, r5, #1",
    "cmp r11, r12",
    "bne 5b",
    // All rows done? r12 the table's end.
    "ldrd r12, lr, [r7, #16]",
    "sub lr, lr, r12",
    "ldr r12, [r7, #32]",
    "add r12, r12, lr, lsl #3",
    "add r12, r12, #8",
    "cmp r11, r12",
    "beq 6f",
    // The lower short edge m → b from the switch's row, in
    // place of the right edge (long on the left) or the left.
    "add r1, r1, r2",
    "add r6, r6, r8",
    "add lr, sp, #16",
    "stm lr, {{r0, r1, r2, r3, r4}}",
    "add lr, sp, #36",
    "stm lr, {{r5, r6, r8, r9, r10}}",
    "strd r11, r12, [sp, #60]",
    "ldr r1, [sp, #56]",
    "lsl r0, r1, #4",
    "add r0, r0, #8",
    "ldr r2, [sp, #0]",
    "add r3, sp, #16",
    "cmp r2, #0",
    "it lt",
    "addlt r3, sp, #36",
    "ldrd r1, r2, [sp, #4]",
    thumb2_edge!(),
    "add lr, sp, #36",
    "ldm lr, {{r5, r6, r8, r9, r10}}",
    "add lr, sp, #16",
    "ldm lr, {{r0, r1, r2, r3, r4}}",
    "sub r1, r1, r2",
    "sub r6, r6, r8",
    "ldrd r11, r12, [sp, #60]",
    "b 5b",
    // Any span with a pixel? Else 0: no planes.
    "6:",
    "ldr r11, [r7, #32]",
    "7:",
    "ldr r1, [r11, #4]",
    "cmp r1, #0",
    "bgt 8f",
    "add r11, r11, #8",
    "cmp r11, r12",
    "bne 7b",
    "movs r0, #0",
    "b 99f",
    // The planes: the corners in their own order.
    "8:",
    "ldm r7, {{r8, r9, r10}}",
    "ldr r0, [r8]",
    "ldr r1, [r9]",
    "ldr r2, [r10]",
    "sxth r3, r0",
    "asr r4, r0, #16",
    "sxth r5, r1",
    "sub r5, r5, r3",
    "asr r6, r1, #16",
    "sub r6, r6, r4",
    "sxth r11, r2",
    "sub r11, r11, r3",
    "asr r12, r2, #16",
    "sub r12, r12, r4",
    // X = 8 − x₀ and Y = 8 − y₀ + 16·r_top at sp + 32.
    "rsb r0, r3, #8",
    "ldr r1, [r7, #16]",
    "rsb r2, r4, #8",
    "add r1, r2, r1, lsl #4",
    "strd r0, r1, [sp, #32]",
    // The reciprocal of |area|·2ⁿ (`recip_fast`) into r4.
    "ldr r0, [r7, #12]",
    "eor r1, r0, r0, asr #31",
    "sub r1, r1, r0, asr #31",
    "clz r2, r1",
    "lsl r1, r1, r2",
    "sub r3, r1, #0x80000000",
    "lsr r4, r3, #25",
    "ubfx r8, r3, #9, #16",
    "ldr r9, [r7, #24]",
    "add r9, r9, r4, lsl #2",
    "ldrd r4, r9, [r9]",
    "sub r9, r4, r9",
    "lsr r9, r9, #10",
    "mul r9, r9, r8",
    "sub r4, r4, r9, lsr #6",
    "umull r8, r9, r1, r4",
    "rsbs r9, r9, #0x80000000",
    "bmi 11f",
    "umull r8, r3, r4, r9",
    "adds r4, r4, r3, lsl #1",
    "it cs",
    "mvncs r4, #0",
    "b 12f",
    "11:",
    "rsb r9, r9, #0",
    "umull r8, r3, r4, r9",
    "sub r4, r4, r3, lsl #1",
    "12:",
    // The sides, signed by the area: dy₂, −dx₂, −dy₁, dx₁ in
    // r12, r11, r6, r5 (each negated for a negative area);
    // then their Λ in place.
    "cmp r0, #0",
    "ittee lt",
    "rsblt r12, r12, #0",
    "rsblt r5, r5, #0",
    "rsbge r11, r11, #0",
    "rsbge r6, r6, #0",
    "rsb r3, r2, #31",
    "add r2, r2, #1",
    thumb2_lambda!("r12"),
    thumb2_lambda!("r11"),
    thumb2_lambda!("r6"),
    thumb2_lambda!("r5"),
    // Depth.
    "ldm r7, {{r8, r9, r10}}",
    "ldr r0, [r8, #4]",
    "ldr r1, [r9, #4]",
    "ldr r2, [r10, #4]",
    "sub r1, r1, r0",
    "sub r2, r2, r0",
    thumb2_attribute!("0", "16", "32"),
    // Red: bits 0–16 of the colour.
    "ldm r7, {{r8, r9, r10}}",
    "ldr r0, [r8, #8]",
    "ldr r1, [r9, #8]",
    "ldr r2, [r10, #8]",
    "ubfx r0, r0, #0, #17",
    "ubfx r1, r1, #0, #17",
    "ubfx r2, r2, #0, #17",
    thumb2_channel!("5"),
    thumb2_attribute!("4", "20", "36"),
    // Green: bits 17–33.
    "ldm r7, {{r8, r9, r10}}",
    "ldrd r0, r3, [r8, #8]",
    "lsr r0, r0, #17",
    "bfi r0, r3, #15, #2",
    "ldrd r1, r3, [r9, #8]",
    "lsr r1, r1, #17",
    "bfi r1, r3, #15, #2",
    "ldrd r2, r3, [r10, #8]",
    "lsr r2, r2, #17",
    "bfi r2, r3, #15, #2",
    thumb2_channel!("6"),
    thumb2_attribute!("8", "24", "40"),
    // Blue: bits 34–50.
    "ldm r7, {{r8, r9, r10}}",
    "ldr r0, [r8, #12]",
    "ldr r1, [r9, #12]",
    "ldr r2, [r10, #12]",
    "ubfx r0, r0, #2, #17",
    "ubfx r1, r1, #2, #17",
    "ubfx r2, r2, #2, #17",
    thumb2_channel!("5"),
    thumb2_attribute!("12", "28", "44"),
    "ldrd r1, r2, [r7, #16]",
    "sub r0, r2, r1",
    "add r0, r0, #1",
    // With stores, the rows drawn by the row loop's routine
    // from a `Rows` in the scratch (its planes, dy 0, the
    // table, its end, the bases and the stride, no pixel yet).
    "ldr r5, [r7, #36]",
    "cbz r5, 99f",
    "ldr r1, [r7, #28]",
    "movs r2, #0",
    "ldr r3, [r7, #32]",
    "add r4, r3, r0, lsl #3",
    "ldrd r6, r8, [r7, #40]",
    "movs r9, #0",
    "movs r10, #0",
    "add r12, sp, #16",
    "stm r12, {{r1, r2, r3, r4, r5, r6, r8, r9, r10}}",
    "mov r0, sp",
    "bl fixshade_gouraud_rows",
    "b 99f",
    "90:",
    "mvn r0, #0",
    "99:",
    "add sp, #76",
    "pop {{r4, r5, r6, r7, r8, r9, r10, r11, pc}}",
    ".size fixshade_gouraud_set_up, . - fixshade_gouraud_set_up",
);

#[cfg(fixshade_thumb2)]
extern "C" {
    /// [`gouraud_set_up`]'s routine (the `global_asm!` above).
    fn fixshade_gouraud_set_up(args: *const GouraudSetUp) -> i32;
}

/// Sets up a kept Gouraud triangle in one routine: its rows' spans into
/// `args.table` and, unless no row covers a sample, its four planes (the
/// depth, then red, green and blue) into `args.planes`, the values of
/// `setup::set_up` and `setup::planes` for its `Vtx<4>` corners (each
/// corner's depth attribute and lit colour as `shade.rs`'s Gouraud
/// attributes, `v·m + 2¹⁵`). With `args.cbase` not null it draws the
/// rows too ([`gouraud_depth_rows`]' routine, called) and returns the
/// pixels written; else it returns the rows written (`last_row −
/// first_row + 1`); 0 where none covers a sample (no planes), and `None`
/// where the Rust set-up is to take the triangle: more than 32 rows, or a
/// plane too steep for the 32-bit gradients (the exact quotients'). The
/// caller has ruled out rows whose spans need a clamp.
///
/// On ARMv7-M one routine of assembly (of the procedure call standard,
/// which [`gouraud_run`]'s loop calls too), the triangle's values in
/// registers from stage to stage: the corners sorted, the walk's edges by
/// `sdiv` (each of five words, the two or three of a triangle in a scratch
/// on the stack), 14 instructions a row (each edge's remainder kept less
/// its divisor, the carry tested by the add's sign), the reciprocal and
/// the four `Λ`, 30 instructions an attribute's plane besides its values'
/// loads. Elsewhere `None`: [`GOURAUD_SET_UP`] is false there and the
/// caller does not ask.
///
/// # Safety
/// The entries are readable 16-byte cache entries of kept vertices (window
/// positions inside the guard band, so that every difference of two is
/// below 2¹⁵ and every product of two differences below 2³⁰) whose
/// colour word holds a lit colour; `nodes` is that table; `planes` is
/// valid for writes of a `Planes<4>` and `table` for 32 rows (the routine
/// writes at most that many, whatever the entries hold); a `cbase` not
/// null and `zbase` are column 0 of `first_row` in a colour and a depth
/// store in which every row to `last_row`, at every column a span of the
/// triangle's may take, lies (`Rows::new`'s contract, `stride` bytes a
/// row).
#[inline(always)]
pub(crate) unsafe fn gouraud_set_up(args: &GouraudSetUp) -> Option<usize> {
    #[cfg(fixshade_thumb2)]
    {
        // SAFETY: the caller's contract; the routine keeps what the
        // procedure call standard asks it to keep.
        let n = unsafe { fixshade_gouraud_set_up(args) };
        usize::try_from(n).ok()
    }
    #[cfg(not(fixshade_thumb2))]
    {
        let _ = args;
        None
    }
}

/// Where a vertex cache entry keeps its flags word ([`skip_culled`]: the
/// word at this byte offset, the rare path's flag at bit [`RARE_BIT`]).
#[cfg_attr(not(any(fixshade_thumb1, fixshade_thumb2)), allow(dead_code))]
pub(crate) const FLAGS_AT: usize = 12;

/// The rare path's flag in a cache entry's flags word.
#[cfg_attr(not(any(fixshade_thumb1, fixshade_thumb2)), allow(dead_code))]
pub(crate) const RARE_BIT: u32 = 22;

/// ARMv7-M, [`skip_culled`]'s and [`gouraud_run`]'s loops: the addresses
/// of the three entries of the triangle at `p` (its `u16` indices) into
/// `a`, `b`, `c`, entries of 16 bytes from `base` (each argument a
/// register's name or an operand's `{…}`).
#[cfg(fixshade_thumb2)]
#[rustfmt::skip]
macro_rules! thumb2_entries {
    ($a:literal, $b:literal, $c:literal, $p:literal, $base:literal) => {
        concat!(
            "ldrh ", $a, ", [", $p, "]\n",
            "ldrh ", $b, ", [", $p, ", #2]\n",
            "ldrh ", $c, ", [", $p, ", #4]\n",
            "add ", $a, ", ", $base, ", ", $a, ", lsl #4\n",
            "add ", $b, ", ", $base, ", ", $b, ", lsl #4\n",
            "add ", $c, ", ", $base, ", ", $c, ", lsl #4\n",
        )
    };
}

/// ARMv7-M, [`skip_culled`]'s and [`gouraud_run`]'s loops: the doubled
/// area of the entries at `a`, `b`, `c` (their first words) into `area`,
/// leaving `a`'s position in `a` and the differences `b − a`, `c − a` in
/// `b` and `c`; a kept triangle to `8f`, else on from the next (`skip`,
/// the local label stepping `p`; `head`, its loop's) or to `done` at
/// `end`. Bit 0 of `mode`: cull back faces.
#[cfg(fixshade_thumb2)]
#[rustfmt::skip]
macro_rules! thumb2_area_next {
    ($a:literal, $b:literal, $c:literal, $area:literal, $mode:literal, $p:literal,
     $end:literal, $skip:literal, $head:literal, $done:literal) => {
        concat!(
            "ldr ", $a, ", [", $a, "]\n",
            "ldr ", $b, ", [", $b, "]\n",
            "ldr ", $c, ", [", $c, "]\n",
            "ssub16 ", $b, ", ", $b, ", ", $a, "\n",
            "ssub16 ", $c, ", ", $c, ", ", $a, "\n",
            "smusdx ", $area, ", ", $b, ", ", $c, "\n",
            "cmp ", $area, ", #0\n",
            "blt 8f\n",
            "beq ", $skip, "f\n",
            "tst ", $mode, ", #1\n",
            "beq 8f\n",
            $skip, ":\n",
            "adds ", $p, ", #6\n",
            "cmp ", $p, ", ", $end, "\n",
            "bne ", $head, "b\n",
            "b ", $done, "f\n",
        )
    };
}

/// ARMv7-M, [`skip_culled`]'s and [`gouraud_run`]'s kept triangle: its
/// box from [`thumb2_area_next`]'s `a`, `b`, `c`: the least and greatest
/// of the differences b − a, c − a and 0 in each half (`sel` after
/// `ssub16` takes each half by its own comparison), then a added back
/// (differences within ±2¹⁵ in the guard band): the greatest corner into
/// `hi`, the least into `lo`; `b` and `c` changed.
#[cfg(fixshade_thumb2)]
#[rustfmt::skip]
macro_rules! thumb2_box {
    ($a:literal, $b:literal, $c:literal, $hi:literal, $lo:literal) => {
        concat!(
            "ssub16 ", $hi, ", ", $b, ", ", $c, "\n",
            "sel ", $hi, ", ", $b, ", ", $c, "\n",
            "sel ", $lo, ", ", $c, ", ", $b, "\n",
            "mov ", $c, ", #0\n",
            "ssub16 ", $b, ", ", $hi, ", ", $c, "\n",
            "sel ", $hi, ", ", $hi, ", ", $c, "\n",
            "ssub16 ", $b, ", ", $lo, ", ", $c, "\n",
            "sel ", $lo, ", ", $c, ", ", $lo, "\n",
            "sadd16 ", $lo, ", ", $a, ", ", $lo, "\n",
            "sadd16 ", $hi, ", ", $a, ", ", $hi, "\n",
        )
    };
}

/// ARMv7-M, [`skip_culled`]'s and [`gouraud_run`]'s scan from the
/// triangle at `p` to `end` (`done` there, a local label): with bit 1 of
/// `mode` the entries' flags read (a triangle with a rare corner to
/// `rare`, a local label), a loop of its own without; a kept triangle's
/// area in `area` and its box in `t` (the greatest corner) and `u` (the
/// least, [`thumb2_box`]) at label 8; the entry registers are changed; the
/// block's operands `flags` and `rare` name the flags word and the flag.
#[cfg(fixshade_thumb2)]
#[rustfmt::skip]
macro_rules! thumb2_scan {
    ($a:literal, $b:literal, $c:literal, $t:literal, $u:literal, $area:literal,
     $mode:literal, $p:literal, $end:literal, $base:literal, $rare:literal, $done:literal) => {
        concat!(
            "cmp ", $p, ", ", $end, "\n",
            "beq ", $done, "f\n",
            "tst ", $mode, ", #2\n",
            "beq 3f\n",
            "1:\n",
            thumb2_entries!($a, $b, $c, $p, $base),
            "ldr ", $t, ", [", $a, ", #{flags}]\n",
            "ldr ", $u, ", [", $b, ", #{flags}]\n",
            "orrs ", $t, ", ", $u, "\n",
            "ldr ", $u, ", [", $c, ", #{flags}]\n",
            "orrs ", $t, ", ", $u, "\n",
            "tst ", $t, ", #{rare}\n",
            "bne ", $rare, "f\n",
            thumb2_area_next!($a, $b, $c, $area, $mode, $p, $end, "2", "1", $done),
            // The same without the flags.
            "3:\n",
            thumb2_entries!($a, $b, $c, $p, $base),
            thumb2_area_next!($a, $b, $c, $area, $mode, $p, $end, "4", "3", $done),
            "8:\n",
            thumb2_box!($a, $b, $c, $t, $u),
        )
    };
}

/// ARMv6-M, [`skip_culled`]'s loops: the byte offsets of the three
/// entries of the triangle at r0 into r4, r5 and r6.
#[cfg(fixshade_thumb1)]
macro_rules! thumb1_offsets {
    () => {
        concat!(
            "ldrh r4, [r0, #0]\n",
            "ldrh r5, [r0, #2]\n",
            "ldrh r6, [r0, #4]\n",
            "lsls r4, r4, #4\n",
            "lsls r5, r5, #4\n",
            "lsls r6, r6, #4\n",
        )
    };
}

/// ARMv6-M, [`skip_culled`]'s loops: the doubled area of the entries'
/// first words in r7, r1 and r3 into r1 (r3–r7 taken), its flags set by
/// the last `subs`.
#[cfg(fixshade_thumb1)]
macro_rules! thumb1_area {
    () => {
        concat!(
            "asrs r4, r7, #16\n",
            "asrs r5, r1, #16\n",
            "asrs r6, r3, #16\n",
            "subs r5, r5, r4\n",
            "subs r6, r6, r4\n",
            "sxth r7, r7\n",
            "sxth r1, r1\n",
            "sxth r3, r3\n",
            "subs r1, r1, r7\n",
            "subs r3, r3, r7\n",
            "muls r1, r6, r1\n",
            "muls r3, r5, r3\n",
            "subs r1, r1, r3\n",
        )
    };
}

/// ARMv6-M, after [`thumb1_area`]: a kept triangle to `8f` (cull, bit 0
/// of the mode, in r9), else on from the next (`skip`, the local label
/// stepping r0; `head`, its loop's) or to `9f` at the end (r8).
#[cfg(fixshade_thumb1)]
macro_rules! thumb1_next {
    ($skip:literal, $head:literal) => {
        concat!(
            "beq ",
            $skip,
            "f\n",
            "bmi 8f\n",
            "mov r7, r9\n",
            "lsls r7, r7, #31\n",
            "beq 8f\n",
            $skip,
            ":\n",
            "adds r0, #6\n",
            "cmp r0, r8\n",
            "bne ",
            $head,
            "b\n",
            "b 9f\n",
        )
    };
}

/// A kept triangle as the scan found it ([`skip_culled`]): its doubled
/// area and, where the scan makes it ([`BOX_IN_SCAN`]), the box of its
/// window positions, packed as an entry's first word is (`x` in the low
/// half, `y` in the high), its least and greatest corner.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Found {
    pub(crate) area: i32,
    pub(crate) lo: u32,
    pub(crate) hi: u32,
}

/// Whether [`skip_culled`] gives a kept triangle's box: on ARMv7-M, ten
/// instructions of halfword SIMD (`ssub16` and `sel` for the least and
/// greatest of each half, `sadd16` back from the differences) on the
/// positions the area was made from, where the compiled minima and maxima
/// of six loaded halves were some thirty with their spills.
pub(crate) const BOX_IN_SCAN: bool = cfg!(fixshade_thumb2);

/// The first triangle of `tris` (`[u16; 3]` vertex indices, up to `end`)
/// the whole-frame loop must look at, and its doubled area: one with a
/// corner the rare path takes (flag [`RARE_BIT`] of the entry's word at
/// [`FLAGS_AT`]; its area not found), or one whose kept window positions
/// (an entry's first word: `x` in the low half, `y` in the high) make a
/// doubled area that is neither 0 nor culled (`area > 0` with `cull`);
/// `end` where there is none. In assembly: the cull of a fine mesh's
/// triangles is most of its triangle loop, and compiled, that loop holds
/// a kept triangle's values on the stack across every culled one (M0+:
/// 59 instructions a triangle, M4F: 42). On ARMv7-M the area is two
/// `ssub16` and one `smusdx` of the packed positions (the differences
/// within ±2¹⁵ in the guard band, the products' difference within
/// `i32`): the same value as `(x₁ − x₀)(y₂ − y₀) − (x₂ − x₀)(y₁ − y₀)`.
/// `None` elsewhere: the caller's Rust tests each triangle. Without
/// `rare` (a draw whose every vertex the lean path keeps: the mesh's box
/// is contained, `src/vertex.rs`), the flags are not read: a loop of its
/// own, seven instructions a triangle shorter on ARMv7-M, ten on ARMv6-M
/// (where it also loads by register offset, with no addresses made).
///
/// # Safety
/// `tris ..= end` is one slice's range; every index in it is below the
/// length of the cache at `cache`, whose entries are 16 bytes, the
/// window position first; without `rare`, no entry has the flag.
#[inline(always)]
#[allow(unused_variables)]
pub(crate) unsafe fn skip_culled(
    tris: *const [u16; 3],
    end: *const [u16; 3],
    cache: *const u8,
    cull: bool,
    rare: bool,
) -> Option<(*const [u16; 3], Found)> {
    // Bit 0: cull back faces; bit 1: read the flags.
    let mode = cull as u32 | (rare as u32) << 1;
    #[cfg(fixshade_thumb2)]
    {
        let (at, area, lo, hi): (*const [u16; 3], i32, u32, u32);
        // SAFETY: the caller's contract: each pass reads one triangle's
        // three indices and, for each, its entry's first word and flags
        // word; it stops at `end`.
        unsafe {
            core::arch::asm!(
                thumb2_scan!(
                    "{a}", "{b}", "{c}", "{t}", "{u}", "{area}", "{mode}", "{p}", "{end}", "{base}",
                    "9", "9"
                ),
                "9:",
                p = inout(reg) tris => at,
                end = in(reg) end,
                base = in(reg) cache,
                mode = in(reg) mode,
                flags = const FLAGS_AT,
                rare = const 1u32 << RARE_BIT,
                area = out(reg) area,
                a = out(reg) _,
                b = out(reg) _,
                c = out(reg) _,
                t = out(reg) hi,
                u = out(reg) lo,
                options(readonly, nostack),
            );
        }
        Some((at, Found { area, lo, hi }))
    }
    #[cfg(fixshade_thumb1)]
    {
        let (at, area): (*const [u16; 3], i32);
        // SAFETY: as above. r6 and r7, which `asm!` may not name, are
        // pushed and popped around their use; `end` and `cull` wait in r8
        // and r9.
        unsafe {
            core::arch::asm!(
                "push {{r6, r7}}",
                "mov r8, r1",
                "mov r9, r3",
                "cmp r0, r8",
                "beq 9f",
                // Bit 1 of the mode to the sign: the flags read, or not.
                "lsls r7, r3, #30",
                "bpl 3f",
                "1:",
                thumb1_offsets!(),
                "adds r4, r4, r2",
                "adds r5, r5, r2",
                "adds r6, r6, r2",
                "ldr r7, [r4, #{flags}]",
                "ldr r1, [r5, #{flags}]",
                "orrs r7, r1",
                "ldr r1, [r6, #{flags}]",
                "orrs r7, r1",
                "lsls r7, r7, #{rare_up}",
                "bmi 9f",
                "ldr r7, [r4, #0]",
                "ldr r1, [r5, #0]",
                "ldr r3, [r6, #0]",
                thumb1_area!(),
                thumb1_next!("2", "1"),
                // The same without the flags.
                "3:",
                thumb1_offsets!(),
                "ldr r7, [r4, r2]",
                "ldr r1, [r5, r2]",
                "ldr r3, [r6, r2]",
                thumb1_area!(),
                thumb1_next!("4", "3"),
                "8:",
                "mov r3, r1",
                "9:",
                "pop {{r6, r7}}",
                inout("r0") tris => at,
                inout("r1") end => _,
                in("r2") cache,
                inout("r3") mode => area,
                flags = const FLAGS_AT,
                rare_up = const 31 - RARE_BIT,
                out("r4") _,
                out("r5") _,
                out("r8") _,
                out("r9") _,
                options(readonly),
            );
        }
        Some((at, Found { area, lo: 0, hi: 0 }))
    }
    #[cfg(not(any(fixshade_thumb1, fixshade_thumb2)))]
    {
        None
    }
}

/// The lit-for-the-front-face flag in a cache entry's flags word (the word
/// at [`FLAGS_AT`]), which [`gouraud_run`] tests.
#[cfg_attr(not(fixshade_thumb2), allow(dead_code))]
pub(crate) const FRONT_BIT: u32 = 20;

/// Whether the whole-frame loop of a cached Gouraud draw into stores that
/// hold its rect runs [`gouraud_run`]: on ARMv7-M, where the one-routine
/// set-up ([`GOURAUD_SET_UP`]) is.
pub(crate) const GOURAUD_RUN: bool = GOURAUD_SET_UP;

/// A corner's lighting for [`gouraud_run`]: `(frame, stats, entry,
/// vertex)` → not 0 where the entry now holds the front face's colour.
pub(crate) type LightCorner = unsafe extern "C" fn(*const (), *mut (), *mut u8, u32) -> u32;

/// What [`gouraud_run`] reads and writes. `repr(C)`: the assembly reads
/// it at its offsets (`set_up` 0, `rect` 48, `cbase` 64, `zbase` 68,
/// `frame` 72, `stats` 76, `light` 80, `mode` 84, `area` 88, `lo` 92,
/// `hi` 96, `drawn` 100, `pixels` 104).
#[repr(C)]
pub(crate) struct GouraudRun {
    /// The set-up's arguments: its constants (`nodes`, `planes`,
    /// `table`, `stride`) set by the caller, the rest by the loop.
    pub(crate) set_up: GouraudSetUp,
    /// The draw's rect: `c0`, `c1`, `r0`, `r1`.
    pub(crate) rect: [i32; 4],
    /// Column 0 of row 0 (the set-up's origin's) in the colour and the
    /// depth store.
    pub(crate) cbase: *mut u16,
    pub(crate) zbase: *mut u16,
    /// What `light` is given with a corner.
    pub(crate) frame: *const (),
    pub(crate) stats: *mut (),
    pub(crate) light: LightCorner,
    /// Bit 0: cull back faces; bit 1: read the rare path's flags; bit 2:
    /// light back faces for their side.
    pub(crate) mode: u32,
    /// The triangle the loop stopped at: its [`Found`].
    pub(crate) area: i32,
    pub(crate) lo: u32,
    pub(crate) hi: u32,
    /// Triangles set up and pixels written by the loop (the pixels
    /// saturating).
    pub(crate) drawn: u32,
    pub(crate) pixels: u32,
}

/// ARMv7-M, [`gouraud_run`]: corner `k`'s lighting (its entry at
/// `run.set_up.entries[k]`, its index at byte `index` of the triangle)
/// where the entry is not lit for the front face; to the caller where it
/// cannot be.
#[cfg(fixshade_thumb2)]
macro_rules! thumb2_light_corner {
    ($k:literal, $index:literal, $lit:literal) => {
        concat!(
            "ldr r2, [r9, #",
            $k,
            "]\n",
            "ldr r1, [r2, #{flags}]\n",
            "tst r1, #{front}\n",
            "bne ",
            $lit,
            "f\n",
            "ldrh r3, [r4, #",
            $index,
            "]\n",
            "ldrd r0, r1, [r9, #72]\n",
            "ldr r12, [r9, #80]\n",
            "blx r12\n",
            "cmp r0, #0\n",
            "beq 97f\n",
            $lit,
            ":\n",
        )
    };
}

/// ARMv7-M, [`gouraud_run`]'s test of a box of at most 2 × 2 samples:
/// edge `p → q` (the corners' positions at sp + `off` and the word after)
/// at the four samples (the first's position at sp + 16, the column and
/// row steps at sp + 20 and 24): `f = dx·(s.y − p.y) − dy·(s.x − p.x)`
/// less 1 where the edge is neither top nor left (`(dy << 16) − dx ≥ 0`),
/// by `smlsdx` of the packed differences, then its steps `−16·dy` and
/// `16·dx` by `smusdx`; or-ed into r0–r3.
#[cfg(fixshade_thumb2)]
#[rustfmt::skip]
macro_rules! thumb2_sample_edge {
    ($off:literal) => {
        concat!(
            "ldrd r12, lr, [sp, #", $off, "]\n",
            "ssub16 lr, lr, r12\n",
            "sxth r6, lr\n",
            "asr r7, lr, #16\n",
            "rsb r7, r6, r7, lsl #16\n",
            "mvn r11, r7, asr #31\n",
            "ldr r6, [sp, #16]\n",
            "ssub16 r6, r6, r12\n",
            "smlsdx r6, lr, r6, r11\n",
            "orr r0, r0, r6\n",
            "ldr r7, [sp, #20]\n",
            "smusdx r7, lr, r7\n",
            "add r7, r6, r7\n",
            "orr r1, r1, r7\n",
            "ldr r12, [sp, #24]\n",
            "smusdx r12, lr, r12\n",
            "add r6, r6, r12\n",
            "orr r2, r2, r6\n",
            "add r7, r7, r12\n",
            "orr r3, r3, r7\n",
        )
    };
}

// ARMv7-M: `gouraud_run`'s loop, a routine of the procedure call
// standard (`r0` the `GouraudRun`, `r1` the first triangle, `r2` the
// end, `r3` the cache; the triangle it stops at returned in `r0`; r4–r11
// kept), so that it may call `run.light`, compiled code. Its state in
// r4 (the triangle), r5 (the end), r8 (the cache), r9 (the run), r10
// (the mode), which its calls keep; a scratch of 36 bytes on the stack
// (32 used; sp 8-byte aligned at the calls).
#[cfg(fixshade_thumb2)]
core::arch::global_asm!(
    ".section .text.fixshade_gouraud_run,\"ax\",%progbits",
    ".global fixshade_gouraud_run",
    ".type fixshade_gouraud_run, %function",
    ".p2align 2",
    ".thumb_func",
    "fixshade_gouraud_run:",
    "push {{r4, r5, r6, r7, r8, r9, r10, r11, lr}}",
    "sub sp, #36",
    "mov r9, r0",
    "mov r4, r1",
    "mov r5, r2",
    "mov r8, r3",
    "ldr r10, [r9, #84]",
    // The scan; a kept triangle's box (hi r3, lo r12), kept for the
    // caller.
    thumb2_scan!("r0", "r1", "r2", "r3", "r12", "r11", "r10", "r4", "r5", "r8", "97", "99"),
    "str r11, [r9, #88]",
    "strd r12, r3, [r9, #92]",
    // Rows r6 ..= r7 (`Samples::of_box`); none: the next.
    "ldrd r0, r1, [r9, #56]",
    "asr r6, r12, #16",
    "add r6, r6, #7",
    "asr r6, r6, #4",
    "cmp r6, r0",
    "it lt",
    "movlt r6, r0",
    "asr r7, r3, #16",
    "sub r7, r7, #9",
    "asr r7, r7, #4",
    "cmp r7, r1",
    "it gt",
    "movgt r7, r1",
    "cmp r6, r7",
    "bgt 6f",
    // Columns: past the rect's, to the caller (a clamp); none,
    // the next.
    "ldrd r2, lr, [r9, #48]",
    "sxth r0, r12",
    "add r0, r0, #7",
    "asr r0, r0, #4",
    "sxth r1, r3",
    "sub r1, r1, #8",
    "asr r1, r1, #4",
    "cmp r0, r2",
    "blt 97f",
    "cmp r1, lr",
    "bgt 97f",
    "subs r1, r1, r0",
    "blt 6f",
    // At most 2 × 2 samples: none covered (`covers_none`), the
    // next. The samples' edge functions (`EdgeFunctions`, its
    // corners b and c swapped for a negative area) or-ed per
    // sample (r0–r3: the first, a column on, a row on, both),
    // from the corners B, C, A, B, the first sample and the
    // steps to the others at sp.
    "cmp r1, #1",
    "bgt 5f",
    "sub r2, r7, r6",
    "cmp r2, #1",
    "bgt 5f",
    "lsl r1, r1, #4",
    "lsl r2, r2, #20",
    "strd r1, r2, [sp, #20]",
    "lsl r0, r0, #4",
    "add r0, r0, #8",
    "lsl r1, r6, #4",
    "add r1, r1, #8",
    "pkhbt r0, r0, r1, lsl #16",
    "str r0, [sp, #16]",
    "strd r6, r7, [r9, #16]",
    thumb2_entries!("r0", "r1", "r2", "r4", "r8"),
    "ldr r0, [r0]",
    "ldr r1, [r1]",
    "ldr r2, [r2]",
    "cmp r11, #0",
    "bge 31f",
    "mov r3, r1",
    "mov r1, r2",
    "mov r2, r3",
    "31:",
    "strd r1, r2, [sp]",
    "strd r0, r1, [sp, #8]",
    "movs r0, #0",
    "movs r1, #0",
    "movs r2, #0",
    "movs r3, #0",
    thumb2_sample_edge!("0"),
    thumb2_sample_edge!("4"),
    thumb2_sample_edge!("8"),
    "and r0, r0, r1",
    "and r2, r2, r3",
    "ldrd r6, r7, [r9, #16]",
    "ldrd r12, r3, [r9, #92]",
    "ldr r11, [r9, #88]",
    "ands r0, r0, r2",
    "bmi 6f",
    "5:",
    // A facing snapping may have turned (`snap_may_flip`):
    // 2|a| ≤ p + p/8 + 3, p = 2(width + height).
    "ssub16 r0, r3, r12",
    "sxth r1, r0",
    "add r1, r1, r0, asr #16",
    "lsl r1, r1, #1",
    "add r1, r1, r1, lsr #3",
    "add r1, r1, #3",
    "eor r2, r11, r11, asr #31",
    "sub r2, r2, r11, asr #31",
    "cmp r1, r2, lsl #1",
    "bhs 97f",
    // A back face lit for its side: to the caller.
    "cmp r11, #0",
    "ble 7f",
    "tst r10, #4",
    "bne 97f",
    "7:",
    // The set-up's arguments; its corners lit (`run.light`,
    // as `Frame::gouraud_in_one` lights them: in order, to the
    // caller at one that keeps the back face's colour).
    thumb2_entries!("r0", "r1", "r2", "r4", "r8"),
    "stm r9, {{r0, r1, r2}}",
    "str r11, [r9, #12]",
    "strd r6, r7, [r9, #16]",
    "ldr r0, [r0, #{flags}]",
    "ldr r1, [r1, #{flags}]",
    "ands r0, r1",
    "ldr r2, [r2, #{flags}]",
    "ands r0, r2",
    "tst r0, #{front}",
    "bne 20f",
    thumb2_light_corner!("0", "0", "11"),
    thumb2_light_corner!("4", "2", "12"),
    thumb2_light_corner!("8", "4", "13"),
    "20:",
    // The stores' bases at the first row; set up and drawn, or
    // to the caller.
    "ldrd r0, r1, [r9, #64]",
    "ldr r2, [r9, #40]",
    "mla r0, r6, r2, r0",
    "mla r1, r6, r2, r1",
    "str r0, [r9, #36]",
    "str r1, [r9, #44]",
    "mov r0, r9",
    "bl fixshade_gouraud_set_up",
    "cmp r0, #0",
    "blt 97f",
    "ldrd r1, r2, [r9, #100]",
    "add r1, r1, #1",
    "adds r2, r2, r0",
    "it cs",
    "mvncs r2, #0",
    "strd r1, r2, [r9, #100]",
    // The next triangle, in the loop of the mode.
    "6:",
    "adds r4, #6",
    "cmp r4, r5",
    "beq 99f",
    "tst r10, #2",
    "bne 1b",
    "b 3b",
    "97:",
    "99:",
    "mov r0, r4",
    "add sp, #36",
    "pop {{r4, r5, r6, r7, r8, r9, r10, r11, pc}}",
    ".size fixshade_gouraud_run, . - fixshade_gouraud_run",
    flags = const FLAGS_AT,
    rare = const 1u32 << RARE_BIT,
    front = const 1u32 << FRONT_BIT,
);

#[cfg(fixshade_thumb2)]
extern "C" {
    /// [`gouraud_run`]'s loop (the `global_asm!` above).
    fn fixshade_gouraud_run(
        run: *mut GouraudRun,
        tris: *const [u16; 3],
        end: *const [u16; 3],
        cache: *mut u8,
    ) -> *const [u16; 3];
}

/// The whole-frame loop of a cached Gouraud draw, from triangle `tris`
/// to `end`, for the triangles the lean path takes whole: [`skip_culled`]'s
/// scan, then for each kept triangle the tests of `Frame::triangle`
/// (`src/triangle.rs`) and `Frame::whole` (`src/shade.rs`), its corners
/// lit (`run.light`), and [`gouraud_set_up`]'s routine setting it up and
/// drawing its rows. Returns the first triangle it leaves to the caller
/// (`run.area`, `lo`, `hi` its [`Found`]): one with a rare corner, a box
/// of more than 2 × 2 samples whose facing snapping may have turned or of
/// at most 2 × 2 covering one (snapping tested the same way), a back face
/// lit for its side, columns past the rect's, a corner that keeps the
/// back face's colour, or one the routine leaves (more than 32 rows, a
/// steep plane); `end` where there is none. The triangles it skips are
/// those the caller's tests skip (culled, of no area, with no sample).
///
/// # Safety
/// [`skip_culled`]'s contract, the cache writable; `run.set_up`'s
/// constants as [`gouraud_set_up`] asks, `run.cbase` and `run.zbase` as
/// its stores ask for every row of `run.rect` (`Out::row_stores`), and
/// `run.light` safe to call with `run.frame`, `run.stats`, an entry of
/// the cache and its vertex's index.
#[allow(unused_variables)]
pub(crate) unsafe fn gouraud_run(
    run: &mut GouraudRun,
    tris: *const [u16; 3],
    end: *const [u16; 3],
    cache: *mut u8,
) -> *const [u16; 3] {
    #[cfg(fixshade_thumb2)]
    {
        // SAFETY: the caller's contract.
        unsafe { fixshade_gouraud_run(run, tris, end, cache) }
    }
    #[cfg(not(fixshade_thumb2))]
    {
        end
    }
}

/// An optimisation barrier that emits no instruction, for the body of a
/// loop that LLVM must not runtime-unroll.
///
/// LLVM does not runtime-unroll a loop that holds an assembly statement,
/// and this is an empty one. A span's pixel loop steps four planes and
/// two pointers; unrolled, it needs more registers than a Cortex-M has and
/// spills its planes to the stack in every iteration.
#[inline(always)]
pub(crate) fn keep_loop_rolled() {
    core::hint::black_box(());
}

#[cfg(test)]
mod tests {
    /// The halving steps count as the instruction does: zero, every power
    /// of two and its neighbours, and a sweep of other values; so does the
    /// one step of `W`'s range, within it.
    #[test]
    fn leading_zeros_forms_agree() {
        let mut xs = vec![0u32, 1, u32::MAX];
        for k in 0..32 {
            xs.extend([1u32 << k, (1u32 << k).wrapping_sub(1), (1u32 << k) | 1]);
        }
        xs.extend((0..100_000u32).map(|i| i.wrapping_mul(0x9E37_79B9) >> (i % 32)));
        for x in xs {
            assert_eq!(super::leading_zeros_halving(x), x.leading_zeros(), "{x:#x}");
            if (1 << 22..1 << 31).contains(&x) {
                assert_eq!(
                    super::leading_zeros_of_w_step(x),
                    x.leading_zeros(),
                    "{x:#x}"
                );
            }
        }
    }
}
