//! The flash mesh format (`fixshade::mesh`) and its host converter
//! (`fixshade_host::mesh_convert`): positions within the stated quantisation
//! bound after a round trip through the bytes, octahedral normals within
//! the stated angle, the byte loader refusing every kind of bad input
//! with an error (never a panic), the box folded into the matrix within
//! its stated error, vertex normals from quantised positions, and the
//! converter's Rust source compiling (a checked-in file, compared with
//! what the converter writes today).

use fixshade::include_mesh;
use fixshade::mesh::{vertex_normals, Bounds, Mesh, MeshError, PackedNormal, HEADER_LEN};
use fixshade::{Mat4, Vec3};
use fixshade_host::generate;
use fixshade_host::mesh_convert::{decode_normal, encode_normal, MeshData};
use fixshade_host::reference;
use fixshade_host::scene_desc::MeshDesc;

// The converter's Rust source for tests/data/tetrahedron.obj, checked in:
// it must compile, and `checked_in_files_are_the_converters_output` holds
// it to what the converter writes.
include!("../data/tetrahedron.rs");

/// xorshift64*, deterministic.
fn rng(seed: u64) -> impl FnMut() -> u64 {
    let mut s = seed;
    move || {
        s ^= s >> 12;
        s ^= s << 25;
        s ^= s >> 27;
        s.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
}

/// A uniform `f64` in [−1, 1).
fn unit(next: &mut impl FnMut() -> u64) -> f64 {
    (next() >> 11) as f64 / (1u64 << 52) as f64 - 1.0
}

/// `bytes` copied to an even (`odd` false) or odd address: a buffer and
/// where in it the copy starts.
fn placed(bytes: &[u8], odd: bool) -> (Vec<u8>, usize) {
    let mut v = vec![0u8; bytes.len() + 1];
    let at = (v.as_ptr() as usize + odd as usize) % 2;
    v[at..at + bytes.len()].copy_from_slice(bytes);
    (v, at)
}

/// Borrows `bytes` from an even address and copies the mesh out.
fn load(bytes: &[u8]) -> Result<MeshData, MeshError> {
    let (v, at) = placed(bytes, false);
    Mesh::from_bytes(&v[at..at + bytes.len()]).map(|m| MeshData::from_mesh(&m))
}

/// The stated quantisation bound on an axis of extent `e` (half a step),
/// with room for the `f64` rounding of the conversion itself.
fn half_step_bound(e: f64) -> f64 {
    (e + 2f64.powi(-24)) / 131070.0 + 2f64.powi(-40) + 1e-12
}

/// Converts, writes bytes, reads them back, and checks every position
/// against the input: within half a step, below `E/65535` where `E >
/// 3·2⁻²⁴`, inside the `I8F24` range; clamped ones (within 3·2⁻²⁴ of ±128)
/// within 2.5·2⁻²⁴. Returns the worst error relative to `E/65535` on
/// axes of extent at least 2⁻¹⁰ (where the `2⁻²⁴` terms are negligible).
fn round_trip(what: &str, desc: &MeshDesc) -> f64 {
    let data = MeshData::from_desc(desc).unwrap_or_else(|e| panic!("{what}: {e}"));
    let back = load(&data.to_bytes()).unwrap_or_else(|e| panic!("{what}: {e}"));
    assert_eq!(back, data, "{what}: bytes round trip");
    let extent = [0, 1, 2].map(|k| {
        let (lo, hi) = desc
            .positions
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(p[k]), hi.max(p[k]))
            });
        hi - lo
    });
    let mut worst: f64 = 0.0;
    for (i, (p, q)) in desc.positions.iter().zip(&back.positions).enumerate() {
        let d = back.bounds.position_f64(*q);
        assert!(
            Vec3::from_f64(d).is_ok(),
            "{what}: vertex {i} {d:?} left I8F24"
        );
        for k in 0..3 {
            let err = (d[k] - p[k]).abs();
            let near_end = p[k] > 128.0 - 3.0 * 2f64.powi(-24) || p[k] < -128.0;
            let bound = if near_end {
                half_step_bound(extent[k]).max(2.5 * 2f64.powi(-24))
            } else {
                half_step_bound(extent[k])
            };
            assert!(
                err <= bound,
                "{what}: vertex {i} axis {k}: {err:e} > {bound:e}"
            );
            if extent[k] > 3.0 * 2f64.powi(-24) && !near_end {
                assert!(err <= extent[k] / 65535.0, "{what}: vertex {i} axis {k}");
                if extent[k] >= 2f64.powi(-10) {
                    worst = worst.max(err / (extent[k] / 65535.0));
                }
            }
        }
    }
    worst
}

