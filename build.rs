//! Sets `fixshade_soft_mul64` for targets whose cores have no 32 × 32 →
//! 64-bit multiply instruction (ARMv6-M: Cortex-M0 and M0+, the RP2040's
//! core; ARMv8-M Baseline: Cortex-M23). There a product of two `i64` is a
//! call to `__aeabi_lmul` (37 instructions a call in the QEMU count), and
//! [`widening`]'s products of 32-bit operands are built from 16 × 16 →
//! 32-bit ones instead (one `muls` each). Stable Rust has no
//! `target_feature` for this, so the target's name decides, as
//! `cortex-m`'s build script does for `armv6m`.
//!
//! Sets `fixshade_soft_div64` for targets whose pointers are narrower than
//! 64 bits, where a 64-bit division is a library call: there
//! [`division`]'s shared-divisor floors and reciprocals go without one.
//!
//! The kernel reads both only through [`platform`].
//!
//! [`widening`]: src/num/widening.rs
//! [`division`]: src/num/division.rs
//! [`platform`]: src/platform.rs
fn main() {
    println!("cargo:rustc-check-cfg=cfg(fixshade_soft_mul64)");
    println!("cargo:rustc-check-cfg=cfg(fixshade_soft_div64)");
    println!("cargo:rustc-check-cfg=cfg(fixshade_explicit_draw)");
    println!("cargo:rerun-if-changed=build.rs");
    let target = std::env::var("TARGET").unwrap_or_default();
    if target.starts_with("thumbv6m") || target.starts_with("thumbv8m.base") {
        println!("cargo:rustc-cfg=fixshade_soft_mul64");
    }
    let width = std::env::var("CARGO_CFG_TARGET_POINTER_WIDTH").unwrap_or_default();
    if width != "64" {
        println!("cargo:rustc-cfg=fixshade_soft_div64");
    }
}
