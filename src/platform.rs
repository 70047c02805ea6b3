//! Every choice the kernel makes by target, in one place.
//!
//! The rest of the crate asks named questions ([`SOFT_MUL64`],
//! [`hardware_div32`], …) and calls named operations ([`pack_planes`],
//! [`keep_loop_rolled`]); the `cfg`s on the target, the
//! inline assembly and the optimisation barriers that answer them live
//! here only. Every answer is a constant, so the branch not taken is
//! removed at compile time and each target's code is what it would be with
//! the `cfg` written at the call site.
//!
//! The frames do not depend on any of these choices: each names two forms
//! of the same values (unit tests hold the forms to each other, and CI runs
//! the test suite on the host with `--cfg fixshade_soft_mul64 --cfg
//! fixshade_soft_div32`); only the instructions differ.

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

/// The target stores integers little-endian, the byte order of the mesh
/// layout: where this holds, a mesh's arrays are read in place as `i16` and
/// `u16` values.
#[inline(always)]
pub(crate) const fn little_endian() -> bool {
    cfg!(target_endian = "little")
}

/// `x.leading_zeros()`. ARMv6-M and ARMv8-M Baseline have no
/// count-leading-zeros instruction (nor a 32 × 32 → 64-bit multiply, whose
/// flag tells them apart), and the library's (`__clzsi2`) is a call of
/// about 30 instructions: there, five inline halving steps.
#[inline(always)]
pub(crate) fn leading_zeros(x: u32) -> u32 {
    if SOFT_MUL64 {
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
    #[cfg(all(target_arch = "arm", target_has_atomic = "32"))]
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
    #[cfg(not(all(target_arch = "arm", target_has_atomic = "32")))]
    {
        let c = |v: i32| (v >> 20) as u32;
        ((c(r) << 11) | (c(g) << 5) | c(b)) as u16
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
