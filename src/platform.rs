//! Every choice the kernel makes by target, in one place.
//!
//! The rest of the crate asks named questions ([`SOFT_MUL64`],
//! [`wide_pointer`], [`armv7m`], [`hardware_div32`], …) and calls named operations
//! ([`pack_565_pair`], [`keep_loop_rolled`]); the `cfg`s on the target, the
//! inline assembly and the optimisation barriers that answer them live
//! here only. Every answer is a constant, so the branch not taken is
//! removed at compile time and each target's code is what it would be with
//! the `cfg` written at the call site.
//!
//! The frames do not depend on any of these choices: each names two forms
//! of the same values (unit tests hold the forms to each other, and CI runs
//! the test suite on the host with `--cfg fixshade_soft_mul64 --cfg
//! fixshade_soft_div64`); only the instructions differ.

/// The core has no 32 × 32 → 64-bit multiply instruction (ARMv6-M: the
/// Cortex-M0 and M0+, the RP2040's core; ARMv8-M Baseline: the Cortex-M23),
/// so a product of two `i64`s is a call to `__aeabi_lmul`, a 64 × 64-bit
/// product of 37 instructions. Where this holds, the wide products are
/// built from 16 × 16 → 32-bit ones (one `muls` each). The build script
/// sets `fixshade_soft_mul64` from the target's name: stable Rust has no
/// `target_feature` for the instruction.
pub(crate) const SOFT_MUL64: bool = cfg!(fixshade_soft_mul64);

/// A 64-bit division is a library call (the build script sets
/// `fixshade_soft_div64` where pointers are narrower than 64 bits): about
/// 330 instructions on a Cortex-M0 and 180 on a Cortex-M4, which divides
/// only 32-bit numbers in hardware. Where this holds, several quotients by
/// one divisor share one reciprocal instead.
pub(crate) const SOFT_DIV64: bool = cfg!(fixshade_soft_div64);

/// The core divides 32-bit numbers in one instruction: every target but
/// ARMv6-M (the Cortex-M0 and M0+), told apart as in [`armv7m`].
#[inline(always)]
pub(crate) const fn hardware_div32() -> bool {
    !cfg!(all(target_arch = "arm", not(target_has_atomic = "32")))
}

/// The target's pointers, and so its general registers, are 64 bits wide:
/// 64-bit multiplies and checked products are single instructions there,
/// and on the 32-bit cores they are library calls or pairs of operations on
/// halves.
#[inline(always)]
pub(crate) const fn wide_pointer() -> bool {
    cfg!(target_pointer_width = "64")
}

/// The target stores integers little-endian, the byte order of the mesh
/// layout: where this holds, a mesh's arrays are read in place as `i16` and
/// `u16` values.
#[inline(always)]
pub(crate) const fn little_endian() -> bool {
    cfg!(target_endian = "little")
}

/// The core is an ARMv7-M one (Cortex-M3, M4, M7): Thumb-2, whose
/// data-processing instructions take repeated-byte masks such as
/// `0xF800F800` as immediates and shift their second operand for free.
/// `target_has_atomic = "32"` is the stable `cfg` that tells an ARMv7-M
/// core from an ARMv6-M one (which has no `ldrex`/`strex`).
#[inline(always)]
pub(crate) const fn armv7m() -> bool {
    cfg!(all(target_arch = "arm", target_has_atomic = "32"))
}

/// `x.leading_zeros()`. ARMv6-M has no count-leading-zeros instruction,
/// and the library's (`__clzsi2`) is a call of about 30 instructions:
/// there, five inline halving steps.
#[inline(always)]
pub(crate) fn leading_zeros(x: u32) -> u32 {
    if cfg!(all(target_arch = "arm", not(target_has_atomic = "32"))) {
        leading_zeros_halving(x)
    } else {
        x.leading_zeros()
    }
}

/// [`leading_zeros`] in halving steps.
#[inline(always)]
fn leading_zeros_halving(x: u32) -> u32 {
    if x == 0 {
        return 32;
    }
    let (mut x, mut n) = (x, 0);
    for k in [16, 8, 4, 2, 1] {
        if x >> (32 - k) == 0 {
            n += k;
            x <<= k;
        }
    }
    n
}

/// `(r & 0xF800F800) | ((g & 0xFC00FC00) >> 5) | ((b & 0xF800F800) >> 11)`:
/// two RGB565 pixels from three words of two 16-bit lanes each (red, green,
/// blue; the low lanes make the low pixel).
///
/// On ARMv7-M five instructions of inline assembly: every mask is an
/// immediate and the shifts ride on the `orr`s. Written in Rust, LLVM
/// rewrites the expression into shift-then-mask, whose masks are not
/// immediates and take two registers in the span loop. Elsewhere the
/// expression in Rust (the same value).
#[inline(always)]
pub(crate) fn pack_565_pair(r: u32, g: u32, b: u32) -> u32 {
    #[cfg(all(target_arch = "arm", target_has_atomic = "32"))]
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
                r = in(reg) r,
                g = in(reg) g,
                b = in(reg) b,
                w = out(reg) w,
                t = out(reg) _,
                options(pure, nomem, nostack, preserves_flags),
            );
        }
        w
    }
    #[cfg(not(all(target_arch = "arm", target_has_atomic = "32")))]
    {
        (r & 0xF800_F800) | ((g >> 5) & 0x07E0_07E0) | ((b >> 11) & 0x001F_001F)
    }
}

/// An optimisation barrier that emits no instruction, for the body of a
/// loop that LLVM must not runtime-unroll.
///
/// LLVM does not runtime-unroll a loop that holds an assembly statement,
/// and this is an empty one. The Gouraud span loop on ARMv7-M steps two
/// pixel pairs per iteration; unrolled further, it needs more registers
/// than the core has and spills its lanes to the stack in every iteration.
/// The barrier keeps it at two pairs.
#[inline(always)]
pub(crate) fn keep_loop_rolled() {
    core::hint::black_box(());
}

#[cfg(test)]
mod tests {
    /// The halving steps count as the instruction does: zero, every power
    /// of two and its neighbours, and a sweep of other values.
    #[test]
    fn leading_zeros_forms_agree() {
        let mut xs = vec![0u32, 1, u32::MAX];
        for k in 0..32 {
            xs.extend([1u32 << k, (1u32 << k).wrapping_sub(1), (1u32 << k) | 1]);
        }
        xs.extend((0..100_000u32).map(|i| i.wrapping_mul(0x9E37_79B9) >> (i % 32)));
        for x in xs {
            assert_eq!(super::leading_zeros_halving(x), x.leading_zeros(), "{x:#x}");
        }
    }
}
