//! The kernel's per-vertex colour (`Lighting::shade`, quantised to
//! RGB565) against the f64 reference (`reference::illuminate`, quantised as
//! SPEC.md 6), within 1 LSB per channel (SPEC.md 7), on hand-picked and
//! random inputs.
//!
//! Every case is one `LightDesc`/`MaterialDesc` description; [`Case::eval`]
//! builds both sides from it and runs every monomorphisation that applies:
//! Blinn–Phong and Phong (and `NoSpecular` where `Ks` is black), infinite
//! and local viewer, and the light set as a `heapless::Vec<AnyLight, _>`,
//! as the concrete light type (one light), with and without the
//! attenuation type (`(1, 0, 0)`), and as a tuple (two lights). All kernel
//! variants of one case must agree bit for bit.

use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
use fixshade::illumination::{InfiniteViewer, LocalViewer};
use fixshade::light::{
    unit_from_f64, AnyLight, AreaLight, Attenuation, DirectionalLight, LightSet, PointLight,
    SpotCone, SpotLight,
};
use fixshade::material::{BlinnPhong, NoSpecular, Phong, Specular};
use fixshade::num::WidePoint;
use fixshade::{Exponent, Lighting, Mat4, Material, Rgb, Shade, Unit3, Vec3};
use fixshade_host::reference::{eye_lights, illuminate, quantize_rgb565, EyeLight, LightingModel};
use fixshade_host::scene_desc::{LightDesc, MaterialDesc, SpecularModel, Viewer, IDENTITY};
use proptest::prelude::*;

const MODELS: [SpecularModel; 2] = [SpecularModel::Blinn, SpecularModel::Phong];
const VIEWERS: [Viewer; 2] = [Viewer::Infinite, Viewer::Local];
const NO_ATT: [f64; 3] = [1.0, 0.0, 0.0];

// ---------------------------------------------------------------------------
// Descriptions → kernel values
// ---------------------------------------------------------------------------

fn rgb(c: [f64; 3]) -> Rgb {
    Rgb::from_f64(c).expect("colour")
}

fn point_light(p: [f64; 3], d: [f64; 3], s: [f64; 3], a: [f64; 3]) -> PointLight {
    PointLight {
        position: WidePoint::from_f64(p).expect("light position"),
        diffuse: rgb(d),
        specular: rgb(s),
        attenuation: Attenuation::from_f64(a).expect("attenuation"),
    }
}

fn kernel_light(l: &LightDesc) -> AnyLight {
    match l {
        LightDesc::Directional {
            direction,
            diffuse,
            specular,
        } => AnyLight::Directional(
            DirectionalLight::from_unit(unit_from_f64(*direction).expect("direction"))
                .with_diffuse(rgb(*diffuse))
                .with_specular(rgb(*specular)),
        ),
        LightDesc::Point {
            position,
            diffuse,
            specular,
            attenuation,
        } => AnyLight::Point(point_light(*position, *diffuse, *specular, *attenuation)),
        LightDesc::Spot {
            position,
            axis,
            cutoff_deg,
            exponent,
            diffuse,
            specular,
            attenuation,
        } => AnyLight::Spot(SpotLight {
            light: point_light(*position, *diffuse, *specular, *attenuation),
            cone: SpotCone::from_f64(*axis, *cutoff_deg, *exponent).expect("cone"),
        }),
        LightDesc::Area {
            center,
            edge_u,
            edge_v,
            samples_k,
            diffuse,
            specular,
            attenuation,
        } => AnyLight::Area(AreaLight {
            center: WidePoint::from_f64(*center).expect("centre"),
            edge_u: WidePoint::from_f64(*edge_u).expect("edge u"),
            edge_v: WidePoint::from_f64(*edge_v).expect("edge v"),
            samples_k: *samples_k as u8,
            diffuse: rgb(*diffuse),
            specular: rgb(*specular),
            attenuation: Attenuation::from_f64(*attenuation).expect("attenuation"),
        }),
    }
}

/// The shininess through the kernel's own float constructor.
fn exponent(n: f64) -> Exponent {
    Exponent::from_f32(n as f32).expect("shininess in [0, 4096]")
}

/// One input of the illumination equation, as a description.
#[derive(Clone, Debug)]
struct Case {
    name: String,
    material: MaterialDesc,
    ambient: [f64; 3],
    lights: Vec<LightDesc>,
    p: [f64; 3],
    n: [f64; 3],
}

/// The outcome of one case for one specular model and viewer.
#[derive(Clone, Copy, Debug)]
struct Outcome {
    kernel: Rgb565,
    reference: [f64; 3],
    expected: Rgb565,
    /// Error per channel in that channel's LSBs.
    err: [u32; 3],
}

fn channels(c: Rgb565) -> [i32; 3] {
    [c.r() as i32, c.g() as i32, c.b() as i32]
}

fn from_raw(raw: u16) -> Rgb565 {
    Rgb565::new((raw >> 11) as u8, ((raw >> 5) & 63) as u8, (raw & 31) as u8)
}

