//! The vertex stage: each mesh vertex's window position, depth and lit
//! colour, in a 16-byte [`CachedVertex`] per vertex.
//!
//! # Rows
//! Once a draw, the projection, the view and model matrices, the mesh's
//! box and the viewport are folded into four rows ([`Rows`]): functions
//! `V(q) = Σ g[c]·q[c] + t` of a vertex's `i16` mesh position `q`, exact
//! in integers, whose true values are `V·2^e`, one exponent a row. They
//! are the vertex's homogeneous window coordinates: `X`, `Y` (the window
//! position relative to the set-up's origin, a pixel corner at the
//! viewport's centre, times `w_c`), `Z` (the depth attribute times `w_c`)
//! and `W` (`w_c`), so that the window position is `X/W` and the depth
//! attribute `Z/W`. No absolute size is part of them: each row keeps 28
//! bits of its largest coefficient.
//!
//! # Per vertex
//! Where the rows allow it ([`Rows::fast`]: `X` and `Y` at `W`'s exponent
//! plus 16, `Z` at plus 25), a vertex takes `⌊V/2¹⁴⌋` of each row in
//! 32-bit pieces, one reciprocal of its `W` ([`recip_fast`]) and three
//! products: the snapped position `round(x₁₄·2¹⁶/w₁₄)` exactly (a
//! quotient the reciprocal leaves within a 2⁻¹⁶ of a rounding's half is
//! divided exactly), and the depth attribute. A draw whose mesh box lies
//! in front of the near plane and inside the guard band ([`Rows::contained`],
//! decided from the box's eight corners) tests nothing per vertex;
//! otherwise a vertex behind the near plane, outside the guard band,
//! past `z_w = 2` or too close to the eye for 32-bit precision is marked
//! for the rare path (`src/clip.rs`), which works from the exact rows.
//!
//! The colour is lit the first time a drawn triangle needs it.

use crate::camera::ProjectionCoeffs;
use crate::color::Shade;
use crate::illumination::{Lighting, Viewer};
use crate::light::{LightSet, PreparedLights};
use crate::material::Specular;
use crate::mesh::Mesh;
use crate::normalize::normalize;
use crate::num::division::{div_rem_u64, floor_div, recip_fast};
use crate::num::widening::{mul_i32_i16, mul_i32_u32, mul_i32_u32_shr31};
use crate::num::Wide;
use crate::options::DrawStats;
use crate::platform;
use crate::vector::{normal_matrix, Mat4, Unit3, Vec3};

/// How far a window coordinate the lean set-up takes may lie from the
/// set-up's origin, in 1/16 pixel on each axis (±1 023 pixels): then every
/// difference of two coordinates is below 2¹⁵ and every doubled area
/// below 2³¹.
pub(crate) const GUARD: i32 = (1 << 14) - 16;

/// The depth attribute's scale: `z_w·DEPTH_K·2 + 2⁷`, whose `>> 8` is
/// SPEC.md 5's `d = round(z_w·65535)`.
const DEPTH_K: i64 = 65535 << 7;

/// `Z/W` in the fast rows is the depth attribute times 2⁻²⁵: below 1 up to
/// `z_w = 2`.
const Z_SHIFT: i32 = 25;

/// `X/W` in the fast rows is the window position (1/16 pixel) times 2⁻¹⁶.
const XY_SHIFT: i32 = 16;

/// One row: `V(q) = Σ g[c]·q[c] + t`, true value `V·2^e`, with `|g| ≤
/// 2²⁸` and `|t| ≤ 2⁴³`, so `|V| < 2⁴⁵`. Kept also split at bit 14 for
/// [`Row::fourteen`]. (`repr(C)`, `t` and `g` first, [`platform::ROW_BYTES`]
/// a row: the platform's loop reads them, [`platform::fourteen_rows`].)
#[repr(C)]
#[derive(Clone, Copy, Debug)]
struct Row {
    t: i64,
    g: [i32; 3],
    /// `g >> 14` and `t >> 14`.
    gh: [i32; 3],
    th: i32,
    /// `g & 0x3FFF` and `t & 0x3FFF`.
    gl: [i32; 3],
    tl: i32,
    e: i32,
}

const _: () = assert!(core::mem::size_of::<Row>() == platform::ROW_BYTES);
const _: () = assert!(core::mem::offset_of!(Row, gh) == platform::ROW_SPLIT);
const _: () = assert!(core::mem::offset_of!(Row, tl) == platform::ROW_SPLIT + 28);

impl Row {
    /// A row of zeros (what [`Rows::new`] writes its rows over).
    const ZERO: Row = Row {
        t: 0,
        g: [0; 3],
        gh: [0; 3],
        th: 0,
        gl: [0; 3],
        tl: 0,
        e: 0,
    };

    /// The row of coefficients `v[..3]` and constant `v[3]` at exponent
    /// `e`.
    fn at(v: &[Wide; 4], e: i32) -> Row {
        let g = [v[0].at(e) as i32, v[1].at(e) as i32, v[2].at(e) as i32];
        let t = v[3].at(e);
        Row {
            g,
            t,
            e,
            gh: g.map(|g| g >> 14),
            th: (t >> 14) as i32,
            gl: g.map(|g| g & 0x3FFF),
            tl: (t & 0x3FFF) as i32,
        }
    }

    /// The least exponent at which the coefficients `v[..3]` and the
    /// constant `v[3]` keep the row's bounds.
    fn exponent(v: &[Wide; 4]) -> i32 {
        let b = v[..3].iter().map(|w| w.bits() - 28).max().unwrap_or(0);
        b.max(v[3].bits() - 43)
    }

    /// `V(q)`, exactly: each product below 2⁴³.
    #[inline(always)]
    fn exact(&self, q: [i16; 3]) -> i64 {
        let g = &self.g;
        mul_i32_i16(g[0], q[0]) + mul_i32_i16(g[1], q[1]) + mul_i32_i16(g[2], q[2]) + self.t
    }

    /// [`Row::exact`] out of line, for [`Rows::exact`].
    #[inline(never)]
    fn exact_cold(&self, q: [i16; 3]) -> i64 {
        self.exact(q)
    }