#[test]
fn obj_and_generators_round_trip_within_the_bound() {
    let bunny = MeshData::from_obj_file("tests/data/bunny.obj").expect("bunny");
    let desc = generate::read_obj(|| {
        std::fs::File::open("tests/data/bunny.obj").map(std::io::BufReader::new)
    })
    .expect("bunny");
    assert_eq!(MeshData::from_desc(&desc).unwrap(), bunny);
    let mut worst = round_trip("bunny.obj", &desc);
    for (what, d) in [
        ("sphere", generate::sphere(48, 24, 1.0)),
        ("big sphere", generate::sphere(192, 96, 100.0)),
        ("torus", generate::torus(1.0, 0.25, 64, 32)),
        ("plane", generate::plane(3.0, 16)),
        ("cube", generate::cube(250.0)),
    ] {
        worst = worst.max(round_trip(what, &d));
    }
    // Random clouds at every scale, offset anywhere, and clouds touching
    // the ends of I8F24 (where the box is clamped into the range).
    let mut next = rng(0x9e37_79b9_7f4a_7c15);
    for case in 0..300 {
        let scale = 2f64.powi(-(case % 30)) * 100.0;
        let centre = [0, 1, 2].map(|_| unit(&mut next) * (127.0 - scale).max(0.0));
        let mut positions: Vec<[f64; 3]> = (0..50)
            .map(|_| [0, 1, 2].map(|k| centre[k] + scale * unit(&mut next)))
            .collect();
        if case % 7 == 0 {
            let top = 128.0 - 2f64.powi(-25) - 2f64.powi(-44); // rounds below 128
            positions.push([-128.0, top, top]);
            positions.push([top, -128.0, 127.999]);
        }
        let d = MeshDesc {
            positions,
            normals: None,
            indices: vec![[0, 1, 2]],
        };
        worst = worst.max(round_trip(&format!("cloud {case}"), &d));
    }
    println!("worst quantisation error: {worst:.4} of E/65535");
    // Half a step is about half of E/65535.
    assert!(worst > 0.45 && worst <= 0.5 + 1e-4, "{worst}");
}

