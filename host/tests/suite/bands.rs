//! The band renderer against the whole-frame render: bit for bit, for band
//! heights 1, 7, 16 and the full height, cached and recomputed vertices, on
//! the standard scenes; the frame split between two workers
//! (`Bands::interleaved`, one thread each); and its errors.

use embedded_graphics::draw_target::DrawTarget;
use embedded_graphics::geometry::{OriginDimensions, Size};
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::primitives::Rectangle;
use embedded_graphics::Pixel;
use fixshade::band::Bands;
use fixshade::framebuffer::Framebuffer;
use fixshade::render::{CachedVertex, DrawStats, RenderError};
use fixshade_host::scene_desc::{SceneDesc, Shading};
use fixshade_host::scene_kernel::KernelScene;
use fixshade_host::standard_scenes;

/// A framebuffer that counts `fill_contiguous` calls and checks that each
/// is a full-width band.
struct Counting<'a> {
    fb: Framebuffer<'a>,
    fills: usize,
    rows: u32,
}

impl OriginDimensions for Counting<'_> {
    fn size(&self) -> Size {
        self.fb.size()
    }
}

impl DrawTarget for Counting<'_> {
    type Color = Rgb565;
    type Error = core::convert::Infallible;
    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(
        &mut self,
        _: I,
    ) -> Result<(), Self::Error> {
        panic!("the band renderer only uses fill_contiguous");
    }
    fn fill_contiguous<I: IntoIterator<Item = Rgb565>>(
        &mut self,
        area: &Rectangle,
        colors: I,
    ) -> Result<(), Self::Error> {
        assert_eq!(area.top_left.x, 0);
        assert_eq!(area.size.width, self.fb.size().width);
        assert_eq!(area.top_left.y as u32, self.rows, "bands in order, no gap");
        self.rows += area.size.height;
        self.fills += 1;
        self.fb.canvas().fill_contiguous(area, colors)
    }
}

fn whole(k: &KernelScene) -> (Vec<u16>, DrawStats) {
    let (w, h) = (k.width, k.height);
    let mut px = vec![0u16; (w * h) as usize];
    let mut depth = vec![0u16; (w * h) as usize];
    let mut cache = vec![CachedVertex::default(); k.mesh().positions.len()];
    let mut fb = Framebuffer::new(&mut px, w, h).unwrap();
    let stats = k
        .render_framebuffer(&mut fb, &mut depth, &mut cache)
        .unwrap();
    (px, stats)
}

fn banded(k: &KernelScene, h_band: u32, cached: bool) -> (Vec<u16>, DrawStats) {
    let (w, h) = (k.width, k.height);
    let mut px = vec![0x1234u16; (w * h) as usize];
    let n = (w * h_band) as usize;
    let mut colour = vec![0u16; n];
    let mut depth = vec![0u16; n];
    let mut cache = vec![CachedVertex::default(); k.mesh().positions.len()];
    let mut t = Counting {
        fb: Framebuffer::new(&mut px, w, h).unwrap(),
        fills: 0,
        rows: 0,
    };
    let v = if cached { Some(&mut cache[..]) } else { None };
    let stats = k
        .render_bands(&mut t, h_band, &mut colour, &mut depth, v)
        .unwrap();
    assert_eq!(t.rows, h);
    assert_eq!(t.fills, h.div_ceil(h_band.min(h)) as usize);
    (px, stats)
}

/// The band renders of `d` at heights 1, 7, 16 and the full height,
/// cached and recomputed, against the whole frame; returns the stats of
/// the cached 1-row bands and the whole frame's.
fn check(name: &str, d: &SceneDesc) -> (DrawStats, DrawStats) {
    let k = KernelScene::new(d).unwrap();
    let (reference, all) = whole(&k);
    let mut one_row = DrawStats::default();
    for h in [1, 7, 16, k.height] {
        for cached in [true, false] {
            let (got, stats) = banded(&k, h, cached);
            let diff = got.iter().zip(&reference).filter(|(a, b)| a != b).count();
            assert_eq!(
                diff, 0,
                "{name}: band height {h}, cached {cached}: {diff} pixels differ"
            );
            assert_eq!(
                stats.pixels, all.pixels,
                "{name}: {h} rows, cached {cached}"
            );
            // Every triangle drawn is set up at least once (one that spans
            // several bands, once in each).
            assert!(stats.drawn >= all.drawn, "{name}: {h} rows");
            if cached && h == 1 {
                one_row = stats;
            }
        }
    }
    (one_row, all)
}

#[test]
fn s1_bands_equal_whole_frame() {
    check("S1", &standard_scenes::s1(320, 240));
}

