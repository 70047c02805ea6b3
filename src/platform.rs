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

use crate::walk::Planes;

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

/// A Gouraud span through the depth test, written in place: `row` and
/// `zrow` the span's pixels and stored depths (the same length), on the
/// depth and colour `planes` (`[z, r, g, b]`, `src/walk.rs`) from column
/// `x0`, `dy` rows below their first; returns the pixels written. Each
/// pixel's depth is `clamp(z >> 12, 0, 65535)`; it is written, with its
/// colour ([`pack_planes`]), where that is below the stored one.
///
/// On Cortex-M cores the span's start (`at + gx·x0 + gy·dy`, wrapping) and
/// loop are assembly: on ARMv7-M (and ARMv8-M Mainline) 17 instructions a
/// written pixel (`usat` clamps, the colour in five), on ARMv6-M 22 (a
/// depth above 65535 fails the unsigned comparison as its clamp would, a
/// negative one becomes 0). In Rust, LLVM keeps the four planes, their
/// steps and two pointers in too few registers and reloads steps from the
/// stack at every pixel (24 and 41 instructions). The frame pointer `r7`
/// and `r6`, which `asm!` may not name, are saved and used. Elsewhere the
/// loop in Rust, the same values.
#[inline(always)]
pub(crate) fn gouraud_depth(
    row: &mut [u16],
    zrow: &mut [u16],
    planes: &Planes<4>,
    x0: i32,
    dy: i32,
) -> u32 {
    let n = row.len().min(zrow.len());
    if n == 0 {
        return 0;
    }
    #[cfg(fixshade_thumb2)]
    {
        let failed: u32;
        // SAFETY: `row` and `zrow` hold `n ≥ 1` pixels each, and the loop
        // reads and writes exactly those; `planes` is twelve words
        // (`repr(C)`). r6 and r7 are pushed and popped around their use; sp
        // is restored.
        unsafe {
            core::arch::asm!(
                "push {{r6, r7}}",
                "ldr r7, [r3, #16]",
                "ldr r8, [r3, #20]",
                "ldr r9, [r3, #24]",
                "ldr r10, [r3, #28]",
                "ldr r6, [r3, #12]",
                "mla r6, r10, r4, r6",
                "ldr r11, [r3, #44]",
                "mla r6, r11, r5, r6",
                "ldr r12, [r3]",
                "mla r12, r7, r4, r12",
                "ldr r11, [r3, #32]",
                "mla r12, r11, r5, r12",
                "ldr lr, [r3, #4]",
                "mla lr, r8, r4, lr",
                "ldr r11, [r3, #36]",
                "mla lr, r11, r5, lr",
                "ldr r11, [r3, #40]",
                "mul r11, r11, r5",
                "mla r5, r9, r4, r11",
                "ldr r11, [r3, #8]",
                "add r5, r11",
                "mov r4, lr",
                "mov r3, r12",
                "movs r11, #0",
                "2:",
                "ldrh r12, [r0]",
                "usat lr, #16, r3, asr #12",
                "cmp lr, r12",
                "bhs 4f",
                "strh lr, [r0], #2",
                "lsrs r12, r5, #20",
                "lsrs lr, r4, #20",
                "orr lr, r12, lr, lsl #6",
                "lsrs r12, r6, #20",
                "orr lr, r12, lr, lsl #5",
                "strh lr, [r1], #2",
                "3:",
                "add r3, r7",
                "add r4, r8",
                "add r5, r9",
                "add r6, r10",
                "subs r2, #1",
                "bne 2b",
                "b 5f",
                "4:",
                "adds r0, #2",
                "adds r1, #2",
                "adds r11, #1",
                "b 3b",
                "5:",
                "pop {{r6, r7}}",
                inout("r0") zrow.as_mut_ptr() => _,
                inout("r1") row.as_mut_ptr() => _,
                inout("r2") n => _,
                inout("r3") planes as *const Planes<4> => _,
                inout("r4") x0 => _,
                inout("r5") dy => _,
                out("r8") _,
                out("r9") _,
                out("r10") _,
                out("r11") failed,
                out("r12") _,
                out("lr") _,
            );
        }
        n as u32 - failed
    }
    #[cfg(fixshade_thumb1)]
    {
        let failed: u32;
        // SAFETY: as above; r12 holds the row's end, lr the failures.
        unsafe {
            core::arch::asm!(
                "push {{r6, r7}}",
                "lsls r5, r5, #1",
                "adds r5, r5, r1",
                "mov r12, r5",
                "ldr r6, [r2, #16]",
                "mov r8, r6",
                "ldr r6, [r2, #20]",
                "mov r9, r6",
                "ldr r6, [r2, #24]",
                "mov r10, r6",
                "ldr r6, [r2, #28]",
                "mov r11, r6",
                "ldr r5, [r2, #28]",
                "muls r5, r3, r5",
                "ldr r6, [r2, #44]",
                "muls r6, r4, r6",
                "adds r5, r5, r6",
                "ldr r6, [r2, #12]",
                "adds r5, r5, r6",
                "ldr r7, [r2, #24]",
                "muls r7, r3, r7",
                "ldr r6, [r2, #40]",
                "muls r6, r4, r6",
                "adds r7, r7, r6",
                "ldr r6, [r2, #8]",
                "adds r7, r7, r6",
                "ldr r6, [r2, #32]",
                "muls r6, r4, r6",
                "mov lr, r6",
                "ldr r6, [r2, #16]",
                "muls r6, r3, r6",
                "add r6, lr",
                "mov lr, r6",
                "ldr r6, [r2]",
                "add r6, lr",
                "mov lr, r6",
                "ldr r6, [r2, #36]",
                "muls r6, r4, r6",
                "ldr r4, [r2, #20]",
                "muls r4, r3, r4",
                "adds r4, r4, r6",
                "ldr r6, [r2, #4]",
                "adds r3, r4, r6",
                "mov r4, r7",
                "mov r2, lr",
                "movs r6, #0",
                "mov lr, r6",
                "2:",
                "ldrh r6, [r0]",
                "asrs r7, r2, #12",
                "bmi 6f",
                "7:",
                "cmp r7, r6",
                "bhs 4f",
                "strh r7, [r0]",
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
                "adds r0, #2",
                "adds r1, #2",
                "cmp r1, r12",
                "bne 2b",
                "b 5f",
                "4:",
                "mov r6, lr",
                "adds r6, #1",
                "mov lr, r6",
                "b 3b",
                "6:",
                "movs r7, #0",
                "b 7b",
                "5:",
                "mov r2, lr",
                "pop {{r6, r7}}",
                inout("r0") zrow.as_mut_ptr() => _,
                inout("r1") row.as_mut_ptr() => _,
                inout("r2") planes as *const Planes<4> => failed,
                inout("r3") x0 => _,
                inout("r4") dy => _,
                inout("r5") n => _,
                out("r8") _,
                out("r9") _,
                out("r10") _,
                out("r11") _,
                out("r12") _,
                out("lr") _,
            );
        }
        n as u32 - failed
    }
    #[cfg(not(any(fixshade_thumb1, fixshade_thumb2)))]
    {
        let p = planes;
        let mut a: [i32; 4] = core::array::from_fn(|k| {
            p.at[k]
                .wrapping_add(p.gx[k].wrapping_mul(x0))
                .wrapping_add(p.gy[k].wrapping_mul(dy))
        });
        let mut written = 0;
        for (px, z) in row[..n].iter_mut().zip(&mut zrow[..n]) {
            let d16 = (a[0] >> 12).clamp(0, 0xFFFF);
            if d16 < *z as i32 {
                *z = d16 as u16;
                *px = pack_planes(a[1], a[2], a[3]);
                written += 1;
            }
            for (v, s) in a.iter_mut().zip(&p.gx) {
                *v = v.wrapping_add(*s);
            }
        }
        written
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