fn lit<S: Specular, L: LightSet>(
    m: &Material<S>,
    viewer: Viewer,
    ambient: Rgb,
    lights: &L,
    p: Vec3,
    n: Unit3,
) -> Shade {
    match viewer {
        Viewer::Infinite => {
            Lighting::<S, InfiniteViewer, L>::new(m, ambient, lights, &Mat4::IDENTITY).shade(p, n)
        }
        Viewer::Local => {
            Lighting::<S, LocalViewer, L>::new(m, ambient, lights, &Mat4::IDENTITY).shade(p, n)
        }
    }
}

impl Case {
    fn new(name: impl Into<String>, material: MaterialDesc, lights: Vec<LightDesc>) -> Case {
        Case {
            name: name.into(),
            material,
            ambient: [0.1; 3],
            lights,
            p: [0.0, 0.0, -3.0],
            n: [0.0, 0.0, 1.0],
        }
    }

    fn at(mut self, p: [f64; 3], n: [f64; 3]) -> Case {
        self.p = p;
        self.n = n;
        self
    }

    fn ambient(mut self, a: [f64; 3]) -> Case {
        self.ambient = a;
        self
    }

    fn base_material(&self) -> Material<NoSpecular> {
        let m = &self.material;
        Material::new()
            .with_emission(rgb(m.emission))
            .with_ambient(rgb(m.ambient))
            .with_diffuse(rgb(m.diffuse))
    }

    /// The kernel's colour for light set `lights` with the given model and
    /// viewer (and, where `Ks` is black, also without specular: the same).
    fn kernel<L: LightSet>(&self, model: SpecularModel, viewer: Viewer, lights: &L) -> Shade {
        let (ks, n) = (
            rgb(self.material.specular),
            exponent(self.material.shininess),
        );
        let p = Vec3::from_f64(self.p).expect("position in range");
        let nu = unit_from_f64(self.n).expect("normal");
        let a = rgb(self.ambient);
        let base = self.base_material();
        let s = match model {
            SpecularModel::Blinn => {
                let m = base.with_specular(BlinnPhong {
                    color: ks,
                    shininess: n,
                });
                lit(&m, viewer, a, lights, p, nu)
            }
            SpecularModel::Phong => {
                let m = base.with_specular(Phong {
                    color: ks,
                    shininess: n,
                });
                lit(&m, viewer, a, lights, p, nu)
            }
        };
        if ks.is_black() {
            let plain = lit(&base, viewer, a, lights, p, nu);
            assert_eq!(plain, s, "{}: NoSpecular differs from black Ks", self.name);
        }
        s
    }

    /// The kernel's colour through every light-set type that fits.
    fn kernel_all(&self, model: SpecularModel, viewer: Viewer) -> Shade {
        let any: heapless::Vec<AnyLight, 64> = self.lights.iter().map(kernel_light).collect();
        let s = self.kernel(model, viewer, &any);
        let same = |other: Shade, how: &str| {
            assert_eq!(
                other, s,
                "{}: {how} differs from heapless::Vec<AnyLight> ({model:?}, {viewer:?})",
                self.name
            );
        };
        match any.as_slice() {
            [] => same(self.kernel(model, viewer, &()), "()"),
            [one] => {
                same(self.kernel(model, viewer, &[*one]), "[AnyLight; 1]");
                match one {
                    AnyLight::Directional(l) => same(self.kernel(model, viewer, l), "directional"),
                    AnyLight::Point(l) => {
                        same(self.kernel(model, viewer, l), "PointLight");
                        if l.attenuation == Attenuation::NONE {
                            let l = l.without_attenuation();
                            same(self.kernel(model, viewer, &l), "PointLight<NoAttenuation>");
                        }
                    }
                    AnyLight::Spot(l) => {
                        same(self.kernel(model, viewer, l), "SpotLight");
                        if l.light.attenuation == Attenuation::NONE {
                            let l = SpotLight {
                                light: l.light.without_attenuation(),
                                cone: l.cone,
                            };
                            same(self.kernel(model, viewer, &l), "SpotLight<NoAttenuation>");
                        }
                    }
                    AnyLight::Area(l) => same(self.kernel(model, viewer, l), "AreaLight"),
                }
            }
            [a, b] => same(
                self.kernel(model, viewer, &(*a, *b)),
                "(AnyLight, AnyLight)",
            ),
            _ => {}
        }
        s
    }

    fn reference(&self, model: SpecularModel, viewer: Viewer) -> [f64; 3] {
        let lights = eye_lights(&self.lights, &IDENTITY);
        let m = LightingModel {
            material: &self.material,
            global_ambient: self.ambient,
            lights: &lights,
            specular_model: model,
            viewer,
        };
        illuminate(&m, self.p, self.n)
    }

    fn eval(&self, model: SpecularModel, viewer: Viewer) -> Outcome {
        let kernel = self.kernel_all(model, viewer).to_rgb565();
        let reference = self.reference(model, viewer);
        let expected = from_raw(quantize_rgb565(reference));
        let (k, e) = (channels(kernel), channels(expected));
        Outcome {
            kernel,
            reference,
            expected,
            err: [0, 1, 2].map(|c| (k[c] - e[c]).unsigned_abs()),
        }
    }
}