#[test]
fn s2_bands_equal_whole_frame() {
    let (rows, all) = check("S2", &standard_scenes::s2(320, 240));
    // Two triangles, each set up again in every 1-row band: both cover a
    // pixel in each of the 240 rows.
    assert_eq!(all.drawn, 2);
    assert_eq!(rows.drawn, 2 * 240);
}

#[test]
fn s3_bands_equal_whole_frame() {
    let (rows, all) = check("S3", &standard_scenes::s3(320, 240));
    // Triangles crossing row boundaries are set up in each band they
    // cover: more set-ups than triangles drawn.
    assert!(rows.drawn > all.drawn, "{rows:?} {all:?}");
}

#[test]
fn s4_bands_equal_whole_frame() {
    check("S4", &standard_scenes::s4(320, 240));
}

#[test]
fn tiled_targets_equal_whole_frame() {
    // Wider than a tile (2 032 pixels): drawn tile by tile, each with the
    // guard band around its own centre; the quad's two triangles reach
    // into all three tiles and are set up in each (clipped to its band, a
    // triangle may be set up as more than one piece).
    let (_, all) = check("S2 4100 × 40", &standard_scenes::s2(4100, 40));
    assert!(all.drawn >= 2 * 3, "{all:?}");
    assert_eq!(all.pixels, 4100 * 40);
    // The sphere across the boundary of two tiles.
    check("S1 4064 × 40", &standard_scenes::s1(4064, 40));
}

#[test]
fn other_modes_and_sizes_equal_whole_frame() {
    // Flat and Gouraud bunny, Phong sphere, two-sided lighting without
    // culling, dithering, a floor crossing the near plane, odd sizes.
    let mut cases: Vec<(&str, SceneDesc)> = Vec::new();
    for (name, shading) in [
        ("bunny flat", Shading::Flat),
        ("bunny gouraud", Shading::Gouraud),
    ] {
        let mut d = standard_scenes::s4(97, 61);
        d.shading = shading;
        cases.push((name, d));
    }
    let mut d = standard_scenes::s1(64, 200);
    d.shading = Shading::Phong;
    cases.push(("sphere phong", d));
    let mut d = standard_scenes::s1(120, 90);
    d.cull = false;
    d.two_sided = true;
    d.dither = true;
    cases.push(("sphere two-sided dithered", d));
    let mut d = standard_scenes::s1(80, 60);
    d.camera.eye = [0.0, 0.0, 1.05];
    d.camera.near = 0.3;
    let k = KernelScene::new(&d).unwrap();
    assert!(k.render_frame().unwrap().stats.clipped > 0);
    cases.push(("sphere crossing the near plane", d));
    for (name, d) in &cases {
        let k = KernelScene::new(d).unwrap();
        let reference = whole(&k);
        for h in [1, 2, 3, 5, 16, 59, k.height, k.height + 10] {
            for cached in [true, false] {
                assert!(
                    banded(&k, h, cached).0 == reference.0,
                    "{name}: band height {h}, cached {cached}"
                );
            }
        }
    }
}

#[test]
fn too_small_buffers_are_errors() {
    let k = KernelScene::new(&standard_scenes::s1(40, 30)).unwrap();
    let mut px = vec![0u16; 40 * 30];
    let mut fb = Framebuffer::new(&mut px, 40, 30).unwrap();
    let mut fb = fb.canvas();
    let mut cache = vec![CachedVertex::default(); k.mesh().positions.len()];
    let (mut colour, mut depth) = (vec![0u16; 40 * 4], vec![0u16; 40 * 4]);
    let r = k.render_bands(&mut fb, 5, &mut colour, &mut depth, None);
    assert_eq!(r, Err(RenderError::BandTooSmall));
    let r = k.render_bands(&mut fb, 0, &mut colour, &mut depth, None);
    assert_eq!(r, Err(RenderError::BandTooSmall));
    let r = k.render_bands(&mut fb, 4, &mut colour, &mut depth[..159], None);
    assert_eq!(r, Err(RenderError::DepthTooSmall));
    let short = cache.len() - 1;
    let r = k.render_bands(
        &mut fb,
        4,
        &mut colour,
        &mut depth,
        Some(&mut cache[..short]),
    );
    assert_eq!(r, Err(RenderError::CacheTooSmall));
    assert!(px.iter().all(|&p| p == 0), "nothing drawn on an error");
    // An empty target draws nothing and needs nothing.
    let mut none: [u16; 0] = [];
    let mut fb = Framebuffer::new(&mut none, 0, 0).unwrap();
    assert!(k
        .render_bands(&mut fb.canvas(), 1, &mut [], &mut [], None)
        .is_ok());
}

