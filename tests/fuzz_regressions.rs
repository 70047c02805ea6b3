//! Inputs of the `render` fuzz target (`fuzz/`) kept as regression tests:
//! each runs through the same decode-and-check function as the fuzzer
//! (`tests/common/fuzz_scene.rs`), which asserts no panic, no write outside
//! the target, the documented errors and agreement of the two draw paths.

#[path = "common/fuzz_scene.rs"]
mod fuzz_scene;

use fuzz_scene::run;

#[test]
fn empty_input() {
    // All zero: a 0 × 0 target, the raw camera of zeros.
    let r = run(&[]);
    assert_eq!(r.drawn, 0);
}

/// Crash 1 (`crash-2e8e7144…`): an area light whose eye-space edge vectors
/// are near the `WidePoint` limit (±2⁶² raw) overflowed `(1 − k)·(u + v)`
/// in `AreaLight::prepare` (src/light.rs), "attempt to multiply with
/// overflow" in debug, a wrapped sample position in release. Fixed: the
/// first sample is computed in `i128` and clamped, the sample walk
/// saturates at the range.
#[test]
fn crash_area_light_huge_edges() {
    const CRASH: [u8; 109] = [
        0x81, 0x01, 0x23, 0x91, 0x6f, 0xff, 0x80, 0x01, 0xff, 0xff, 0xff, 0xff, 0x49, 0xf1, 0x27,
        0xee, 0x00, 0x00, 0x5e, 0x01, 0x01, 0x36, 0xfb, 0xff, 0x46, 0x46, 0x46, 0x63, 0x63, 0x63,
        0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63,
        0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63, 0x63,
        0x63, 0x63, 0x63, 0x46, 0x46, 0x46, 0x02, 0x01, 0xda, 0xda, 0x00, 0x00, 0x00, 0x00, 0x91,
        0xda, 0xda, 0xda, 0xda, 0xda, 0xff, 0xf1, 0x46, 0x46, 0x46, 0x46, 0x46, 0x46, 0x46, 0x46,
        0x46, 0x46, 0x46, 0xe9, 0x46, 0x46, 0x46, 0x46, 0x46, 0x46, 0x46, 0x46, 0x46, 0x46, 0x46,
        0x46, 0x46, 0x00, 0x3a,
    ];
    let s = fuzz_scene::decode(&CRASH);
    assert!(
        s.lights
            .iter()
            .any(|l| matches!(l, fixshade::light::AnyLight::Area(_))),
        "the input no longer decodes to an area light: {s:?}"
    );
    run(&CRASH);
}

/// The same bug without the decoder: area lights whose centre and edges
/// are at the largest values the float constructor accepts, every k.
#[test]
fn area_light_at_the_range_limit() {
    use fixshade::illumination::LocalViewer;
    use fixshade::light::AreaLight;
    use fixshade::material::BlinnPhong;
    use fixshade::num::WidePoint;
    use fixshade::{Exponent, Lighting, Mat4, Material, Rgb, Unit3, Vec3};
    let big = 2.7e11; // below 2^38
    let m = Material::new().with_specular(BlinnPhong {
        color: Rgb::WHITE,
        shininess: Exponent::from_int(8),
    });
    for k in [1u8, 2, 7, 64] {
        for (c, u, v) in [
            ([big; 3], [big; 3], [big; 3]),
            ([-big; 3], [-big; 3], [-big; 3]),
            ([big, -big, big], [-big, big, big], [big, big, -big]),
            ([0.0, 0.0, 1.0], [big, 0.0, 0.0], [0.0, big, 0.0]),
        ] {
            let light = AreaLight {
                center: WidePoint::from_f64(c).unwrap(),
                edge_u: WidePoint::from_f64(u).unwrap(),
                edge_v: WidePoint::from_f64(v).unwrap(),
                ..AreaLight::new([0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], k).unwrap()
            };
            let l = Lighting::<_, LocalViewer, _>::new(&m, Rgb::BLACK, &light, &Mat4::IDENTITY);
            let shade = l.shade(Vec3::from_f32(0.0, 0.0, -1.0).unwrap(), Unit3::Z);
            // Defined and clamped: some channel value in [0, 1].
            assert!(shade.to_bits().iter().all(|&c| c <= 1 << 16));
        }
    }
}

/// The committed seed corpus (`fuzz/seeds/render`, 24 inputs picked from
/// the fuzzer's corpus across its size range) through the same check.
#[test]
fn seed_corpus() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/fuzz/seeds/render");
    let mut n = 0;
    let mut drew = 0;
    for f in std::fs::read_dir(dir).expect("fuzz/seeds/render") {
        let data = std::fs::read(f.unwrap().path()).unwrap();
        if run(&data).drawn > 0 {
            drew += 1;
        }
        n += 1;
    }
    assert!(n >= 20, "{n} seeds");
    println!("{n} seeds, {drew} drew something");
}
