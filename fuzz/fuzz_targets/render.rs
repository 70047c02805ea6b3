//! Arbitrary bytes rendered as a scene (see `tests/common/fuzz_scene.rs`,
//! shared with `tests/fuzz_regressions.rs`): nothing may panic or
//! overflow, nothing may be written outside the target, errors must be the
//! documented ones.
#![no_main]

use libfuzzer_sys::fuzz_target;

#[path = "../../host/tests/suite/fuzz_scene.rs"]
mod fuzz_scene;

fuzz_target!(|data: &[u8]| {
    let _ = fuzz_scene::run(data);
});