    /// `⌊V(q)/2¹⁴⌋`, below 2³¹ in magnitude. Where a 64-bit product is a
    /// library call, from 32-bit pieces: `V = 2¹⁴·(Σ gₕq + tₕ) + (Σ gₗq +
    /// tₗ)`, with `|gₕ·q| ≤ 2²⁹`, `|tₕ| ≤ 2²⁹` (the high sum at most 2³¹ −
    /// 2²⁹) and `0 ≤ gₗ < 2¹⁴` (the low one within ±1.5·2³⁰), so both sums
    /// fit `i32` and `⌊V/2¹⁴⌋ = Σₕ + ⌊Σₗ/2¹⁴⌋`.
    #[inline(always)]
    fn fourteen(&self, q: [i16; 3]) -> i32 {
        if platform::SOFT_MUL64 {
            let q = [q[0] as i32, q[1] as i32, q[2] as i32];
            let (h, l) = (&self.gh, &self.gl);
            let hi = h[0] * q[0] + h[1] * q[1] + h[2] * q[2] + self.th;
            let lo = l[0] * q[0] + l[1] * q[1] + l[2] * q[2] + self.tl;
            hi + (lo >> 14)
        } else {
            (self.exact(q) >> 14) as i32
        }
    }
}

/// The draw's four rows (`X`, `Y`, `Z`, `W`) and what holds for every
/// vertex of the mesh's box.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Rows {
    r: [Row; 4],
    /// `X`, `Y` at `W`'s exponent plus [`XY_SHIFT`] and `Z` at plus
    /// [`Z_SHIFT`]: vertices take the 32-bit form.
    fast: bool,
    /// Fast, and every point of the mesh's box is in front of the near
    /// plane, inside the guard band, before `z_w = 2` and far enough from
    /// the eye: no vertex is tested.
    contained: bool,
    /// Fast, and every point of the mesh's box behind the near plane or
    /// past one side of the guard band, which holds the whole target:
    /// nothing of the mesh is drawn.
    outside: bool,
}

/// A vertex's window position (1/16 pixel from the set-up's origin) and
/// depth attribute, or `None` where it goes to the rare path.
pub(crate) type Window = Option<[i32; 3]>;

impl Rows {
    /// The rows of a `w × h` viewport (`w`, `h` ≤ 2²⁰) seen through
    /// projection `p` from the model-view matrix `mv` with the mesh's box
    /// folded in (`mv·(q·2⁻¹⁵, 1)` is the eye position, raw `I8F24`).
    pub(crate) fn new(mv: &Mat4, p: &ProjectionCoeffs, w: u32, h: u32) -> Rows {
        let m = &mv.m;
        // Once a draw: every loop below is kept rolled, one body a row or
        // a column, for flash (unrolled, the rows' `Wide` sums took 5 KB).
        let eye = |r: usize, c: usize| Wide::new(m[r][c] as i64, if c < 3 { -15 } else { 0 });
        // w_c = −z_e (perspective) or 1 (orthographic).
        let mut wc = [Wide::ZERO; 4];
        for (c, v) in wc.iter_mut().enumerate() {
            *v = if p.perspective {
                eye(2, c).neg()
            } else if c == 3 {
                Wide::new(1 << 24, 0)
            } else {
                Wide::ZERO
            };
            platform::keep_loop_rolled();
        }
        // The set-up's origin: the pixel corner at or left of and above the
        // viewport's centre, so that pixel centres lie at 16k + 8.
        let (w, h) = (w as i64, h as i64);
        let (ox, oy) = (16 * (w >> 1), 16 * (h >> 1));
        // Clip row `r` is `s·e_r·2⁻²⁴ + k`; each window row is one scaled
        // by `scale`, plus `off·w_c`; the fourth is `w_c`.
        let clip = [
            (p.sx, p.tx, 8 * w, 8 * w - ox),
            (p.sy, p.ty, -8 * h, 8 * h - oy),
            (p.a, p.b, DEPTH_K, 1 << 23),
        ];
        let mut rows = [[Wide::ZERO; 4]; 4];
        rows[3] = wc;
        for (r, &(s, k, scale, off)) in clip.iter().enumerate() {
            for (c, out) in rows[r].iter_mut().enumerate() {
                let mut v = Wide::new(s as i64 * m[r][c] as i64, if c < 3 { -39 } else { -24 });
                if c == 3 {
                    v = v.add(&Wide::new(k as i64, 0));
                }
                *out = v.mul(scale).add(&wc[c].mul(off));
                platform::keep_loop_rolled();
            }
        }
        let mut natural = [0; 4];
        for (n, v) in natural.iter_mut().zip(&rows) {
            *n = Row::exponent(v);
            platform::keep_loop_rolled();
        }
        let ew = natural[3];
        let forced = [ew + XY_SHIFT, ew + XY_SHIFT, ew + Z_SHIFT, ew];
        let fast = (0..4).all(|k| natural[k] <= forced[k]);
        let e = if fast { forced } else { natural };
        let mut out = Rows {
            r: [Row::ZERO; 4],
            fast,
            contained: false,
            outside: false,
        };
        for (k, row) in out.r.iter_mut().enumerate() {
            *row = Row::at(&rows[k], e[k]);
            platform::keep_loop_rolled();
        }
        if fast {
            // What every corner says: each takes the lean path ([`LEAN`]),
            // or each lies past one plane bounding what is drawn.
            let mut all = u32::MAX;
            for q in Rows::corners() {
                all &= corner(out.exact(q));
                platform::keep_loop_rolled();
            }
            // The guard band holds a target of at most 2 044 pixels a
            // side (its last pixel's far edge 1 022 pixels from the
            // origin); a larger one's pixels past it are drawn too.
            let sides = if w.max(h) <= 2044 { 0x1E } else { 0 };
            out.contained = all & LEAN != 0;
            out.outside = all & (1 | sides) != 0;
        }
        out
    }

    /// The eight corners of the mesh's box.
    fn corners() -> impl Iterator<Item = [i16; 3]> {
        (0..8).map(|k| [0, 1, 2].map(|c| if k >> c & 1 == 0 { i16::MIN } else { i16::MAX }))
    }