/// The angle between two `f64` vectors (`atan2(|a × b|, a · b)`).
fn angle(a: [f64; 3], b: [f64; 3]) -> f64 {
    let c = [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ];
    let cross = (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt();
    cross.atan2(a[0] * b[0] + a[1] * b[1] + a[2] * b[2])
}

/// Directions: the axes, the octahedron's seams (its equator, where the
/// lower half is folded out, and the planes x = 0 and y = 0 below it,
/// where the fold changes sign), points just off them, and random ones.
fn directions() -> Vec<[f64; 3]> {
    let mut d = Vec::new();
    for k in 0..3 {
        for s in [1.0, -1.0] {
            let mut v = [0.0; 3];
            v[k] = s;
            d.push(v);
        }
    }
    let eps = [0.0, 1e-9, -1e-9, 1e-5, -1e-5];
    for i in 0..4000 {
        let a = std::f64::consts::TAU * i as f64 / 4000.0;
        let e = eps[i % eps.len()];
        let (s, c) = a.sin_cos();
        d.push([c, s, e]); // the equator
        d.push([e, c, -s.abs()]); // x = 0, lower half
        d.push([c, e, -s.abs()]); // y = 0, lower half
        d.push([c, s, -1.0 + e.abs()]); // around −z
    }
    let mut next = rng(0x2545_f491_4f6c_dd1d);
    while d.len() < 1_000_000 {
        let v = [unit(&mut next), unit(&mut next), unit(&mut next)];
        let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        if l > 0.01 && l <= 1.0 {
            d.push(v);
        }
    }
    d
}

#[test]
fn octahedral_normals_within_the_stated_angle() {
    // 3√2/65534: rounding moves the octahedron's point by √6/65534 at
    // most, and the point lies at least 1/√3 from the origin.
    let bound = 3.0 * 2f64.sqrt() / 65534.0;
    let (mut worst, mut worst_int) = (0.0f64, 0.0f64);
    for v in directions() {
        let p = encode_normal(v);
        let a = angle(v, decode_normal(p));
        assert!(a <= bound, "{v:?}: {a:e} rad");
        worst = worst.max(a);
        // The kernel's integer encoder (vertex normals), from the
        // direction scaled to 30 bits.
        let m = v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let iv = v.map(|x| (x / m * (1u32 << 30) as f64).round() as i32);
        let a = angle(v, decode_normal(PackedNormal::from_vector(iv)));
        assert!(a <= bound + 2e-9, "{v:?} as {iv:?}: {a:e} rad");
        worst_int = worst_int.max(a);
        // Every encoded normal is on the octahedron: |x| + |y| + |z| = 32767.
        let o = p.octahedron();
        assert_eq!(o.iter().map(|c| c.abs()).sum::<i32>(), 32767, "{v:?}");
    }
    println!("octahedral angle error: {worst:e} rad (f64 encoder), {worst_int:e} (integer)");
    // The axes are exact.
    for (v, p) in [
        ([1.0, 0.0, 0.0], PackedNormal::X),
        ([0.0, 1.0, 0.0], PackedNormal::Y),
        ([0.0, 0.0, 1.0], PackedNormal::Z),
    ] {
        assert_eq!(encode_normal(v), p);
        assert_eq!(decode_normal(p), v);
        assert_eq!(decode_normal(encode_normal(v.map(|x| -x))), v.map(|x| -x));
    }
    // Every bit pattern decodes without overflow, to at most 2^15 per
    // component and 3·2^15 in all (the bound the renderer's normal
    // transform relies on).
    for u in (i16::MIN..=i16::MAX)
        .step_by(7)
        .chain([i16::MIN + 1, i16::MAX])
    {
        for v in [i16::MIN, i16::MIN + 1, -1, 0, 1, u, i16::MAX] {
            let o = PackedNormal::from_bits(u, v).octahedron();
            assert!(o.iter().all(|c| c.abs() <= 1 << 15), "{u} {v}: {o:?}");
            assert!(o.iter().map(|c| c.abs()).sum::<i32>() <= 3 << 15);
        }
    }
}

/// A valid file, to break.
fn tetrahedron_bytes() -> Vec<u8> {
    include_bytes!("../../../tests/data/tetrahedron.fxm").to_vec()
}

#[test]
fn loader_refuses_bad_input() {
    let good = tetrahedron_bytes();
    assert!(load(&good).is_ok());
    let with = |at: usize, b: &[u8]| {
        let mut v = good.clone();
        v[at..at + b.len()].copy_from_slice(b);
        v
    };
    // Wrong magic, short or empty input.
    assert_eq!(load(b""), Err(MeshError::BadMagic));
    assert_eq!(load(b"FXS"), Err(MeshError::BadMagic));
    assert_eq!(load(&with(0, b"fxsm")), Err(MeshError::BadMagic));
    // Version and flags.
    assert_eq!(
        load(&with(4, &[2, 0])),
        Err(MeshError::UnsupportedVersion(2))
    );
    assert_eq!(load(&with(6, &[3, 0])), Err(MeshError::UnknownFlags(3)));
    assert_eq!(
        load(&with(6, &[0, 0x80])),
        Err(MeshError::UnknownFlags(0x8000))
    );
    // Counts.
    let many = with(8, &65537u32.to_le_bytes());
    assert_eq!(load(&many), Err(MeshError::TooManyVertices(65537)));
    let huge = with(12, &u32::MAX.to_le_bytes());
    let needed = 40 + 4 * 10 + 6 * u32::MAX as u64;
    assert_eq!(
        load(&huge),
        Err(MeshError::Truncated {
            needed,
            len: good.len()
        })
    );
    // Every truncation, header or arrays.
    for len in 0..good.len() {
        let e = load(&good[..len]).unwrap_err();
        let expect = if len < 4 {
            MeshError::BadMagic
        } else if len < HEADER_LEN {
            MeshError::Truncated {
                needed: HEADER_LEN as u64,
                len,
            }
        } else {
            MeshError::Truncated {
                needed: good.len() as u64,
                len,
            }
        };
        assert_eq!(e, expect, "{len} bytes");
    }
    // Trailing bytes; the normals flag cleared (the arrays then do not
    // add up).
    let mut long = good.clone();
    long.extend_from_slice(&[0, 0]);
    let needed = good.len() as u64;
    assert_eq!(
        load(&long),
        Err(MeshError::TrailingBytes {
            needed,
            len: needed as usize + 2
        })
    );
    assert_eq!(
        load(&with(6, &[0, 0])),
        Err(MeshError::TrailingBytes {
            needed: needed - 16,
            len: good.len()
        })
    );
    // Misaligned: the same bytes at an odd address.
    let (v, at) = placed(&good, true);
    assert_eq!(
        Mesh::from_bytes(&v[at..at + good.len()]),
        Err(MeshError::Misaligned)
    );
    // An index out of range (the last triangle's last index).
    let at = good.len() - 2;
    assert_eq!(
        load(&with(at, &4u16.to_le_bytes())),
        Err(MeshError::IndexOutOfRange {
            triangle: 3,
            index: 4
        })
    );
    // Any byte changed to any value: an error or a mesh that validates,
    // never a panic.
    let mut ok = 0;
    for (at, &byte) in good.iter().enumerate() {
        for b in [0u8, 1, 0x7f, 0x80, 0xff, byte ^ 0x10] {
            if let Ok(m) = load(&with(at, &[b])) {
                assert!(m.mesh().validate().is_ok());
                ok += 1;
            }
        }
    }
    assert!(ok > 100, "{ok}");
    // Display: one line each.
    for e in [
        MeshError::BadMagic,
        MeshError::UnsupportedVersion(9),
        MeshError::UnknownFlags(2),
        MeshError::TooManyVertices(70000),
        MeshError::Truncated { needed: 9, len: 1 },
        MeshError::TrailingBytes { needed: 9, len: 10 },
        MeshError::Misaligned,
        MeshError::BigEndianTarget,
    ] {
        let s = e.to_string();
        assert!(!s.is_empty() && !s.contains('\n'), "{e:?}");
    }
}

#[test]
fn checked_in_files_are_the_converters_output() {
    let data = MeshData::from_obj_file("tests/data/tetrahedron.obj").expect("tetrahedron");
    // The Rust source (included at the top of this file, so it compiles).
    assert_eq!(
        data.to_rust("tetrahedron"),
        include_str!("../data/tetrahedron.rs"),
        "regenerate: cargo run -p fixshade-host --bin fixshade-convert -- host/tests/data/tetrahedron.obj host/tests/data/tetrahedron.rs"
    );
    assert_eq!(TETRAHEDRON, data.mesh());
    assert_eq!(TETRAHEDRON_POSITIONS.len(), 4);
    // The bytes, through include_mesh!.
    assert_eq!(
        data.to_bytes(),
        include_bytes!("../../../tests/data/tetrahedron.fxm"),
        "regenerate: cargo run -p fixshade-host --bin fixshade-convert -- host/tests/data/tetrahedron.obj tests/data/tetrahedron.fxm"
    );
    let included = include_mesh!("../../../tests/data/tetrahedron.fxm").expect("valid");
    assert_eq!(included, TETRAHEDRON);
    // The statics are `const`-built and borrowable for 'static.
    static AGAIN: Mesh<'static> = Mesh::new(
        &TETRAHEDRON_POSITIONS,
        TETRAHEDRON.bounds,
        &TETRAHEDRON_INDICES,
    );
    assert_eq!(AGAIN.normals, None);
    assert!(AGAIN.validate().is_ok());
}

