//! Where S1's instructions go by pipeline stage, beside the stage budgets:
//! each instruction of the per-address profile (`scripts/firmware_profile.sh`
//! with `KEEP_PROFILE`) is given to a stage by the linked function it lies
//! in and, in the functions that mix levels, by how often it ran.

use std::fmt::Write as _;
use std::path::Path;

use super::{read, Frame};

/// A stage's budget per unit: M4F, M0+.
type Budget = Option<(u32, u32)>;

/// A target: figure, this run's value, must, goal, in bytes (else
/// instructions).
struct Target(&'static str, Option<u64>, f64, Option<f64>, bool);

/// The stages, in the order of the table: name, unit, budget.
const STAGES: [(&str, &str, Budget); 8] = [
    (
        "vertex (transform, reciprocal, snap, flags)",
        "vertex",
        Some((110, 200)),
    ),
    (
        "lighting (vertices a drawn triangle uses)",
        "lit vertex",
        None,
    ),
    ("triangle loop: cull and reject", "triangle", Some((40, 60))),
    ("set-up and walk", "drawn triangle", Some((600, 950))),
    ("rows (walk and span entry)", "row", Some((35, 60))),
    ("pixels", "pixel", Some((20, 30))),
    ("per draw (constants, loops' entries)", "draw", None),
    (
        "library routines (called from the stages above)",
        "draw",
        None,
    ),
];

/// The stage of an instruction of function `f` that ran `c` times, in a
/// frame of `d` triangles set up and `p` pixels.
fn stage(f: &str, c: u64, d: u64, p: u64) -> usize {
    let draw = c < d / 4;
    if f.starts_with("__") || f.starts_with("compiler_builtins::") {
        7
    } else if f.contains("::project_all") {
        0
    } else if [
        "Stage<S,V,L>::light",
        "::light_corner",
        "Lighting<S,V,L>::shade",
        "normalize::",
        "specular_table::",
    ]
    .iter()
    .any(|k| f.contains(k))
    {
        1
    } else if f.contains("::draw_framebuffer") || f.contains("gouraud_run") {
        if c > d {
            2
        } else if draw {
            6
        } else {
            3
        }
    } else if f.contains("Frame<S,V,L>::draw") || is_row_loop(f) {
        if c >= p {
            5
        } else if c > 2 * d {
            4
        } else if draw {
            6
        } else {
            3
        }
    } else if (f.contains("setup::set_up") || f.contains("gouraud_set_up")) && c > 4 * d {
        // The walk's rows, stepped inside the set-up (the M4F's in its
        // one routine of assembly): more often than a triangle's four
        // attributes (depth and three colours).
        4
    } else if [
        "setup::",
        "walk::",
        "turned_over",
        "Rows::fine",
        "clip::",
        "::gouraud_in_one",
        "gouraud_set_up",
    ]
    .iter()
    .any(|k| f.contains(k))
    {
        if draw {
            6
        } else {
            3
        }
    } else {
        6
    }
}

/// Whether linked function `f` is the Gouraud row loop: the M0+'s
/// `gouraud_depth_rows`, the M4F's routine `fixshade_gouraud_rows`.
fn is_row_loop(f: &str) -> bool {
    f.contains("gouraud_depth_rows") || f.contains("fixshade_gouraud_rows")
}

/// Instructions per stage of a kept profile (`dir`: `byaddr.txt`, "0xADDR
/// COUNT" lines, and `syms.txt`, "ADDR\tNAME" lines, addresses in decimal),
/// and the rows walked (the most any instruction of the row loop ran, short
/// of the pixels: S1 fails no depth test).
fn per_stage(dir: &Path, f: &Frame) -> Result<([u64; 8], u64), String> {
    let mut syms: Vec<(u64, String)> = read(&dir.join("syms.txt"))?
        .lines()
        .filter_map(|l| {
            let (a, n) = l.split_once('\t')?;
            Some((a.trim().parse().ok()?, n.to_string()))
        })
        .collect();
    syms.sort();
    let counts: Vec<(u64, u64)> = read(&dir.join("byaddr.txt"))?
        .lines()
        .filter_map(|l| {
            let (a, c) = l.split_once(' ')?;
            let a = u64::from_str_radix(a.trim_start_matches("0x"), 16).ok()?;
            Some((a, c.trim().parse().ok()?))
        })
        .collect();
    if syms.is_empty() || counts.is_empty() {
        return Err(format!("{}: an empty profile", dir.display()));
    }
    let name = |a: u64| {
        let i = syms.partition_point(|(s, _)| *s <= a);
        if i == 0 {
            ""
        } else {
            syms[i - 1].1.as_str()
        }
    };
    let rows = counts
        .iter()
        .filter(|(a, c)| is_row_loop(name(*a)) && *c < f.pixels)
        .map(|(_, c)| *c)
        .max()
        .ok_or("no row loop in the profile")?;
    let mut s = [0u64; 8];
    for (a, c) in &counts {
        s[stage(name(*a), *c, f.drawn, f.pixels)] += c;
    }
    Ok((s, rows))
}

/// The stage table of S1 (`m4`, `m0`: its frames on the two cores) from
/// the kept profiles under `raw/TARGET/profile_0_raw`.
pub(super) fn stage_table(
    raw: &Path,
    m4: &Frame,
    m0: &Frame,
    md: &mut String,
) -> Result<(), String> {
    let (a, rows4) = per_stage(&raw.join(super::TARGETS[0].0).join("profile_0_raw"), m4)?;
    let (b, rows0) = per_stage(&raw.join(super::TARGETS[1].0).join("profile_0_raw"), m0)?;
    if rows4 != rows0 {
        return Err(format!(
            "S1 walks {rows4} rows on the M4F, {rows0} on the M0+"
        ));
    }
    let units = [
        m4.vertices,
        m4.lit,
        m4.triangles,
        m4.drawn,
        rows4,
        m4.pixels,
        1,
        1,
    ];
    let _ = writeln!(
        md,
        "S1 by stage, beside the stage budgets: each instruction of the per-address profile \
         (below) goes to the stage of the linked function it lies in (`project_all`: vertex; \
         the lighting functions, with the M4F triangle loop's call of them, `light_corner`; \
         library routines apart); in the triangle loop \
         (`draw_framebuffer`, and on the M4F `gouraud_run`, the lean triangle loop in one \
         routine of assembly with its Rust caller) what ran more often than once a triangle \
         set up is the cull and reject, what ran less often is the set-up's; in the walk \
         (`Frame::draw`) and the row loop (`gouraud_depth_rows`, on the M4F the routine \
         `fixshade_gouraud_rows`) what ran once a pixel is per pixel, what ran more often \
         than twice a triangle set up per row ({rows4} rows: the most any instruction of the \
         row loop ran, short of the pixels), else the set-up's; in the set-up (`set_up`, \
         which walks the rows of most triangles, and on the M4F `fixshade_gouraud_set_up`, \
         the Gouraud set-up in one routine of assembly, which calls the row loop) what ran \
         more often than four times a triangle set up (its attributes) per row; the edges' quotients found by steps \
         (`walk::Edge::stepped`, out of line) are the set-up's; what ran fewer times than a \
         quarter of the triangles set up, anywhere, is the draw's own. The library routines' \
         calls are not followed to their callers.\n\n\
         | stage | unit | units | M4F per unit | budget | M0+ per unit | budget |\n\
         | --- | --- | ---: | ---: | ---: | ---: | ---: |"
    );
    for (k, (name, unit, budget)) in STAGES.iter().enumerate() {
        let per = |s: &[u64; 8]| s[k] as f64 / units[k].max(1) as f64;
        let (p4, p0) = (per(&a), per(&b));
        let cell = |p: f64, lim: Option<u32>| match lim {
            Some(l) => (
                format!("{p:.0}"),
                format!("≤ {l}{}", if p <= l as f64 { " ✓" } else { "" }),
            ),
            None => (format!("{p:.0}"), "—".to_string()),
        };
        let (c4, l4) = cell(p4, budget.map(|b| b.0));
        let (c0, l0) = cell(p0, budget.map(|b| b.1));
        let _ = writeln!(
            md,
            "| {name} | {unit} | {} | {c4} | {l4} | {c0} | {l0} |",
            units[k]
        );
    }
    let _ = writeln!(md);
    Ok(())
}

/// The frame and size targets: figure, this run's value, must, goal.
pub(super) fn target_table(
    raw: &Path,
    m4: &[Frame],
    m0: &[Frame],
    microbit_s1: u64,
    md: &mut String,
    js: &mut String,
) -> Result<(), String> {
    let find = |v: &[Frame], n: &str| {
        v.iter()
            .find(|f| f.name == n)
            .map(|f| f.instructions)
            .ok_or(format!("no {n}"))
    };
    let config = |level: &str| -> Result<Option<u64>, String> {
        let p = raw
            .join("config")
            .join(super::TARGETS[1].0)
            .join(level)
            .join("size.txt");
        if p.is_file() {
            Ok(Some(super::text_bytes(&read(&p)?)))
        } else {
            Ok(None)
        }
    };
    let m = 1_000_000.0;
    let rows = [
        Target(
            "M4F S1",
            Some(find(m4, "s1_gouraud")?),
            1.2 * m,
            Some(0.8 * m),
            false,
        ),
        Target(
            "M0+ S1",
            Some(find(m0, "s1_gouraud")?),
            2.0 * m,
            Some(1.3 * m),
            false,
        ),
        Target(
            "M4F S3",
            Some(find(m4, "s3_gouraud")?),
            10.0 * m,
            Some(6.0 * m),
            false,
        ),
        Target(
            "M0+ S3",
            Some(find(m0, "s3_gouraud")?),
            18.0 * m,
            None,
            false,
        ),
        Target(
            "M4F S4 (Phong shading)",
            Some(find(m4, "s4_phong")?),
            12.0 * m,
            Some(6.0 * m),
            false,
        ),
        Target("M0+ S4", Some(find(m0, "s4_phong")?), 25.0 * m, None, false),
        Target(
            "M4F S2",
            Some(find(m4, "s2_gouraud")?),
            0.55 * m,
            None,
            false,
        ),
        Target(
            "16 KB Cortex-M0, S1 in 4-row bands",
            Some(microbit_s1),
            10.0 * m,
            Some(4.0 * m),
            false,
        ),
        Target(
            ".text, S1's configuration, M0+ (runtime included)",
            config("s1")?,
            32.0 * 1024.0,
            Some(16.0 * 1024.0),
            true,
        ),
        Target(
            ".text, S1's configuration without the kernel's `clip` feature, M0+ (runtime included)",
            config("s1_noclip")?,
            32.0 * 1024.0,
            Some(16.0 * 1024.0),
            true,
        ),
        Target(
            ".text, ambient-only configuration, M0+",
            config("ambient")?,
            20.0 * 1024.0,
            None,
            true,
        ),
        Target(
            ".text, ambient-only configuration without `clip`, M0+",
            config("ambient_noclip")?,
            20.0 * 1024.0,
            None,
            true,
        ),
    ];
    let _ = writeln!(
        md,
        "## Targets\n\n\
         Instructions per frame (from the tables above) or bytes of `.text` (from the flash/RAM \
         table below; —: not built in a quick run).\n\n\
         | figure | this run | must | goal | must met |\n\
         | --- | ---: | ---: | ---: | --- |"
    );
    let show = |v: f64, bytes: bool| {
        if bytes {
            format!("{:.1} KB", v / 1024.0)
        } else {
            format!("{:.3} M", v / m)
        }
    };
    let mut entries = Vec::new();
    for Target(name, now, must, goal, bytes) in rows {
        let _ = writeln!(
            md,
            "| {name} | {} | ≤ {} | {} | {} |",
            now.map_or("—".to_string(), |n| show(n as f64, bytes)),
            show(must, bytes),
            goal.map_or("—".to_string(), |g| format!("≤ {}", show(g, bytes))),
            match now {
                Some(n) if n as f64 <= must => "yes",
                Some(_) => "no",
                None => "—",
            }
        );
        entries.push(format!(
            "{{\"figure\": {}, \"value\": {}, \"must\": {must}}}",
            super::json_str(name),
            super::opt(now)
        ));
    }
    let _ = writeln!(md);
    let _ = writeln!(js, "  \"targets\": [{}],", entries.join(", "));
    Ok(())
}
