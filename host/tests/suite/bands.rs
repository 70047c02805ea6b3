//! The band renderer against the whole-frame render: bit for bit, for band
//! heights 1, 7, 16 and the full height, cached and recomputed vertices, on
//! the standard scenes; and its errors.

use embedded_graphics::draw_target::DrawTarget;
use embedded_graphics::geometry::{OriginDimensions, Size};
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::primitives::Rectangle;
use embedded_graphics::Pixel;
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
        self.fb.fill_contiguous(area, colors)
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
    assert!(k.render_bands(&mut fb, 1, &mut [], &mut [], None).is_ok());
}