/// Exact and failing counts over a sweep.
#[derive(Default)]
struct Tally {
    evaluated: usize,
    exact: usize,
    max_err: [u32; 3],
    failures: Vec<String>,
}

impl Tally {
    fn add(&mut self, c: &Case, model: SpecularModel, viewer: Viewer) {
        let o = c.eval(model, viewer);
        self.evaluated += 1;
        if o.err == [0; 3] {
            self.exact += 1;
        }
        for k in 0..3 {
            self.max_err[k] = self.max_err[k].max(o.err[k]);
        }
        if o.err.iter().any(|&e| e > 1) {
            self.failures.push(format!(
                "{} [{model:?}, {viewer:?}]: kernel {:?} expected {:?} (ref {:?}) err {:?} LSB; {c:?}",
                c.name,
                channels(o.kernel),
                channels(o.expected),
                o.reference,
                o.err
            ));
        }
    }

    fn add_all(&mut self, c: &Case) {
        for model in MODELS {
            for viewer in VIEWERS {
                self.add(c, model, viewer);
            }
        }
    }

    fn share(&self) -> f64 {
        self.exact as f64 / self.evaluated.max(1) as f64
    }

    fn assert_ok(&self, what: &str) {
        println!(
            "{what}: {} evaluations, {:.2}% exact, max error {:?} LSB",
            self.evaluated,
            100.0 * self.share(),
            self.max_err
        );
        assert!(self.evaluated > 0);
        assert!(
            self.failures.is_empty(),
            "{what}: {} of {} beyond 1 LSB:\n{}",
            self.failures.len(),
            self.evaluated,
            self.failures.join("\n")
        );
    }
}

fn sweep(what: &str, cases: &[Case]) -> Tally {
    let mut t = Tally::default();
    for c in cases {
        t.add_all(c);
    }
    t.assert_ok(what);
    t
}

// ---------------------------------------------------------------------------
// Description shorthands
// ---------------------------------------------------------------------------

fn material(e: f64, a: f64, d: f64, s: f64, n: f64) -> MaterialDesc {
    MaterialDesc {
        emission: [e; 3],
        ambient: [a, a * 0.8, a * 0.6],
        diffuse: [d, d * 0.7, d * 0.4],
        specular: [s; 3],
        shininess: n,
    }
}

fn shiny(n: f64) -> MaterialDesc {
    material(0.0, 0.2, 0.6, 0.8, n)
}

fn dir(d: [f64; 3], i: f64) -> LightDesc {
    LightDesc::Directional {
        direction: d,
        diffuse: [i; 3],
        specular: [i; 3],
    }
}

fn point(p: [f64; 3], i: f64, att: [f64; 3]) -> LightDesc {
    LightDesc::Point {
        position: p,
        diffuse: [i; 3],
        specular: [i; 3],
        attenuation: att,
    }
}

fn spot(p: [f64; 3], axis: [f64; 3], cutoff: f64, exp: f64, i: f64) -> LightDesc {
    LightDesc::Spot {
        position: p,
        axis,
        cutoff_deg: cutoff,
        exponent: exp,
        diffuse: [i; 3],
        specular: [i; 3],
        attenuation: NO_ATT,
    }
}

fn area(c: [f64; 3], k: u32, i: f64, att: [f64; 3]) -> LightDesc {
    LightDesc::Area {
        center: c,
        edge_u: [1.5, 0.0, 0.3],
        edge_v: [0.0, 1.0, -0.2],
        samples_k: k,
        diffuse: [i; 3],
        specular: [i; 3],
        attenuation: att,
    }
}

fn normalized(v: [f64; 3]) -> [f64; 3] {
    let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    v.map(|x| x / l)
}

// ---------------------------------------------------------------------------
// Hand-picked cases
// ---------------------------------------------------------------------------