/// The frame of `k` drawn by worker `worker` of `workers` in bands of
/// `h_band` rows (`Bands::interleaved`) into a framebuffer of its own,
/// filled with `fill` first, with its own colour band, depth band and
/// vertex cache; and its counts.
fn worker_frame(
    k: &KernelScene,
    h_band: u32,
    cached: bool,
    (worker, workers): (u32, u32),
    fill: u16,
) -> (Vec<u16>, DrawStats) {
    let (w, h) = (k.width, k.height);
    let mut px = vec![fill; (w * h) as usize];
    let n = (w * h_band) as usize;
    let (mut colour, mut depth) = (vec![0u16; n], vec![0u16; n]);
    let mut cache = vec![CachedVertex::default(); k.mesh().positions.len()];
    let mut fb = Framebuffer::new(&mut px, w, h).unwrap();
    let mut display = fb.canvas();
    let mut bands = Bands::new(&mut display, &mut colour, h_band)
        .with_background(k.background)
        .interleaved(worker, workers);
    let v = cached.then_some(&mut cache[..]);
    let stats = k.render_in_bands(&mut bands, &mut depth, v).unwrap();
    (px, stats)
}

/// Two workers, one thread each, draw the even and the odd bands of the
/// standard scenes (`Bands::interleaved(k, 2)`), each into its own
/// framebuffer with its own colour band, depth band and vertex cache: the
/// frame assembled from each worker's bands is, byte for byte, the
/// single-worker band render and the whole frame; a worker leaves the
/// other's rows alone, their counts add up to the whole frame's, and a
/// worker index at or past the worker count draws nothing.
#[test]
fn interleaved_workers_match_the_whole_frame() {
    let scenes = [
        ("S1", standard_scenes::s1(320, 240)),
        ("S2", standard_scenes::s2(320, 240)),
        ("S3", standard_scenes::s3(320, 240)),
        ("S4", standard_scenes::s4(320, 240)),
    ];
    for (name, d) in &scenes {
        let k = KernelScene::new(d).unwrap();
        let (reference, all) = whole(&k);
        // What a worker's framebuffer holds before it draws: a colour the
        // frame does not have.
        let mut used = vec![false; 1 << 16];
        for &p in &reference {
            used[p as usize] = true;
        }
        let fill = used.iter().position(|&u| !u).unwrap() as u16;
        let (w, h) = (k.width as usize, k.height);
        for h_band in [1, 7, 16, 100] {
            for cached in [true, false] {
                let how = format!("{name}: bands of {h_band} rows, cached {cached}");
                let (single, single_stats) = banded(&k, h_band, cached);
                let [(even, s0), (odd, s1)] = std::thread::scope(|scope| {
                    let k = &k;
                    [0, 1]
                        .map(|worker| {
                            scope.spawn(move || worker_frame(k, h_band, cached, (worker, 2), fill))
                        })
                        .map(|t| t.join().unwrap())
                });
                // Row y is in band y / rows, drawn by worker (y / rows) mod 2.
                let rows = h_band.min(h) as usize;
                let mut frame = vec![0u16; w * h as usize];
                for (y, row) in frame.chunks_mut(w).enumerate() {
                    let (mine, other) = if (y / rows).is_multiple_of(2) {
                        (&even, &odd)
                    } else {
                        (&odd, &even)
                    };
                    row.copy_from_slice(&mine[y * w..][..w]);
                    assert!(
                        other[y * w..][..w].iter().all(|&p| p == fill),
                        "{how}: row {y} drawn by the other worker too"
                    );
                }
                assert!(frame == single, "{how}: not the single-worker bands");
                assert!(frame == reference, "{how}: not the whole frame");
                assert_eq!(s0.pixels + s1.pixels, all.pixels, "{how}");
                assert_eq!(s0.drawn + s1.drawn, single_stats.drawn, "{how}");
                assert!(s0.pixels > 0 && s1.pixels > 0, "{how}: {s0:?} {s1:?}");
            }
        }
        // A worker index at or past the worker count: nothing drawn.
        for (worker, workers) in [(2, 2), (5, 2), (1, 1), (1, 0)] {
            let (px, stats) = worker_frame(&k, 16, true, (worker, workers), fill);
            assert!(
                px.iter().all(|&p| p == fill),
                "{name}: worker {worker} of {workers} drew"
            );
            assert_eq!(stats.pixels, 0, "{name}: worker {worker} of {workers}");
            let mut px = vec![fill; w * h as usize];
            let n = k.width as usize * 16;
            let (mut colour, mut depth) = (vec![0u16; n], vec![0u16; n]);
            let mut t = Counting {
                fb: Framebuffer::new(&mut px, k.width, h).unwrap(),
                fills: 0,
                rows: 0,
            };
            let mut bands = Bands::new(&mut t, &mut colour, 16).interleaved(worker, workers);
            k.render_in_bands(&mut bands, &mut depth, None).unwrap();
            assert_eq!(
                t.fills, 0,
                "{name}: worker {worker} of {workers} sent a band"
            );
        }
    }
}