#[test]
fn box_folded_into_the_matrix_within_its_stated_error() {
    let mut next = rng(0x1234_5678_9abc_def1);
    let mut worst = 0.0f64;
    let mut checked = 0;
    for _ in 0..20_000 {
        // Matrices and boxes whose images stay inside I8F24 (entries
        // below 2, offsets below 4, half-extents below 4: every eye
        // coordinate below 3·2·8 + 2 = 50): no clamp.
        let mut m = Mat4::IDENTITY;
        for row in m.m[..3].iter_mut() {
            for x in row.iter_mut() {
                *x = (next() as i32) >> 6;
            }
        }
        let b = Bounds::from_bits(
            [0; 3].map(|_: i32| (next() as i32) >> 5),
            [0; 3].map(|_: u32| (next() as u32) >> 6),
        );
        let q = [0; 3].map(|_: i16| next() as i16);
        let got = b.fold(&m).transform_quantised(q).to_bits();
        for (row, got) in m.m.iter().zip(got) {
            // The exact eye coordinate, in units of 2^-24 · 2^-39.
            let exact: i128 = (0..3)
                .map(|c| {
                    row[c] as i128
                        * (b.offset[c] as i128 * 32768 + b.scale[c] as i128 * q[c] as i128)
                })
                .sum::<i128>()
                + ((row[3] as i128) << 39);
            let exact = exact as f64 / 2f64.powi(39);
            let err = (got as f64 - exact).abs();
            assert!(err <= 2.5, "{m:?} {b:?} {q:?}: {err} raw units");
            worst = worst.max(err);
            checked += 1;
        }
    }
    println!("box fold: worst {worst:.3} raw units (bound 2.5) over {checked} coordinates");
    assert!(worst > 1.0);
}