    /// `⌊V/2¹⁴⌋` of the four rows at position `q`, a row a pass of a loop
    /// kept rolled (`[T; N]::map` is not inlined on ARMv6-M: a call a
    /// vertex; unrolled, the four rows' coefficients spill).
    #[inline(always)]
    fn fourteen(&self, q: [i16; 3]) -> [i32; 4] {
        // SAFETY: four rows `Row`'s size apart, each `t` and `g` first
        // (`repr(C)`).
        if let Some(v) = unsafe { platform::fourteen_rows(self.r.as_ptr().cast(), q) } {
            return v;
        }
        let mut out = [0; 4];
        for (o, r) in out.iter_mut().zip(&self.r) {
            *o = r.fourteen(q);
            platform::keep_loop_rolled();
        }
        out
    }

    /// The exact rows of position `q` (once a draw, for the box's corners,
    /// and on the rare path), a row a call ([`Row::exact_cold`]: its four
    /// rows' twelve products inlined took 510 bytes on ARMv6-M).
    #[inline(never)]
    pub(crate) fn exact(&self, q: [i16; 3]) -> [i64; 4] {
        [0, 1, 2, 3].map(|k| self.r[k].exact_cold(q))
    }

    /// The rows' exponents.
    pub(crate) fn exponents(&self) -> [i32; 4] {
        self.r.map(|r| r.e)
    }

    /// The window position and depth attribute of position `q`, or `None`
    /// for the rare path.
    #[inline(always)]
    pub(crate) fn window(&self, q: [i16; 3]) -> Window {
        if self.fast {
            self.window_of(self.fourteen(q))
        } else {
            None
        }
    }

    /// Whether every vertex of the draw takes the lean path's 32-bit form
    /// without a test: no cache entry of the draw has the rare path's flag.
    #[inline(always)]
    pub(crate) fn contained(&self) -> bool {
        self.contained
    }

    /// Whether nothing of the mesh can be drawn: its box lies wholly behind
    /// the near plane or past one side of the guard band (the target inside
    /// it).
    #[inline(always)]
    pub(crate) fn outside(&self) -> bool {
        self.outside
    }

    /// [`Rows::window`] from the fast rows' [`Rows::fourteen`] `v`.
    #[inline(always)]
    fn window_of(&self, v: [i32; 4]) -> Window {
        // Without the rare path every draw is contained
        // (`Prepared::frame` refuses the others).
        debug_assert!(self.contained || platform::CLIP);
        if self.contained || !platform::CLIP {
            Some(Self::divided(v))
        } else {
            Self::tested(v)
        }
    }

    /// [`Rows::divided`] with the tests, out of line (a draw that is not
    /// contained).
    #[inline(never)]
    fn tested(v: [i32; 4]) -> Window {
        let [x14, y14, z14, w14] = v;
        // In front of the eye with 22 bits (precision), in front of the
        // near plane, before z_w = 2, and |X/W| < 2^-2 (|x| < 2^14).
        let quarter = w14 >> 2;
        let lean = w14 >= 1 << 22
            && z14 > w14 >> 18
            && z14 < w14
            && x14.abs() < quarter
            && y14.abs() < quarter;
        if !lean {
            return None;
        }
        let v = Self::divided(v);
        (v[0].abs() <= GUARD && v[1].abs() <= GUARD).then_some(v)
    }

    /// The 32-bit form: `x = round(x₁₄·2¹⁶/w₁₄)` and the same for `y`,
    /// depth `round(z₁₄·2²⁵/w₁₄)` (within one unit), each from one product
    /// with `r ≈ 2⁶³/d` ([`recip_fast`], a relative `2⁻²⁷`), `d = w₁₄·2ⁿ ∈
    /// [2³¹, 2³²)`.
    ///
    /// With `|x₁₄| < w₁₄/4` (the guard band), `xs = x₁₄·2ⁿ` is below 2³⁰
    /// and `p = ⌊xs·r/2³¹⌋` is `2¹⁶` times the quotient `Q` within a
    /// relative `2⁻²⁷` ([`mul_i32_u32_shr31`]: only the product's high part
    /// is made): `|Q| < 2¹⁴`, so within `2⁻¹³` of it, and within `|Q|·2⁻¹¹`
    /// units of 2⁻¹⁶, below 8 ([`near_half`]). Where the estimate's fraction lies
    /// that close to a half, the rounding is taken from the exact division.
    /// For the depth, `0 ≤ z₁₄ < w₁₄` and `zs = z₁₄·2ⁿ⁻¹ < 2³¹` (`n ≥ 1` as
    /// `w₁₄ < 2³¹`), `⌊zs·r/2³¹⌋` below 2³¹ (`w₁₄ ≥ 2²²`); it is not
    /// snapped, and its rounding is the estimate's.
    #[inline(always)]
    fn divided([x14, y14, z14, w14]: [i32; 4]) -> [i32; 3] {
        // w₁₄ ∈ [2²², 2³¹): every caller's (`Rows::contained`, `tested`).
        let n = platform::leading_zeros_of_w(w14 as u32);
        let d = (w14 as u32) << n;
        let r = recip_fast(d);
        // `⌊p/2³¹⌋` of each product `p` is all that is read of it.
        let estimate = |v: i32| {
            let p = mul_i32_u32_shr31(v << n, r);
            let q = (p + (1 << 15)) >> 16;
            (q, near_half(p))
        };
        let ((x, near_x), (y, near_y)) = (estimate(x14), estimate(y14));
        let zp = mul_i32_u32_shr31(z14 << (n - 1), r);
        let z = (zp + (1 << 5)) >> 6;
        // Where either estimate is near a half, both from the exact
        // division (the other's is the same): one call, at the end, so
        // that no value waits across it.
        if near_x || near_y {
            let (x, y) = exact_round_xy(x14, y14, w14);
            return [x, y, z];
        }
        [x, y, z]
    }

