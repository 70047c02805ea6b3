//! Scenes and comparison helpers shared by the integration tests.
#![allow(dead_code)]

use fixshade::error_measure::{compare, ErrorStats};
use fixshade::reference;
use fixshade::scene_desc::SceneDesc;
use fixshade::scene_kernel::{KernelFrame, KernelScene};

/// Renders `scene` with the kernel and the reference and compares them.
pub fn kernel_vs_reference(scene: &SceneDesc) -> (ErrorStats, KernelFrame) {
    scene.validate().expect("valid scene");
    let k = KernelScene::new(scene)
        .expect("kernel scene")
        .render_frame()
        .expect("kernel render");
    let r = reference::render(scene).expect("reference render");
    (compare(&k.pixels, &k.covered, &r), k)
}

/// The bound of SPEC.md 7 as the issues state it: at most 1 LSB per channel
/// on pixels both cover, coverage mismatches at most 0.1% of covered pixels.
pub fn assert_within_bound(name: &str, e: &ErrorStats) {
    println!("{name}: {e}");
    assert!(e.covered_both > 0, "{name}: nothing covered");
    assert!(
        e.max_error.iter().all(|&m| m <= 1),
        "{name}: max error {:?} LSB",
        e.max_error
    );
    assert!(
        e.coverage_mismatch_share <= 0.001,
        "{name}: coverage mismatches {:.4}%",
        100.0 * e.coverage_mismatch_share
    );
}