/// Every light kind, lit from a few directions.
fn light_kind_cases() -> Vec<Case> {
    let n = normalized([0.2, 0.3, 1.0]);
    let p = [0.3, -0.2, -2.5];
    let mut v = Vec::new();
    for (i, m) in [shiny(16.0), material(0.0, 0.3, 0.9, 0.0, 0.0)]
        .into_iter()
        .enumerate()
    {
        v.push(Case::new(format!("no lights {i}"), m.clone(), vec![]).at(p, n));
        v.push(
            Case::new(
                format!("directional {i}"),
                m.clone(),
                vec![dir([0.5, 0.8, 1.0], 1.0)],
            )
            .at(p, n),
        );
        v.push(
            Case::new(
                format!("point {i}"),
                m.clone(),
                vec![point([1.0, 2.0, 1.0], 1.0, NO_ATT)],
            )
            .at(p, n),
        );
        v.push(
            Case::new(
                format!("point att {i}"),
                m.clone(),
                vec![point([1.0, 2.0, 1.0], 1.0, [0.5, 0.1, 0.05])],
            )
            .at(p, n),
        );
        v.push(
            Case::new(
                format!("spot {i}"),
                m.clone(),
                vec![spot([0.0, 0.0, 0.0], [0.1, -0.05, -1.0], 30.0, 4.0, 1.0)],
            )
            .at(p, n),
        );
        for k in 1..=3 {
            v.push(
                Case::new(
                    format!("area k={k} {i}"),
                    m.clone(),
                    vec![area([0.5, 1.0, 0.5], k, 1.2, NO_ATT)],
                )
                .at(p, n),
            );
            v.push(
                Case::new(
                    format!("area k={k} att {i}"),
                    m.clone(),
                    vec![area([0.5, 1.0, 0.5], k, 1.2, [0.2, 0.3, 0.1])],
                )
                .at(p, n),
            );
        }
        v.push(
            Case::new(
                format!("mixed {i}"),
                m.clone(),
                vec![
                    dir([-1.0, 0.2, 0.5], 0.4),
                    point([2.0, 1.0, 0.0], 0.6, [1.0, 0.05, 0.0]),
                ],
            )
            .at(p, n),
        );
    }
    v
}

/// Shininess from 0 to 2048 with the highlight near its peak, on its
/// flank and in its tail.
fn shininess_cases() -> Vec<Case> {
    let mut v = Vec::new();
    for n in [0.0, 1.0, 8.0, 32.0, 128.0, 1000.0, 2048.0] {
        // Light straight on, slightly off, and further off; the normal
        // tilted by a small angle so that (N·H) and (R·V) run over the
        // steep part of x^n for large n.
        for (k, tilt) in [0.0, 0.004, 0.01, 0.02, 0.05, 0.2, 0.6]
            .into_iter()
            .enumerate()
        {
            let nrm = normalized([tilt, 0.3 * tilt, 1.0]);
            v.push(
                Case::new(
                    format!("n={n} tilt {k} dir"),
                    shiny(n),
                    vec![dir([0.0, 0.0, 1.0], 1.0)],
                )
                .at([0.0, 0.0, -2.0], nrm),
            );
            v.push(
                Case::new(
                    format!("n={n} tilt {k} dir oblique"),
                    shiny(n),
                    vec![dir([0.6, 0.0, 0.8], 1.0)],
                )
                .at([0.0, 0.0, -2.0], normalized([0.3 + tilt, 0.1 * tilt, 1.0])),
            );
            v.push(
                Case::new(
                    format!("n={n} tilt {k} point"),
                    shiny(n),
                    vec![point([0.0, 0.0, 1.0], 1.0, NO_ATT)],
                )
                .at([0.05, -0.03, -2.0], nrm),
            );
        }
    }
    v
}

/// N·L near 0 (10⁻³, 10⁻⁴) and near 1.
fn grazing_cases() -> Vec<Case> {
    let mut v = Vec::new();
    let normals = [
        [0.0, 0.0, 1.0],
        normalized([0.3, -0.4, 0.8]),
        normalized([-0.7, 0.1, 0.2]),
    ];
    for (j, nrm) in normals.into_iter().enumerate() {
        // A unit vector perpendicular to the normal.
        let t = normalized([nrm[1] + nrm[2], nrm[2] - nrm[0], -nrm[0] - nrm[1]]);
        for (k, cos) in [1e-3f64, 1e-4, 1e-2, 0.999, 0.9999, 1.0]
            .into_iter()
            .enumerate()
        {
            let sin = (1.0 - cos * cos).sqrt();
            let l = [0, 1, 2].map(|i| cos * nrm[i] + sin * t[i]);
            for (m_name, m) in [
                ("diffuse", material(0.0, 0.2, 1.0, 0.0, 0.0)),
                ("shiny8", shiny(8.0)),
                ("shiny64", shiny(64.0)),
            ] {
                v.push(
                    Case::new(
                        format!("grazing n{j} cos{k} {m_name} dir"),
                        m.clone(),
                        vec![dir(l, 1.0)],
                    )
                    .at([0.1, 0.2, -3.0], nrm),
                );
                let p = [0.1, 0.2, -3.0];
                let lp = [0, 1, 2].map(|i| p[i] + 2.0 * l[i]);
                v.push(
                    Case::new(
                        format!("grazing n{j} cos{k} {m_name} point"),
                        m,
                        vec![point(lp, 1.0, NO_ATT)],
                    )
                    .at(p, nrm),
                );
            }
        }
    }
    v
}