    /// The unsnapped window position of fast-row position `q` in units of
    /// 2⁻¹² of a sixteenth (`x₁₄·2²⁸/w₁₄` from the same product as the
    /// snapped one, within 2⁻⁴ units of it; below 2²⁶ in the guard band),
    /// or `None` where `q` has none: the facing of a sliver
    /// (`src/triangle.rs`).
    pub(crate) fn fine(&self, q: [i16; 3]) -> Option<[i64; 2]> {
        let [x14, y14, _, w14] = self.fourteen(q);
        let quarter = w14 >> 2;
        if !self.fast || w14 <= 0 || x14.abs() >= quarter || y14.abs() >= quarter {
            return None;
        }
        let n = platform::leading_zeros(w14 as u32);
        let r = recip_fast((w14 as u32) << n);
        Some([x14, y14].map(|v| mul_i32_u32(v << n, r) >> 35))
    }

    /// The exact window position (1/16 pixel) and depth attribute of the
    /// exact rows `v` of a point in front of the eye (`W > 0`), relative to
    /// the set-up's origin moved by `(dx, dy)` sixteenths, if both
    /// coordinates lie within `±limit` and the depth within `±2³⁰`: the
    /// rare path's, for vertices and the corners clipping makes.
    pub(crate) fn window_exact(&self, v: [i64; 4], dx: i64, dy: i64, limit: i64) -> Window {
        let e = self.exponents();
        let [x, y, z, w] = v;
        if w <= 0 {
            return None;
        }
        let x = quotient(x, e[0] - e[3], w)? - dx;
        let y = quotient(y, e[1] - e[3], w)? - dy;
        let z = quotient(z, e[2] - e[3], w)?;
        let inside = |a: i64| a.abs() <= limit;
        (inside(x) && inside(y) && z.abs() <= 1 << 30).then_some([x as i32, y as i32, z as i32])
    }
}

/// [`corner`]'s flag of a corner that takes the lean path.
const LEAN: u32 = 1 << 5;

/// What the fast rows' exact values `v` at a corner of the mesh's box say
/// of it: [`LEAN`] where it is in front of the near plane (depth attribute
/// above 2⁷), before `z_w = 2`, inside the guard band with half a sixteenth
/// to spare and `W ≥ 2³⁶` (for [`Rows::contained`]); bit 0 where it lies
/// behind the near plane (`Z < 0`: the depth attribute below 0), bits 1 to
/// 4 where it lies past the band's right, left, lower or upper side (for
/// [`Rows::outside`]). Each test is linear in the position, so the box's
/// corners decide for the box: a half-space of these homogeneous rows
/// holds the points behind the eye that project into it too, so a box
/// whose corners all lie past one plane has no point drawn. `|X|·2¹⁶ <
/// 2⁶²` and `G·W < 2⁶⁰`.
fn corner(v: [i64; 4]) -> u32 {
    let [x, y, z, w] = v;
    let gw = (GUARD - 1) as i64 * w;
    let (px, py) = (x.abs() << XY_SHIFT > gw, y.abs() << XY_SHIFT > gw);
    let lean = (w >= 1 << 36) & (z > (w + (1 << 18) - 1) >> 18) & (z < w) & !(px | py);
    // A side's bit by the coordinate's sign (where it is 0, `W < 0`: the
    // point lies past both sides).
    (lean as u32) << 5
        | (z < 0) as u32
        | (px as u32) << (1 + (x < 0) as u32)
        | (py as u32) << (3 + (y < 0) as u32)
}

/// Whether the estimate `p = Q·2¹⁶` (its floor) may lie on the other side
/// of a rounding's half than `Q`, for `|Q| < 2¹⁴` (inside the guard band,
/// as every caller's is): its 16 bits below the unit within 10 of `2¹⁵`.
/// The estimate's error is `|Q|·2⁻¹¹` units, below 8, and one more for
/// the truncation; the bound 10 is that of the largest `|Q|`, taken for
/// every `Q` so that the test is one comparison (a smaller `Q` near a
/// half takes the exact division a little more often, with the same
/// rounding).
#[inline(always)]
fn near_half(p: i32) -> bool {
    ((p & 0xFFFF) - (0x8000 - 10)) as u32 <= 20
}

/// `round(x·2¹⁶/w)` exactly, half up (`|x| < 2³¹`, `w > 0`).
fn exact_round(x: i32, w: i32) -> i32 {
    floor_div(((x as i64) << 17) + w as i64, 2 * w as i64) as i32
}

/// [`exact_round`] of `x` and of `y` (rare, out of line).
#[inline(never)]
fn exact_round_xy(x: i32, y: i32, w: i32) -> (i32, i32) {
    (exact_round(x, w), exact_round(y, w))
}

/// `round(v·2^s / w)`, half up, for `|v| < 2⁴⁶` and `0 < w < 2⁴⁶`, if its
/// magnitude is below 2⁴⁰: by long division in 16-bit digits where
/// `v·2^s` does not fit (each step's remainder below `w`, shifted by 16
/// below 2⁶²). Out of line: three calls a corner on the rare path.
#[inline(never)]
fn quotient(v: i64, s: i32, w: i64) -> Option<i64> {
    if s < 0 {
        // ⌊2v/(w·2^-s)⌋ = ⌊⌊2v/w⌋/2^-s⌋ (nested floors).
        let f = floor_div(2 * v, w) >> (-s).min(63);
        return Some((f + 1) >> 1);
    }
    // floor(|v|·2^(s+1)/w) in digits.
    let (q, r) = div_rem_u64(v.unsigned_abs(), w as u64);
    let (mut q, mut r) = (q as i64, r as i64);
    let mut left = s + 1;
    while left > 0 {
        let c = left.min(16);
        let (dq, dr) = div_rem_u64((r << c) as u64, w as u64);
        q = (q << c) + dq as i64;
        r = dr as i64;
        left -= c;
        if q >> 42 != 0 {
            return None;
        }
    }
    // floor(2x) for the signed value, then ⌊(floor(2x) + 1)/2⌋.
    let f = if v >= 0 { q } else { -q - (r != 0) as i64 };
    Some((f + 1) >> 1)
}

