//! Sets `fixshade_soft_mul64` for targets whose cores have no 32 × 32 →
//! 64-bit multiply instruction (ARMv6-M: Cortex-M0 and M0+, the RP2040's
//! core; ARMv8-M Baseline: Cortex-M23). There a product of two `i64` is a
//! call to `__aeabi_lmul` (37 instructions a call in the QEMU count), and
//! [`widening`]'s products of 32-bit operands are built from 16 × 16 →
//! 32-bit ones instead (one `muls` each). Stable Rust has no
//! `target_feature` for this, so the target's name decides, as
//! `cortex-m`'s build script does for `armv6m`.
//!
//! Sets `fixshade_soft_div32` for ARMv6-M, which has no divide
//! instruction: there [`division`]'s shared-divisor floors take a
//! reciprocal instead of a library call.
//!
//! Sets `fixshade_thumb1` (ARMv6-M, ARMv8-M Baseline) or `fixshade_thumb2`
//! (ARMv7-M, ARMv8-M Mainline) for the Cortex-M cores, whose span loops
//! [`platform`] writes in assembly (stable Rust's `cfg` has no
//! `target_feature` that tells them apart).
//!
//! With `FIXSHADE_LIMBS=1` in the environment it sets
//! `fixshade_soft_mul64` and `fixshade_soft_div32` on any target: the
//! Cortex-M0's arithmetic on the host, for the test suite (`.ci/run`). The
//! same as `RUSTFLAGS="--cfg fixshade_soft_mul64 --cfg
//! fixshade_soft_div32"`, but for this crate alone, so that its
//! dependencies are not built again.
//!
//! With `FIXSHADE_EXPLICIT=1` in the environment it sets
//! `fixshade_explicit_draw` (the explicit call, `src/explicit.rs`) for the
//! Cortex-M targets: the firmware's second build (`scripts/firmware.sh`),
//! again for this crate alone and not for the host build of the
//! firmware's build scripts.
//!
//! The kernel reads them only through [`platform`].
//!
//! [`widening`]: src/num/widening.rs
//! [`division`]: src/num/division.rs
//! [`platform`]: src/platform.rs
fn main() {
    println!("cargo:rustc-check-cfg=cfg(fixshade_soft_mul64)");
    println!("cargo:rustc-check-cfg=cfg(fixshade_soft_div32)");
    println!("cargo:rustc-check-cfg=cfg(fixshade_explicit_draw)");
    println!("cargo:rustc-check-cfg=cfg(fixshade_thumb1)");
    println!("cargo:rustc-check-cfg=cfg(fixshade_thumb2)");
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-env-changed=FIXSHADE_LIMBS");
    let limbs = std::env::var("FIXSHADE_LIMBS").is_ok_and(|v| v == "1");
    let target = std::env::var("TARGET").unwrap_or_default();
    let thumb1 = target.starts_with("thumbv6m") || target.starts_with("thumbv8m.base");
    if thumb1 || limbs {
        println!("cargo:rustc-cfg=fixshade_soft_mul64");
    }
    if thumb1 {
        println!("cargo:rustc-cfg=fixshade_thumb1");
    }
    if target.starts_with("thumbv7") || target.starts_with("thumbv8m.main") {
        println!("cargo:rustc-cfg=fixshade_thumb2");
    }
    if target.starts_with("thumbv6m") || limbs {
        println!("cargo:rustc-cfg=fixshade_soft_div32");
    }
    // Read (and so watched) for the Cortex-M targets only: a host build
    // (the firmware's build scripts') stays as it was.
    if target.starts_with("thumb") {
        println!("cargo:rerun-if-env-changed=FIXSHADE_EXPLICIT");
        if std::env::var("FIXSHADE_EXPLICIT").is_ok_and(|v| v == "1") {
            println!("cargo:rustc-cfg=fixshade_explicit_draw");
        }
    }
}