/// Lights at distance 0.001 and 10 000, attenuation constants 10⁻⁶ … 10⁶.
fn distance_cases() -> Vec<Case> {
    let mut v = Vec::new();
    let p = [0.25, -0.5, -2.0];
    let nrm = normalized([0.1, 0.2, 1.0]);
    let dirs = [normalized([0.0, 0.0, 1.0]), normalized([0.5, 0.5, 0.7])];
    let consts = [1e-6, 1e-3, 1.0, 1e3, 1e6];
    for (di, d) in dirs.into_iter().enumerate() {
        for dist in [0.001, 0.01, 1.0, 100.0, 10_000.0] {
            let lp = [0, 1, 2].map(|i| p[i] + dist * d[i]);
            let mut atts = vec![NO_ATT, [0.0; 3]];
            for &c in &consts {
                atts.push([c, 0.0, 0.0]);
                atts.push([0.0, c, 0.0]);
                atts.push([0.0, 0.0, c]);
                atts.push([1.0, c, c]);
            }
            for att in atts {
                let name = format!("dist {dist} dir{di} att {att:?}");
                v.push(
                    Case::new(
                        format!("{name} point"),
                        shiny(32.0),
                        vec![point(lp, 1.0, att)],
                    )
                    .at(p, nrm),
                );
                let sp = LightDesc::Spot {
                    position: lp,
                    axis: d.map(|x| -x),
                    cutoff_deg: 20.0,
                    exponent: 2.0,
                    diffuse: [1.0; 3],
                    specular: [1.0; 3],
                    attenuation: att,
                };
                v.push(Case::new(format!("{name} spot"), shiny(32.0), vec![sp]).at(p, nrm));
            }
            // Area lights far away and very close.
            let a = LightDesc::Area {
                center: lp,
                edge_u: [0.4 * dist, 0.0, 0.0],
                edge_v: [0.0, 0.3 * dist, 0.0],
                samples_k: 2,
                diffuse: [1.0; 3],
                specular: [1.0; 3],
                attenuation: [1.0, 0.1, 0.0],
            };
            v.push(Case::new(format!("dist {dist} dir{di} area"), shiny(32.0), vec![a]).at(p, nrm));
        }
    }
    v
}

/// Spot cutoffs 0.5°, 30°, 90° and exponents up to 128, inside and
/// outside the cone.
fn spot_cases() -> Vec<Case> {
    let mut v = Vec::new();
    let p = [0.0, 0.0, -2.0];
    for cutoff in [0.5f64, 30.0, 90.0] {
        for exp in [0.0, 1.0, 2.0, 8.0, 32.0, 128.0] {
            // γ as a fraction of the cutoff: on the axis, well inside,
            // near the edge (but not on it: a tie there is a jump).
            for frac in [0.0, 0.3, 0.7, 0.9, 1.2] {
                let g = (cutoff * frac).min(89.0_f64).to_radians();
                // The spot sits at distance 3 from P, at angle g off its axis.
                let axis = normalized([0.2, -0.3, -1.0]);
                let side = normalized([1.0, 0.0, 0.2]);
                let from_p = [0, 1, 2].map(|i| -axis[i] * g.cos() + side[i] * g.sin());
                let pos = [0, 1, 2].map(|i| p[i] + 3.0 * from_p[i]);
                let nrm = normalized([from_p[0] + 0.1, from_p[1], from_p[2] + 0.3]);
                v.push(
                    Case::new(
                        format!("spot cutoff {cutoff} exp {exp} frac {frac}"),
                        shiny(16.0),
                        vec![spot(pos, axis, cutoff, exp, 1.0)],
                    )
                    .at(p, nrm),
                );
            }
        }
    }
    v
}

/// Intensities and colours above 1 that clamp, 16 lights summing past 1,
/// emission.
fn clamp_cases() -> Vec<Case> {
    let mut v = Vec::new();
    let p = [0.1, 0.1, -2.0];
    let nrm = normalized([0.1, 0.1, 1.0]);
    for i in [1.5, 3.0, 10.0, 100.0, 255.0] {
        v.push(
            Case::new(
                format!("bright dir {i}"),
                shiny(8.0),
                vec![dir([0.3, 0.2, 1.0], i)],
            )
            .at(p, nrm),
        );
        v.push(
            Case::new(
                format!("bright point {i}"),
                shiny(8.0),
                vec![point([0.5, 0.5, 1.0], i, [1.0, 0.2, 0.1])],
            )
            .at(p, nrm),
        );
        // A bright light that still leaves a channel below 1.
        let dim = LightDesc::Directional {
            direction: [0.0, 0.3, 1.0],
            diffuse: [i, i / 50.0, i / 400.0],
            specular: [0.0; 3],
        };
        v.push(
            Case::new(
                format!("bright mixed {i}"),
                material(0.0, 0.1, 0.8, 0.0, 0.0),
                vec![dim],
            )
            .at(p, nrm),
        );
    }
    for (k, c) in [1.2, 2.0, 5.0].into_iter().enumerate() {
        let m = MaterialDesc {
            emission: [0.0; 3],
            ambient: [c, 0.5, 0.1],
            diffuse: [c, c * 0.3, 0.05],
            specular: [c; 3],
            shininess: 20.0,
        };
        v.push(
            Case::new(
                format!("material above 1 #{k}"),
                m,
                vec![dir([0.5, 0.4, 1.0], 0.7)],
            )
            .at(p, nrm),
        );
    }
    // 16 lights of 0.1 each: the sum passes 1 in some channels only.
    let sixteen: Vec<LightDesc> = (0..16)
        .map(|j| {
            let a = j as f64 * 0.39;
            match j % 4 {
                0 => dir([a.cos(), a.sin(), 1.5], 0.12),
                1 => point([2.0 * a.cos(), 2.0 * a.sin(), 1.0], 0.12, [1.0, 0.1, 0.0]),
                2 => spot(
                    [a.cos(), a.sin(), 0.5],
                    [-a.cos() * 0.3, -a.sin() * 0.3, -1.0],
                    60.0,
                    2.0,
                    0.12,
                ),
                _ => area([a.cos(), a.sin(), 1.0], 2, 0.12, NO_ATT),
            }
        })
        .collect();
    v.push(Case::new("16 lights", shiny(10.0), sixteen.clone()).at(p, nrm));
    v.push(
        Case::new(
            "16 lights dim material",
            material(0.0, 0.1, 0.3, 0.1, 10.0),
            sixteen.clone(),
        )
        .at(p, nrm),
    );
    v.push(Case::new("16 lights grey", material(0.0, 0.0, 0.5, 0.0, 0.0), sixteen).at(p, nrm));
    // Emission alone, emission plus light, emission above 1.
    for e in [0.0, 0.25, 0.5, 1.0, 1.7] {
        let m = material(e, 0.2, 0.5, 0.3, 12.0);
        v.push(Case::new(format!("emission {e}"), m.clone(), vec![]).at(p, nrm));
        v.push(
            Case::new(
                format!("emission {e} lit"),
                m,
                vec![dir([0.2, 0.1, 1.0], 0.6)],
            )
            .at(p, nrm),
        );
    }
    // Ambient above 1.
    v.push(
        Case::new("ambient 3", material(0.0, 0.3, 0.5, 0.0, 0.0), vec![])
            .ambient([3.0, 1.0, 0.2])
            .at(p, nrm),
    );
    v
}