/// The colour and flags word: red in bits 0–16, green 17–33, blue 34–50
/// (three `Q.16` channels, 0 ..= 65536), then the flags.
const COLOUR_MASK: u64 = (1 << 51) - 1;
/// The colour is the front face's.
const B_FRONT: u64 = 1 << 52;
/// The colour is the back face's (negated normal).
const B_BACK: u64 = 1 << 53;
/// The colour word holds the eye normal instead (Phong shading, which
/// keeps no colour): three `i16` in bits 0–47.
const B_NORMAL: u64 = 1 << 55;
/// The vertex goes to the rare path: behind the near plane, outside the
/// guard band, past `z_w = 2` or too close to the eye for the 32-bit
/// form (its window position is not kept).
const B_RARE: u64 = 1 << 54;

/// One vertex's per-frame data, in a cache the caller provides (one per
/// mesh vertex): 16 bytes.
///
/// The window position is kept as `i16` sixteenths of a pixel from the
/// viewport's centre, the depth attribute as `i32`, and one lit colour
/// (three 17-bit channels) with the flags in 64 bits; Phong shading, which
/// lights pixels, keeps the vertex's eye normal there instead. A vertex lit
/// for both faces (a silhouette vertex with two-sided lighting) keeps the
/// first face's colour; the other one is lit again when asked for.
///
/// ```
/// use fixshade::render::CachedVertex;
/// assert_eq!(core::mem::size_of::<CachedVertex>(), 16);
/// // `const`: a cache can be a `static`.
/// static EMPTY: [CachedVertex; 642] = [CachedVertex::new(); 642];
/// ```
///
/// ```
/// # use fixshade::prelude::*;
/// # static P: [[i16; 3]; 3] = [[-16384, -16384, 0], [16384, -16384, 0], [0, 16384, 0]];
/// # static N: [PackedNormal; 3] = [PackedNormal::Z; 3];
/// # const MESH: Mesh = Mesh::new(&P, Bounds::cube(2.0), &[[0, 1, 2]]).with_normals(&N);
/// # let camera = Camera::look_at([0.0, 0.0, 3.0], [0.0; 3], [0.0, 1.0, 0.0]).unwrap();
/// # let sun = DirectionalLight::new([0.0, 0.0, 1.0]).unwrap();
/// # let material = Material::new();
/// # let renderer = Renderer::new(&camera, &material, &sun);
/// let mut px = [0u16; 32 * 32];
/// let mut fb = Framebuffer::new(&mut px, 32, 32).unwrap();
/// let mut short = [CachedVertex::new(); 2]; // the mesh has 3 vertices
/// let e = MESH.shaded(&renderer).with_cache(&mut short).draw(&mut fb);
/// assert_eq!(e, Err(RenderError::CacheTooSmall));
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[repr(C)]
pub struct CachedVertex {
    x: i16,
    y: i16,
    z: i32,
    c: [u32; 2],
}

// The layout the triangle loop's assembly reads (`platform::skip_culled`):
// `x` and `y` the first word, the flags word with the rare path's flag.
const _: () = assert!(core::mem::size_of::<CachedVertex>() == 16);
const _: () = assert!(core::mem::offset_of!(CachedVertex, x) == 0);
const _: () = assert!(core::mem::offset_of!(CachedVertex, y) == 2);
const _: () = assert!(core::mem::offset_of!(CachedVertex, c) + 4 == platform::FLAGS_AT);
// And the Gouraud set-up's (`platform::gouraud_set_up`): the depth
// attribute the second word, the colour ([`pack`]) the third and fourth.
const _: () = assert!(core::mem::offset_of!(CachedVertex, z) == 4);
const _: () = assert!(core::mem::offset_of!(CachedVertex, c) == 8);
const _: () = assert!(B_RARE == 1 << (32 + platform::RARE_BIT));

impl CachedVertex {
    /// An empty entry (every draw call overwrites what it uses).
    ///
    /// ```
    /// use fixshade::render::CachedVertex;
    /// const EMPTY: CachedVertex = CachedVertex::new();
    /// assert_eq!(EMPTY, CachedVertex::default());
    /// ```
    pub const fn new() -> CachedVertex {
        CachedVertex {
            x: 0,
            y: 0,
            z: 0,
            c: [0; 2],
        }
    }

    /// The entry of a projected vertex (no colour yet).
    #[inline(always)]
    pub(crate) fn of(w: Window) -> CachedVertex {
        match w {
            Some([x, y, z]) => CachedVertex {
                x: x as i16,
                y: y as i16,
                z,
                c: [0; 2],
            },
            None => CachedVertex {
                c: [0, (B_RARE >> 32) as u32],
                ..CachedVertex::new()
            },
        }
    }

    #[inline(always)]
    fn bits(&self) -> u64 {
        self.c[0] as u64 | (self.c[1] as u64) << 32
    }

    #[inline(always)]
    fn set_bits(&mut self, v: u64) {
        self.c = [v as u32, (v >> 32) as u32];
    }

    /// Whether the vertex goes to the rare path (its position is not
    /// kept): the flag word's bit, for a test of three vertices at once.
    #[inline(always)]
    pub(crate) fn rare_bits(&self) -> u32 {
        self.c[1] & (B_RARE >> 32) as u32
    }

    /// The kept window position (not rare).
    #[inline(always)]
    pub(crate) fn xy(&self) -> [i32; 2] {
        [self.x as i32, self.y as i32]
    }

    /// The kept window position and depth attribute (not rare).
    #[inline(always)]
    pub(crate) fn position(&self) -> [i32; 3] {
        [self.x as i32, self.y as i32, self.z]
    }

    /// The kept position, or `None` for a rare vertex.
    #[inline(always)]
    pub(crate) fn window(&self) -> Window {
        (self.rare_bits() == 0).then(|| self.position())
    }
}

/// Where a draw's per-vertex work is kept: [`Cached`]
/// ([`Shaded::with_cache`](crate::Shaded::with_cache)) or [`Recomputed`]
/// (the default).
///
/// ```
/// use fixshade::band::{Cached, Recomputed, VertexMode};
/// use fixshade::render::CachedVertex;
/// fn cached<X: VertexMode>(_: &X) -> bool {
///     X::CACHED
/// }
/// let mut storage = [CachedVertex::default(); 3];
/// let mut mode = Cached(&mut storage);
/// assert!(cached(&mode) && mode.cache().len() == 3);
/// assert!(!cached(&Recomputed) && Recomputed.cache().is_empty());
/// ```
pub trait VertexMode {
    /// Whether the vertices are cached.
    const CACHED: bool;
    /// The cache (empty for [`Recomputed`]).
    fn cache(&mut self) -> &mut [CachedVertex];
}

