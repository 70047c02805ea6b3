//! Criterion benchmarks of the standard scenes : S1–S4 at 320 × 240
//! into a [`Framebuffer`], in every shading mode the scene allows, with the
//! fixed-point kernel and with the f64 reference in the same run, so the
//! ratio fixed/reference reads from one run.
//!
//! A kernel frame is what [`KernelScene::render`] does: clear the colour
//! and depth buffers, then draw. A reference frame is
//! [`fixshade_host::reference::render`], which allocates and fills its own frame.
//!
//! `cargo bench` runs them all; `cargo bench -- S1/` only S1.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use std::hint::black_box;
use std::time::Duration;

use fixshade::framebuffer::Framebuffer;
use fixshade::render::CachedVertex;
use fixshade_host::scene_desc::{SceneDesc, Shading};
use fixshade_host::scene_kernel::KernelScene;
use fixshade_host::standard_scenes;

/// The shading modes a standard scene allows: S2 is defined by per-vertex
/// colours interpolated (Gouraud), so flat and Phong have no meaning there.
fn modes(name: &str) -> &'static [Shading] {
    match name {
        "S2" => &[Shading::Gouraud],
        _ => &[Shading::Flat, Shading::Gouraud, Shading::Phong],
    }
}

fn mode_name(s: Shading) -> &'static str {
    match s {
        Shading::Flat => "flat",
        Shading::Gouraud => "gouraud",
        Shading::Phong => "phong",
    }
}

fn bench_scenes(c: &mut Criterion) {
    for (name, base) in standard_scenes::all() {
        let mut group = c.benchmark_group(name);
        group
            .sample_size(20)
            .warm_up_time(Duration::from_millis(500))
            .measurement_time(Duration::from_secs(2));
        for &shading in modes(name) {
            let desc = SceneDesc {
                shading,
                ..base.clone()
            };
            let scene = KernelScene::new(&desc).expect("standard scene converts");
            let (w, h) = (desc.width, desc.height);
            let n = w as usize * h as usize;
            let mut pixels = vec![0u16; n];
            let mut depth = vec![0u16; n];
            let mut cache = vec![CachedVertex::default(); desc.mesh.positions.len()];
            group.bench_function(BenchmarkId::new("kernel", mode_name(shading)), |b| {
                b.iter(|| {
                    let mut fb = Framebuffer::new(&mut pixels, w, h).expect("framebuffer");
                    let stats = scene
                        .render_framebuffer(&mut fb, &mut depth, &mut cache)
                        .expect("renders");
                    black_box(stats);
                })
            });
            // The same frame through the generic DrawTarget path (one
            // fill_contiguous per span), to show what the fast path saves.
            group.bench_function(
                BenchmarkId::new("kernel-drawtarget", mode_name(shading)),
                |b| {
                    b.iter(|| {
                        let mut fb = Framebuffer::new(&mut pixels, w, h).expect("framebuffer");
                        let stats = scene
                            .render(&mut fb.canvas(), &mut depth, &mut cache)
                            .expect("renders");
                        black_box(stats);
                    })
                },
            );
            group.bench_function(BenchmarkId::new("reference", mode_name(shading)), |b| {
                b.iter(|| {
                    black_box(fixshade_host::reference::render(black_box(&desc)).expect("renders"))
                })
            });
        }
        group.finish();
    }
}

criterion_group!(benches, bench_scenes);
criterion_main!(benches);