fn all_hand_picked() -> Vec<(&'static str, Vec<Case>)> {
    vec![
        ("light kinds", light_kind_cases()),
        ("shininess 0..2048", shininess_cases()),
        ("grazing", grazing_cases()),
        ("distances and attenuation", distance_cases()),
        ("spot cones", spot_cases()),
        ("clamping, 16 lights, emission", clamp_cases()),
    ]
}

#[test]
fn every_light_kind() {
    sweep("light kinds", &light_kind_cases());
}

#[test]
fn shininess_0_to_2048_both_models() {
    sweep("shininess", &shininess_cases());
}

#[test]
fn grazing_angles() {
    sweep("grazing", &grazing_cases());
}

#[test]
fn near_and_far_lights_with_attenuation() {
    sweep("distance", &distance_cases());
}

#[test]
fn spot_cutoffs_and_exponents() {
    sweep("spot", &spot_cases());
}

#[test]
fn clamping_many_lights_and_emission() {
    sweep("clamp", &clamp_cases());
}

/// The whole hand-picked sweep, with the share of exact results (run with
/// `--nocapture` to see it).
#[test]
fn hand_picked_sweep_exact_share() {
    let mut total = Tally::default();
    for (name, cases) in all_hand_picked() {
        let mut t = Tally::default();
        for c in &cases {
            t.add_all(c);
        }
        println!(
            "hand-picked {name:32} {:5} evaluations  {:6.2}% exact  max {:?} LSB",
            t.evaluated,
            100.0 * t.share(),
            t.max_err
        );
        total.evaluated += t.evaluated;
        total.exact += t.exact;
        for k in 0..3 {
            total.max_err[k] = total.max_err[k].max(t.max_err[k]);
        }
        total.failures.extend(t.failures);
    }
    total.assert_ok("hand-picked total");
    assert!(
        total.share() >= 0.9,
        "only {:.2}% exact",
        100.0 * total.share()
    );
}

/// A shininess in (0, 1/512) — found by the random test. The kernel's
/// exponent has 8 fractional bits, so it rounds such an `n` to 0, and then
/// `x^0 = 1` (SPEC.md 3) applies even where `max(R·V, 0) = 0`, while the
/// reference's `0^n` with `n > 0` is 0: the full `Is·Ks` appears where
/// there should be no highlight at all.
#[test]
fn tiny_nonzero_shininess() {
    let mut t = Tally::default();
    for n in [2.7e-4, 1e-3, 1.9e-3] {
        let m = MaterialDesc {
            emission: [0.0; 3],
            ambient: [0.0; 3],
            diffuse: [0.0; 3],
            specular: [0.0, 0.0, 0.298],
            shininess: n,
        };
        let light = LightDesc::Directional {
            direction: [0.5509, -0.8156, 0.1771],
            diffuse: [0.0; 3],
            specular: [0.0, 0.0, 1.0075],
        };
        // N·L = 0.55 > 0 but R·V = −0.18 (Phong) and, with the normal
        // turned away from the viewer, N·H < 0 (Blinn): spec = 0^n = 0.
        t.add_all(
            &Case::new(format!("shininess {n}"), m.clone(), vec![light.clone()])
                .at([0.0, 0.0, -5.45], [1.0, 0.0, 0.0]),
        );
        t.add_all(
            &Case::new(format!("shininess {n} back-lit"), m, vec![light])
                .at([0.0, 0.0, -5.45], normalized([0.6, -0.3, -0.74])),
        );
    }
    t.assert_ok("tiny shininess");
}