/// Vertices transformed, projected and lit once per frame, in caller
/// storage of one [`CachedVertex`] per mesh vertex.
///
/// ```
/// use fixshade::band::{Cached, VertexMode};
/// use fixshade::render::CachedVertex;
/// let mut storage = [CachedVertex::default(); 4];
/// let mut mode = Cached(&mut storage);
/// assert_eq!(mode.cache().len(), 4);
/// ```
#[derive(Debug)]
pub struct Cached<'c>(pub &'c mut [CachedVertex]);

impl VertexMode for Cached<'_> {
    const CACHED: bool = true;
    #[inline(always)]
    fn cache(&mut self) -> &mut [CachedVertex] {
        self.0
    }
}

/// No per-vertex storage: each triangle's vertices are transformed,
/// projected and lit again for each triangle that draws them (a draw into
/// bands keeps the last 64 in a table on the stack, `src/band.rs`).
///
/// ```
/// use fixshade::band::{Recomputed, VertexMode};
/// assert!(Recomputed.cache().is_empty());
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Recomputed;

impl VertexMode for Recomputed {
    const CACHED: bool = false;
    #[inline(always)]
    fn cache(&mut self) -> &mut [CachedVertex] {
        &mut []
    }
}

/// The packed colour word of a shade.
fn pack(s: Shade) -> u64 {
    let b = s.to_bits();
    b[0] as u64 | (b[1] as u64) << 17 | (b[2] as u64) << 34
}

#[inline(always)]
fn unpack(v: u64) -> Shade {
    let m = (1u64 << 17) - 1;
    // Packed from a shade ([`pack`]): every channel within 0 ..= 2¹⁶.
    Shade::from_bits_in_range(
        (v & m) as u32,
        ((v >> 17) & m) as u32,
        ((v >> 34) & m) as u32,
    )
}

/// The vertex stage of one draw: the rows, the lighting and what it needs
/// of a vertex (eye position, normal).
pub(crate) struct Stage<'a, 'm, S: Specular, V: Viewer, L: LightSet> {
    pub(crate) lighting: &'a Lighting<S, V, L>,
    pub(crate) mesh: &'a Mesh<'m>,
    /// The model-view matrix with the mesh's box folded in.
    modelview: Mat4,
    normal_m: [[i16; 3]; 3],
    pub(crate) rows: Rows,
}

impl<'a, 'm, S: Specular, V: Viewer, L: LightSet> Stage<'a, 'm, S, V, L> {
    /// The matrix that takes `mesh`'s normals to eye space for
    /// `modelview`: made only where a light reads normals (zeros
    /// otherwise), `None` where `modelview` has none.
    pub(crate) fn normal_matrix(modelview: &Mat4) -> Option<[[i16; 3]; 3]> {
        if <L::Prepared as PreparedLights>::EMPTY {
            Some([[0; 3]; 3])
        } else {
            normal_matrix(modelview)
        }
    }

    /// The stage for `mesh` drawn with `modelview` (without the box) and
    /// its [`Stage::normal_matrix`] `normal_m`, projection `p`, on a `w ×
    /// h` viewport.
    pub(crate) fn new(
        lighting: &'a Lighting<S, V, L>,
        mesh: &'a Mesh<'m>,
        modelview: &Mat4,
        normal_m: [[i16; 3]; 3],
        p: &ProjectionCoeffs,
        w: u32,
        h: u32,
    ) -> Self {
        let folded = mesh.bounds.fold(modelview);
        Stage {
            lighting,
            mesh,
            modelview: folded,
            normal_m,
            rows: Rows::new(&folded, p, w, h),
        }
    }

    /// Mesh vertex `i`'s position (`i` below the vertex count).
    #[inline(always)]
    pub(crate) fn position(&self, i: usize) -> [i16; 3] {
        self.mesh.positions.get(i).copied().unwrap_or([0; 3])
    }

    /// Projects mesh vertex `i` (no colour yet).
    #[inline(always)]
    pub(crate) fn project(&self, i: usize) -> CachedVertex {
        CachedVertex::of(self.rows.window(self.position(i)))
    }

    /// Projects every vertex of the mesh into `cache` (one per vertex),
    /// one loop: with the rows in assembly ([`platform::fourteen_rows`]),
    /// a vertex's values fit the registers. (On the M0+, batches of rows
    /// first and divisions after, each a loop of its own, had been cheaper
    /// while the rows were compiled: 374 instructions a vertex against
    /// 424; with the rows in assembly one loop costs less than the
    /// batches.)
    #[inline(never)]
    pub(crate) fn project_all(&self, cache: &mut [CachedVertex]) {
        for (c, q) in cache.iter_mut().zip(self.mesh.positions) {
            *c = CachedVertex::of(self.rows.window(*q));
        }
    }

    /// Eye-space position of mesh vertex `i`.
    #[inline]
    pub(crate) fn eye(&self, i: usize) -> Vec3 {
        self.modelview.transform_quantised(self.position(i))
    }

    /// Eye-space normal of mesh vertex `i`: its octahedral point
    /// transformed, then normalised once.
    ///
    /// `|M_n| ≤ 2¹⁴` and `Σ|N| ≤ 3·2¹⁵` (32767 for the encoder's bits), so
    /// each row's sum of 16 × 16-bit products is at most `3·2²⁹ < 2³¹`.
    #[inline]
    pub(crate) fn eye_normal(&self, i: usize) -> Unit3 {
        if <L::Prepared as PreparedLights>::EMPTY {
            // No light reads it (and the matrix was not made).
            return Unit3::ZERO;
        }
        let Some(n) = self.mesh.normals.and_then(|ns| ns.get(i)) else {
            return Unit3::ZERO;
        };
        let b = n.octahedron();
        let m = &self.normal_m;
        let row = |r: usize| m[r][0] as i32 * b[0] + m[r][1] as i32 * b[1] + m[r][2] as i32 * b[2];
        normalize([row(0), row(1), row(2)]).unwrap_or(Unit3::ZERO)
    }