#[test]
fn vertex_normals_from_quantised_positions() {
    // A sphere, and the same stretched 40 times along x (the box's scale
    // differs per axis: the faces' object-space normals must account for
    // it). Kernel vertex normals against the f64 reference's, on the same
    // (dequantised) positions.
    for stretch in [1.0, 40.0, 1.0 / 40.0] {
        let mut d = generate::sphere(24, 12, 2.0);
        d.normals = None;
        for p in &mut d.positions {
            p[0] *= stretch;
        }
        let mut data = MeshData::from_desc(&d).expect("sphere");
        data.derive_normals().expect("normals");
        let want = reference::vertex_normals(&data.to_desc());
        let got = data.normals.as_ref().unwrap();
        let mut worst = 0.0f64;
        for (i, (w, g)) in want.iter().zip(got).enumerate() {
            if *w == [0.0; 3] {
                assert_eq!(*g, PackedNormal::ZERO, "vertex {i}");
                continue;
            }
            let a = angle(*w, decode_normal(*g));
            worst = worst.max(a);
            assert!(a < 3e-4, "stretch {stretch}, vertex {i}: {a:e} rad");
        }
        println!("vertex normals, stretch {stretch}: worst {worst:e} rad");
    }
    // Buffers and indices are checked; `normals` is ignored.
    let p = [[0i16; 3]; 2];
    let mesh = Mesh::new(&p, Bounds::UNIT, &[[0, 1, 1]]);
    let (mut sums, mut out) = ([[0; 3]; 2], [PackedNormal::X; 2]);
    vertex_normals(&mesh, &mut sums, &mut out).unwrap();
    assert_eq!(out, [PackedNormal::ZERO; 2]);
}