/// Sanity checks that the comparison itself can fail: a kernel colour is
/// compared with the right reference, and a wrong description is caught.
#[test]
fn comparison_detects_a_wrong_side() {
    let good = Case::new("probe", shiny(8.0), vec![dir([0.3, 0.4, 1.0], 1.0)]);
    let o = good.eval(SpecularModel::Blinn, Viewer::Infinite);
    assert!(o.err.iter().all(|&e| e <= 1));
    assert!(channels(o.expected)[0] > 10, "the probe is lit");
    // The reference of a different material must be far from the kernel.
    let mut other = good.clone();
    other.material.diffuse = [0.1; 3];
    let k = channels(
        good.kernel_all(SpecularModel::Blinn, Viewer::Infinite)
            .to_rgb565(),
    );
    let r = channels(from_raw(quantize_rgb565(
        other.reference(SpecularModel::Blinn, Viewer::Infinite),
    )));
    assert!((k[0] - r[0]).abs() > 1);
}

// ---------------------------------------------------------------------------
// Random cases
// ---------------------------------------------------------------------------

fn unit() -> impl Strategy<Value = [f64; 3]> {
    (-1.0f64..1.0, 0.0f64..std::f64::consts::TAU).prop_map(|(z, phi)| {
        let r = (1.0 - z * z).sqrt();
        [r * phi.cos(), r * phi.sin(), z]
    })
}

fn pos() -> impl Strategy<Value = [f64; 3]> {
    [-10.0f64..10.0, -10.0f64..10.0, -10.0f64..10.0]
}

fn colour() -> impl Strategy<Value = [f64; 3]> {
    [0.0f64..2.0, 0.0f64..2.0, 0.0f64..2.0]
}

fn attenuation() -> impl Strategy<Value = [f64; 3]> {
    prop_oneof![
        Just(NO_ATT),
        [0.0f64..2.0, 0.0f64..1.0, 0.0f64..0.5],
        [0.0f64..1e-3, 0.0f64..1e-3, 0.0f64..1e-3],
    ]
}

fn light() -> impl Strategy<Value = LightDesc> {
    prop_oneof![
        (unit(), colour(), colour()).prop_map(|(direction, diffuse, specular)| {
            LightDesc::Directional {
                direction,
                diffuse,
                specular,
            }
        }),
        (pos(), colour(), colour(), attenuation()).prop_map(
            |(position, diffuse, specular, attenuation)| LightDesc::Point {
                position,
                diffuse,
                specular,
                attenuation,
            }
        ),
        (
            pos(),
            unit(),
            0.0f64..=90.0,
            0.0f64..=128.0,
            colour(),
            colour(),
            attenuation()
        )
            .prop_map(
                |(position, axis, cutoff_deg, exponent, diffuse, specular, attenuation)| {
                    LightDesc::Spot {
                        position,
                        axis,
                        cutoff_deg,
                        exponent,
                        diffuse,
                        specular,
                        attenuation,
                    }
                }
            ),
        (
            pos(),
            [-2.0f64..2.0, -2.0f64..2.0, -2.0f64..2.0],
            [-2.0f64..2.0, -2.0f64..2.0, -2.0f64..2.0],
            1u32..=3,
            colour(),
            colour(),
            attenuation()
        )
            .prop_map(
                |(center, edge_u, edge_v, samples_k, diffuse, specular, attenuation)| {
                    LightDesc::Area {
                        center,
                        edge_u,
                        edge_v,
                        samples_k,
                        diffuse,
                        specular,
                        attenuation,
                    }
                }
            ),
    ]
}

/// Shininess 0, or in [1/512, 2048]: (0, 1/512) is the separate test
/// [`tiny_nonzero_shininess`].
fn shininess() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(0.0),
        1.0 / 512.0..4.0f64,
        1.0 / 512.0..64.0f64,
        1.0 / 512.0..=2048.0f64
    ]
}