    /// The eye normal of mesh vertex `i` (its entry `v`): the one its
    /// entry keeps, or made now ([`Stage::eye_normal`]) and kept, in the
    /// colour word that Phong shading does not use. Kept because a vertex
    /// is a corner of about six triangles drawn, and each corner reads it.
    #[inline(always)]
    pub(crate) fn normal(&self, v: &mut CachedVertex, i: usize) -> Unit3 {
        let bits = v.bits();
        let part = |k: u32| (bits >> k) as u16 as i16;
        if bits & B_NORMAL != 0 {
            return Unit3::new_clamped(part(0), part(16), part(32));
        }
        let n = self.eye_normal(i);
        let b = n.to_bits().map(|c| c as u16 as u64);
        v.set_bits((bits & !COLOUR_MASK) | b[0] | b[1] << 16 | b[2] << 32 | B_NORMAL);
        n
    }

    /// The lit colour of vertex `i` (its entry `v`), for its back (negated
    /// normal) if `back`: the cached one, or lit now and kept if the entry
    /// has none yet.
    #[inline(always)]
    pub(crate) fn shade(
        &self,
        v: &mut CachedVertex,
        i: usize,
        back: bool,
        stats: &mut DrawStats,
    ) -> Shade {
        let want = if back { B_BACK } else { B_FRONT };
        if v.c[1] & (want >> 32) as u32 != 0 {
            unpack(v.bits())
        } else {
            self.light(v, i, want, stats)
        }
    }

    /// Lights vertex `i` (its entry `v`) for the front face unless its
    /// entry holds that colour already; whether it now does (an entry lit
    /// first for the back face keeps the back's colour). For a reader of
    /// the entry's colour bits ([`pack`]'s layout), not of a [`Shade`].
    #[inline(always)]
    pub(crate) fn lit_front(&self, v: &mut CachedVertex, i: usize, stats: &mut DrawStats) -> bool {
        let front = (B_FRONT >> 32) as u32;
        if v.c[1] & front == 0 {
            self.light(v, i, B_FRONT, stats);
        }
        v.c[1] & front != 0
    }