fn random_case() -> impl Strategy<Value = Case> {
    (
        colour(),
        colour(),
        colour(),
        colour(),
        shininess(),
        [0.0f64..1.0, 0.0f64..1.0, 0.0f64..1.0],
        prop::collection::vec(light(), 1..=4),
        pos(),
        unit(),
    )
        .prop_map(|(e, a, d, s, n, amb, lights, p, nrm)| Case {
            name: "random".into(),
            material: MaterialDesc {
                // Emission small enough that the sum is not always clamped.
                emission: e.map(|x| x * 0.1),
                ambient: a,
                diffuse: d,
                specular: s,
                shininess: n,
            },
            ambient: amb,
            lights,
            p,
            n: nrm,
        })
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Whether the case sits on one of SPEC.md 3's discontinuities, where any
/// rounding of the inputs flips a term on or off: N·L at 0 (the specular
/// term switches), a spot's cone edge, a light on the point, a local
/// viewer at the point, L + V = 0.
fn near_discontinuity(c: &Case) -> bool {
    const EPS: f64 = 2e-3;
    let n = normalized(c.n);
    let v_local = normalized(c.p.map(|x| -x));
    if dot(c.p, c.p).sqrt() < 1e-2 {
        return true;
    }
    for l in eye_lights(&c.lights, &IDENTITY) {
        let (to, spot) = match &l {
            EyeLight::Directional { to_light, .. } => (*to_light, None),
            EyeLight::Point { position, .. } => ([0, 1, 2].map(|i| position[i] - c.p[i]), None),
            EyeLight::Spot {
                position,
                axis,
                cos_cutoff,
                ..
            } => (
                [0, 1, 2].map(|i| position[i] - c.p[i]),
                Some((*axis, *cos_cutoff)),
            ),
        };
        if dot(to, to).sqrt() < 1e-2 {
            return true;
        }
        let l = normalized(to);
        if dot(n, l).abs() < EPS {
            return true;
        }
        if let Some((axis, cc)) = spot {
            if (-dot(l, axis) - cc).abs() < EPS {
                return true;
            }
        }
        for v in [[0.0, 0.0, 1.0], v_local] {
            if dot(l, v) < -1.0 + EPS {
                return true;
            }
            // The specular base at 0, where max(x, 0)^n has its kink (and,
            // for small n, a near-jump).
            let r = [0, 1, 2].map(|i| 2.0 * dot(n, l) * n[i] - l[i]);
            let h = normalized([0, 1, 2].map(|i| l[i] + v[i]));
            if dot(r, v).abs() < EPS || dot(n, h).abs() < EPS {
                return true;
            }
        }
    }
    false
}

fn config(default_cases: u32) -> ProptestConfig {
    let cases = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default_cases);
    ProptestConfig {
        cases,
        max_global_rejects: cases / 4 + 1024,
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

proptest! {
    #![proptest_config(config(4096))]

    #[test]
    fn random_inputs_within_one_lsb(c in random_case()) {
        prop_assume!(!near_discontinuity(&c));
        for model in MODELS {
            for viewer in VIEWERS {
                let o = c.eval(model, viewer);
                prop_assert!(
                    o.err.iter().all(|&e| e <= 1),
                    "[{:?}, {:?}] kernel {:?} expected {:?} (ref {:?}) err {:?}",
                    model, viewer, channels(o.kernel), channels(o.expected), o.reference, o.err
                );
            }
        }
    }
}

/// The colour `lights` give a point `p` facing +z (`Q.16` bits), diffuse
/// material `m`, no ambient.
fn diffuse_at<L: LightSet>(m: &Material<NoSpecular>, lights: &L, p: Vec3) -> [u32; 3] {
    Lighting::<NoSpecular, InfiniteViewer, _>::new(m, Rgb::BLACK, lights, &Mat4::IDENTITY)
        .shade(p, Unit3::Z)
        .to_bits()
}

/// An area light of zero extent is k² samples at its centre, each carrying
/// 1/k²: the same light as a point light there, for every k, within one
/// `Q.16` unit before quantisation (the sum is divided once; a share folded
/// into each sample's gain was 2 LSB off in green at k = 64), and within
/// 1 LSB of the reference across a row of points, both specular models and
/// viewers.
#[test]
fn zero_extent_area_light_is_a_point_light() {
    let m = Material::new().with_diffuse(rgb([0.8; 3]));
    let lamp = PointLight::new([0.0, 0.0, 2.0]).unwrap();
    let mut cases = Vec::new();
    for k in [1u8, 2, 3, 16, 63, AreaLight::MAX_K] {
        let area = AreaLight::new([0.0, 0.0, 2.0], [0.0; 3], [0.0; 3], k).unwrap();
        for i in 0..=40 {
            let x = i as f32 * 0.025;
            let p = Vec3::from_f32(x, 0.0, 0.0).unwrap();
            let (a, b) = (diffuse_at(&m, &area, p), diffuse_at(&m, &lamp, p));
            for c in 0..3 {
                assert!(
                    a[c].abs_diff(b[c]) <= 1,
                    "k {k} x {x}: area {a:?} point {b:?}"
                );
            }
        }
        for (x, spec) in [(0.39, 0.0), (0.2, 0.5), (0.7, 1.0)] {
            let mut mat = material(0.0, 0.0, 0.8, spec, 24.0);
            mat.diffuse = [0.8; 3];
            let light = LightDesc::Area {
                center: [0.0, 0.0, 2.0],
                edge_u: [0.0; 3],
                edge_v: [0.0; 3],
                samples_k: u32::from(k),
                diffuse: [1.0; 3],
                specular: [1.0; 3],
                attenuation: NO_ATT,
            };
            cases.push(
                Case::new(format!("zero-extent area k {k} at x {x}"), mat, vec![light])
                    .at([x, 0.0, 0.0], [0.0, 0.0, 1.0])
                    .ambient([0.0; 3]),
            );
        }
    }
    sweep("zero-extent area lights", &cases);
}