    /// Lights `v` (mesh vertex `i`) for the facing `want`, keeping the
    /// colour if the vertex has none yet.
    #[inline(never)]
    fn light(&self, v: &mut CachedVertex, i: usize, want: u64, stats: &mut DrawStats) -> Shade {
        let n = self.eye_normal(i);
        let n = if want == B_BACK { n.neg() } else { n };
        // The eye position only for a term that reads it (not for
        // directional lights under the infinite viewer).
        let p = if Lighting::<S, V, L>::READS_POSITION {
            self.eye(i)
        } else {
            Vec3::ZERO
        };
        let s = self.lighting.shade(p, n);
        stats.lit = stats.lit.saturating_add(1);
        let bits = v.bits();
        if bits & (B_FRONT | B_BACK) == 0 {
            v.set_bits((bits & !COLOUR_MASK) | pack(s) | want);
        }
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::Camera;
    use crate::tests::xorshift;

    /// The composed values are the products and sums they stand for, to
    /// 2⁻⁵⁰ (an `f64` holds 53 bits).
    #[test]
    fn wide_products_and_sums() {
        let mut next = xorshift(0x2545_f491_4f6c_dd1d);
        for _ in 0..100_000 {
            let a = (next() >> (next() % 63 + 1)) as i64 * if next() & 1 == 0 { 1 } else { -1 };
            let b = (next() >> 33) as i64 * if next() & 1 == 0 { 1 } else { -1 };
            let (ea, eb) = ((next() % 40) as i32 - 20, (next() % 40) as i32 - 20);
            let p = Wide::new(a, ea).mul(b);
            let want = a as f64 * b as f64 * 2f64.powi(ea);
            let got = p.m as f64 * 2f64.powi(p.e);
            assert!(
                (got - want).abs() <= want.abs() * 2f64.powi(-50) + 1e-300,
                "{a} {b}"
            );
            let s = Wide::new(a, ea).add(&Wide::new(b, eb));
            let want = a as f64 * 2f64.powi(ea) + b as f64 * 2f64.powi(eb);
            let got = s.m as f64 * 2f64.powi(s.e);
            let scale = (a as f64 * 2f64.powi(ea))
                .abs()
                .max((b as f64 * 2f64.powi(eb)).abs());
            assert!(
                (got - want).abs() <= scale * 2f64.powi(-50),
                "{a} {ea} {b} {eb}"
            );
        }
    }

    /// Split and whole rows agree: `⌊V/2¹⁴⌋` from 32-bit pieces is the
    /// exact one, at the rows' bounds and at random positions.
    #[test]
    fn fourteen_is_the_exact_floor() {
        let mut next = xorshift(0x9e37_79b9_7f4a_7c15);
        for _ in 0..2_000 {
            let c = [0, 1, 2].map(|_| {
                Wide::new(
                    (next() >> 35) as i64 * if next() & 1 == 0 { 1 } else { -1 },
                    0,
                )
            });
            let k = Wide::new(
                (next() >> 19) as i64 * if next() & 1 == 0 { 1 } else { -1 },
                0,
            );
            let v = [c[0], c[1], c[2], k];
            let row = Row::at(&v, Row::exponent(&v));
            assert!(row.g.iter().all(|g| g.unsigned_abs() <= 1 << 28));
            assert!(row.t.unsigned_abs() <= 1 << 43);
            for q in Rows::corners().chain((0..20).map(|_| [0, 1, 2].map(|_| next() as i16))) {
                let v = row.exact(q);
                let q32 = q.map(i32::from);
                let hi = row.gh[0] * q32[0] + row.gh[1] * q32[1] + row.gh[2] * q32[2] + row.th;
                let lo = row.gl[0] * q32[0] + row.gl[1] * q32[1] + row.gl[2] * q32[2] + row.tl;
                assert_eq!((hi + (lo >> 14)) as i64, v >> 14);
                assert_eq!(row.fourteen(q) as i64, v >> 14);
            }
        }
    }

    /// Quotients within a few units of 2⁻¹⁶ of a half, across the guard
    /// band (`|Q| < 2¹⁴`) and `W` from 2²² to 2³¹: the fast form's
    /// positions are still the exact roundings (`near_half` sends them to
    /// the exact division), and its depth within one unit.
    #[test]
    fn near_halves_round_exactly() {
        let mut next = xorshift(0x5151_7a7a_0c0c_e3e3);
        for i in 0..300_000u64 {
            let w14 = (1i64 << 22) + (next() % ((1 << 31) - (1 << 22))) as i64;
            let k = (next() % 32_760) as i64 - 16_380;
            // x₁₄ near (k + ½)·w₁₄/2¹⁶, moved by a few of its units (each
            // below 2⁻⁶ of a unit of 2⁻¹⁶ of Q); every tenth anywhere.
            let half = ((2 * k + 1) * w14) >> 17;
            let x14 = if i % 10 == 0 {
                ((next() % (w14 as u64 / 2)) as i64 - w14 / 4 + 1) as i32
            } else {
                (half + (next() % 9) as i64 - 4) as i32
            };
            let (w14, y14, z14) = (w14 as i32, -(x14 / 3), (w14 / 3) as i32);
            let [x, y, z] = Rows::divided([x14, y14, z14, w14]);
            assert_eq!(x, exact_round(x14, w14), "{x14} {w14}");
            assert_eq!(y, exact_round(y14, w14), "{y14} {w14}");
            let ez = z14 as f64 / w14 as f64 * 2f64.powi(25);
            assert!((z as f64 - ez).abs() <= 1.0, "{z} {ez}");
        }
    }

    /// The fast form's positions are the exact rounding of `x₁₄·2¹⁶/w₁₄`,
    /// so within `(2¹⁶ + |x|)/w₁₄` of a sixteenth of the exact window
    /// position beyond the rounding (the floors' share); its depth within
    /// one unit; a contained draw's every vertex takes it.
    #[test]
    fn fast_positions_are_exact_roundings() {
        let cam = Camera::look_at([0.3, 0.4, 3.0], [0.0; 3], [0.0, 1.0, 0.0]).unwrap();
        let p = cam.projection_for(320, 240).unwrap();
        let m = crate::mesh::Bounds::cube(1.0).fold(&cam.view);
        let rows = Rows::new(&m, &p, 320, 240);
        assert!(rows.fast && rows.contained);
        let mut next = xorshift(0x1234_5678_9abc_def1);
        for _ in 0..200_000 {
            let q = [0, 1, 2].map(|_| next() as i16);
            let [x, y, z] = rows.window(q).unwrap();
            let v = rows.exact(q);
            let [x14, y14, _, w14] = [0, 1, 2, 3].map(|k| (v[k] >> 14) as i32);
            assert_eq!(x, exact_round(x14, w14));
            assert_eq!(y, exact_round(y14, w14));
            let ex = v[0] as f64 / v[3] as f64 * 65536.0;
            let floors = (65536.0 + ex.abs()) / w14 as f64;
            assert!((x as f64 - ex).abs() <= 0.5 + floors, "{x} {ex}");
            let ez = v[2] as f64 / v[3] as f64 * 2f64.powi(25);
            assert!((z as f64 - ez).abs() <= 1.0, "{z} {ez}");
            assert_eq!(
                rows.window_exact(v, 0, 0, 1 << 20).map(|w| w[2]),
                Some(z).map(|_| rows.window_exact(v, 0, 0, 1 << 20).unwrap()[2])
            );
        }
    }

    /// [`Rows::outside`] holds only for a box of which no point can be
    /// drawn: over random views of a box (eyes around and inside it, fields
    /// of view from 5° to 120°), no sampled point of a box called outside
    /// lies in front of the near plane (depth attribute above 2⁷) and inside
    /// the guard band; on a target too wide for the band, none lies in
    /// front of the eye's side of `Z = 0`. Both kinds of box occur.
    #[test]
    fn outside_boxes_have_no_drawn_point() {
        use crate::camera::Projection;
        let (mut next, mut pick) = (xorshift(0x0b0c_5eed_f00d_cafe), xorshift(0x005e_ed0f_0b0c));
        let mut f = |s: f32| ((pick() % 2001) as f32 / 1000.0 - 1.0) * s;
        let mut seen = [0; 2];
        for i in 0..6000 {
            let (eye, at) = ([f(30.0), f(30.0), f(30.0)], [f(30.0), f(30.0), f(30.0)]);
            let fovy = 5.0 + (f(1.0) + 1.0) * 57.5;
            let Ok(cam) = Camera::look_at(eye, at, [0.0, 1.0, 0.0]) else {
                continue;
            };
            let lens = Projection::Perspective { fovy_deg: fovy };
            let Ok(cam) = cam.with_projection(lens, 0.1, 100.0) else {
                continue;
            };
            let (w, h) = if i % 4 == 0 { (3000, 200) } else { (320, 240) };
            let Ok(p) = cam.projection_for(w, h) else {
                continue;
            };
            let m = crate::mesh::Bounds::cube(4.0).fold(&cam.view);
            let rows = Rows::new(&m, &p, w, h);
            seen[rows.outside as usize] += 1;
            if !rows.outside {
                continue;
            }
            let g = (GUARD - 1) as i64;
            for _ in 0..300 {
                let q = [0, 1, 2].map(|_| next() as i16);
                let [x, y, z, wv] = rows.exact(q);
                if w > 2044 {
                    assert!(z < 0, "{eye:?} {at:?} {fovy}");
                } else {
                    let band = |a: i64| a.abs() << XY_SHIFT <= g * wv;
                    let drawn = wv > 0 && z > wv >> 18 && band(x) && band(y);
                    assert!(!drawn, "{eye:?} {at:?} {fovy}: {q:?}");
                }
            }
        }
        assert!(seen[0] > 1000 && seen[1] > 200, "{seen:?}");
    }
}
