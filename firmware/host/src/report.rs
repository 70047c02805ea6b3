//! `--report RAW_DIR REPORT_DIR [PEERS_TSV]`: turns what
//! scripts/firmware.sh collected (console lines, plugin counts,
//! `arm-none-eabi-size -A` output) into `REPORT_DIR/firmware_counts.json`
//! and `REPORT_DIR/firmware.md`, with tgx's instruction counts from
//! `PEERS_TSV` beside ours (see [`peers`]).

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::fs;
use std::path::Path;

mod budgets;
mod draw_call;

/// Cycles per instruction assumed for the estimates (see `ESTIMATE_BASIS`).
const CPI_M4: f64 = 1.3;
const CPI_M0: f64 = 1.4;
const MHZ_F4: f64 = 168.0;
const MHZ_RP2040: f64 = 133.0;

const ESTIMATE_BASIS: &str = "Cycles are estimates, not measurements: instructions × an assumed \
average of 1.3 cycles per instruction on the Cortex-M4 (most data-processing instructions and \
multiplies 1 cycle, loads 2 unless pipelined, taken branches 2–4; code assumed to hit the \
STM32F4's ART flash cache) and 1.4 on the RP2040's Cortex-M0+ (loads, stores and taken \
branches 2 cycles, the single-cycle multiplier; code from SRAM or hitting the XIP cache). \
The M0+ counts are of thumbv6m code whose divisions are software `__aeabi_uidiv` calls; \
on an RP2040 the HAL's hardware-divider intrinsics make those cheaper.";

const TARGETS: [(&str, &str); 2] = [
    ("thumbv7em-none-eabihf", "Cortex-M4F"),
    ("thumbv6m-none-eabi", "Cortex-M0+"),
];

/// The configurations of the flash/RAM table: level (firmware/qemu
/// feature), what it renders, and the level its Δ columns are taken
/// against.
const LEVELS: [(&str, &str, Option<&str>); 11] = [
    ("none", "runtime only (no render call)", None),
    (
        "ambient",
        "ambient only (`()` lights, `NoSpecular`, Gouraud, `NoDepth`)",
        Some("none"),
    ),
    (
        "lambert",
        "+ Lambert (one `DirectionalLight`)",
        Some("ambient"),
    ),
    (
        "specular",
        "+ directional specular (`BlinnPhong`)",
        Some("lambert"),
    ),
    ("point", "+ point light with attenuation", Some("specular")),
    ("spot", "+ spot light", Some("point")),
    ("depth", "+ depth buffer (`DepthBuffer`)", Some("spot")),
    ("phong", "+ Phong shading (`PhongShading`)", Some("depth")),
    (
        "s1",
        "**S1 as drawn**: one `DirectionalLight`, `BlinnPhong`, Gouraud, `DepthBuffer`, culling (Δ against \"+ directional specular\")",
        Some("specular"),
    ),
    (
        "s1_noclip",
        "**S1 as drawn, without the kernel's `clip` feature** (no near or guard-band clipping: a draw that would need it is refused; Δ against S1 as drawn)",
        Some("s1"),
    ),
    (
        "ambient_noclip",
        "ambient only, without the kernel's `clip` feature (Δ against ambient only)",
        Some("ambient"),
    ),
];

/// The standard frames (each scene in its own shading mode), in the
/// order of the table beside tgx.
const STANDARD: [(&str, &str); 4] = [
    ("S1", "s1_gouraud"),
    ("S2", "s2_gouraud"),
    ("S3", "s3_gouraud"),
    ("S4", "s4_phong"),
];

/// `key=value` pairs of a console line.
fn fields(line: &str) -> BTreeMap<String, String> {
    line.split_whitespace()
        .filter_map(|w| w.split_once('='))
        .map(|(k, v)| (k.to_string(), v.to_string()))
        .collect()
}

fn num(m: &BTreeMap<String, String>, k: &str) -> Result<u64, String> {
    m.get(k)
        .ok_or_else(|| format!("missing {k}"))?
        .parse()
        .map_err(|e| format!("{k}: {e}"))
}

fn read(p: &Path) -> Result<String, String> {
    fs::read_to_string(p).map_err(|e| format!("{}: {e}", p.display()))
}

fn counts(p: &Path) -> Result<Vec<u64>, String> {
    read(p)?
        .lines()
        .map(|l| {
            l.trim()
                .parse()
                .map_err(|e| format!("{}: {e}", p.display()))
        })
        .collect()
}

struct Frame {
    name: String,
    triangles: u64,
    drawn: u64,
    pixels: u64,
    vertices: u64,
    lit: u64,
    instructions: u64,
    stack: u64,
}

fn frames(dir: &Path) -> Result<Vec<Frame>, String> {
    let log = read(&dir.join("console.log"))?;
    let c = counts(&dir.join("counts.txt"))?;
    let lines: Vec<&str> = log.lines().filter(|l| l.starts_with("frame ")).collect();
    if lines.len() != c.len() {
        return Err(format!(
            "{}: {} frames, {} counts",
            dir.display(),
            lines.len(),
            c.len()
        ));
    }
    lines
        .iter()
        .zip(c)
        .map(|(l, n)| {
            let f = fields(l);
            Ok(Frame {
                name: l.split_whitespace().nth(1).unwrap_or("?").to_string(),
                triangles: num(&f, "triangles")?,
                drawn: num(&f, "drawn")?,
                pixels: num(&f, "pixels")?,
                vertices: num(&f, "vertices")?,
                lit: num(&f, "lit")?,
                instructions: n,
                stack: num(&f, "stack")?,
            })
        })
        .collect()
}

struct Config {
    text: u64,
    rodata: u64,
    bss: u64,
    stack: u64,
    instructions: Option<u64>,
    pixels: u64,
}

/// The code of an `arm-none-eabi-size -A` listing: .text and the vector
/// table.
fn text_bytes(size: &str) -> u64 {
    section(size, ".text") + section(size, ".vector_table")
}

fn section(size: &str, name: &str) -> u64 {
    size.lines()
        .filter_map(|l| {
            let mut w = l.split_whitespace();
            (w.next() == Some(name)).then(|| w.next()?.parse().ok())?
        })
        .next()
        .unwrap_or(0)
}

fn config(dir: &Path) -> Result<Config, String> {
    let size = read(&dir.join("size.txt"))?;
    let log = read(&dir.join("console.log"))?;
    let f = fields(
        log.lines()
            .find(|l| l.starts_with("config"))
            .ok_or("no config line")?,
    );
    let instructions = match counts(&dir.join("counts.txt")) {
        Ok(c) => c.first().copied(),
        Err(_) => None,
    };
    Ok(Config {
        text: text_bytes(&size),
        rodata: section(&size, ".rodata"),
        bss: section(&size, ".bss") + section(&size, ".data"),
        stack: num(&f, "stack")?,
        instructions,
        pixels: num(&f, "pixels")?,
    })
}

/// A peer's instruction counts per core and scene.
struct Peers {
    /// (`m4` or `m0`, `S1`…) → instructions of the second frame's draw.
    draw: BTreeMap<(String, String), u64>,
    /// Where the figures come from, for the sentence under the table.
    source: String,
}

/// tgx's rows (`peer` = `tgx`: the `drawMesh` harness) of a peer harness
/// table: `run_all_arm.sh`'s arm.tsv, or the transcription of its results
/// kept in firmware/peers. Tab-separated with a header row naming at least
/// `peer`, `core`, `scene` and `draw2`; lines starting with `#` state the
/// figures' provenance. A later row replaces an earlier one of the same
/// core and scene, as arm.tsv is appended to run after run.
fn peers(p: &Path) -> Result<Peers, String> {
    let text = read(p)?;
    let mut notes = Vec::new();
    let mut header: Option<Vec<&str>> = None;
    let mut draw = BTreeMap::new();
    for line in text.lines() {
        if let Some(n) = line.strip_prefix('#') {
            notes.push(n.trim());
            continue;
        }
        let cells: Vec<&str> = line.split('\t').map(str::trim).collect();
        let Some(h) = &header else {
            header = Some(cells);
            continue;
        };
        let col = |name: &str| -> Result<&str, String> {
            h.iter()
                .position(|c| *c == name)
                .and_then(|i| cells.get(i).copied())
                .ok_or_else(|| format!("{}: no column {name} in {line:?}", p.display()))
        };
        if col("peer")? != "tgx" {
            continue;
        }
        let n = col("draw2")?
            .parse()
            .map_err(|e| format!("{}: draw2 in {line:?}: {e}", p.display()))?;
        draw.insert((col("core")?.to_string(), col("scene")?.to_string()), n);
    }
    let source = if notes.is_empty() {
        format!(
            "column draw2 of `{}`, written by the peer harness's run_all_arm.sh.",
            p.display()
        )
    } else {
        format!("`{}`. {}", p.display(), notes.join(" "))
    };
    Ok(Peers { draw, source })
}

/// `s` as a JSON string literal.
fn json_str(s: &str) -> String {
    let mut o = String::from('"');
    for c in s.chars() {
        match c {
            '"' => o.push_str("\\\""),
            '\\' => o.push_str("\\\\"),
            c if (c as u32) < 0x20 => {
                let _ = write!(o, "\\u{:04x}", c as u32);
            }
            c => o.push(c),
        }
    }
    o.push('"');
    o
}

fn opt(n: Option<u64>) -> String {
    n.map(|n| n.to_string()).unwrap_or_else(|| "null".into())
}

fn ms(instr: u64, cpi: f64, mhz: f64) -> f64 {
    instr as f64 * cpi / (mhz * 1000.0)
}

fn per(a: u64, b: u64) -> f64 {
    if b == 0 {
        0.0
    } else {
        a as f64 / b as f64
    }
}

/// Writes the report files; the table beside tgx if `peers_tsv` is given.
pub fn run(raw: &Path, out: &Path, peers_tsv: Option<&Path>) -> Result<(), String> {
    let m4 = frames(&raw.join(TARGETS[0].0))?;
    let m0 = frames(&raw.join(TARGETS[1].0))?;
    let mut md = String::new();
    let mut js = String::from("{\n");
    let _ = writeln!(
        md,
        "# fixshade on Cortex-M: instructions, flash, RAM, stack\n\n\
         Written by `scripts/firmware.sh`. Instructions are counted by the QEMU plugin \
         `firmware/plugin/insn_count.c` between the markers around each render call \
         (`Renderer::new` and the draw into the `Framebuffer`, callees included; clearing the frame and \
         depth buffer is not counted), 320 × 240, whole-frame buffer. \"M0+\" counts are of the \
         thumbv6m build, run on QEMU's mps2-an386 (its M4 core executes Thumb-1 code unchanged). \
         Every frame is byte-identical to the host's.\n\n{ESTIMATE_BASIS}\n"
    );
    let _ = writeln!(
        md,
        "| scene | shading | triangles | rasterized | pixels | M4 instr/frame | M4 /triangle | M4 /pixel | M0+ instr/frame | M0+ /triangle | M0+ /pixel | STM32F4 168 MHz (est.) | RP2040 133 MHz (est.) | stack M4 / M0+ |\n\
         | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
    );
    js.push_str("  \"frames\": [\n");
    let mut sorted: Vec<(&Frame, &Frame)> = m4.iter().zip(&m0).collect();
    sorted.sort_by(|a, b| a.0.name.cmp(&b.0.name));
    for (i, (a, b)) in sorted.iter().enumerate() {
        let (scene, mode) = a.name.split_once('_').unwrap_or((&a.name, ""));
        let std = matches!(
            a.name.as_str(),
            "s1_gouraud" | "s2_gouraud" | "s3_gouraud" | "s4_phong"
        );
        let _ = writeln!(
            md,
            "| {}{} | {mode} | {} | {} | {} | {} | {:.0} | {:.1} | {} | {:.0} | {:.1} | {:.2} ms | {:.2} ms | {} / {} B |",
            scene.to_uppercase(),
            // ′: a standard scene in another mode (INSIDE is none of them).
            if std || !scene.starts_with('s') { "" } else { "′" },
            a.triangles,
            a.drawn,
            a.pixels,
            a.instructions,
            per(a.instructions, a.triangles),
            per(a.instructions, a.pixels),
            b.instructions,
            per(b.instructions, b.triangles),
            per(b.instructions, b.pixels),
            ms(a.instructions, CPI_M4, MHZ_F4),
            ms(b.instructions, CPI_M0, MHZ_RP2040),
            a.stack,
            b.stack
        );
        let _ = writeln!(
            js,
            "    {{\"name\": \"{}\", \"scene\": \"{}\", \"shading\": \"{mode}\", \"standard\": {std}, \"vertices\": {}, \"triangles\": {}, \"rasterized\": {}, \"pixels\": {}, \
             \"m4_instructions\": {}, \"m0plus_instructions\": {}, \"m4_stack_bytes\": {}, \"m0plus_stack_bytes\": {}, \
             \"stm32f4_168mhz_ms_estimate\": {:.3}, \"rp2040_133mhz_ms_estimate\": {:.3}}}{}",
            a.name,
            scene.to_uppercase(),
            a.vertices,
            a.triangles,
            a.drawn,
            a.pixels,
            a.instructions,
            b.instructions,
            a.stack,
            b.stack,
            ms(a.instructions, CPI_M4, MHZ_F4),
            ms(b.instructions, CPI_M0, MHZ_RP2040),
            if i + 1 < sorted.len() { "," } else { "" }
        );
    }
    js.push_str("  ],\n");
    let _ = writeln!(
        md,
        "\nS1–S4 in their own shading mode; ′: the same scene in another mode. INSIDE: S1's \
         sphere from inside, culling off, both sides lit, cut by the near plane: the triangle \
         loop's kept back faces and the rare path (`src/clip.rs`). UNCULLED: S1 with culling \
         off and one side lit: back faces set up as the front ones are.\n"
    );

    let find = |v: &[Frame], n: &str| v.iter().find(|f| f.name == n).map(|f| f.instructions);
    let _ = writeln!(
        js,
        "  \"cpi_assumed\": {{\"cortex_m4\": {CPI_M4}, \"cortex_m0plus\": {CPI_M0}}},"
    );
    if let Some(p) = peers_tsv {
        let tgx = peers(p)?;
        let _ = writeln!(
            md,
            "## Speed on the devices beside tgx\n\n\
             Instructions per frame, draw only (the renderer's per-frame set-up and the draw call; \
             no clear), counted by the same plugin between the same kind of markers on the same \
             QEMU machine; each scene in its own shading mode. tgx is github.com/vindar/tgx's \
             `Renderer3D` (float, Gouraud, a 16-bit z-buffer where the scene has a depth test) drawing \
             the same triangles with `drawMesh`; how closely its frames match ours is in the peer \
             harness's RESULTS.md.\n\n\
             | scene | fixshade M4F | tgx M4F | fixshade M0+ | tgx M0+ |\n\
             | --- | ---: | ---: | ---: | ---: |"
        );
        let mut rows = Vec::new();
        for (scene, frame) in STANDARD {
            let ours = (
                find(&m4, frame).ok_or(format!("no {frame}"))?,
                find(&m0, frame).ok_or(format!("no {frame}"))?,
            );
            let theirs = |core: &str| {
                tgx.draw
                    .get(&(core.to_string(), scene.to_string()))
                    .copied()
            };
            let (t4, t0) = (theirs("m4"), theirs("m0"));
            let cell = |n: Option<u64>| n.map(|n| n.to_string()).unwrap_or_else(|| "—".into());
            let _ = writeln!(
                md,
                "| {scene} | {} | {} | {} | {} |",
                ours.0,
                cell(t4),
                ours.1,
                cell(t0)
            );
            rows.push(format!(
                "{{\"scene\": \"{scene}\", \"fixshade_m4\": {}, \"tgx_m4\": {}, \"fixshade_m0plus\": {}, \"tgx_m0plus\": {}}}",
                ours.0,
                opt(t4),
                ours.1,
                opt(t0)
            ));
        }
        let _ = writeln!(
            md,
            "\nfixshade: this run (the standard frames of the first table). tgx: {} \
             —: the harness does not run that scene.\n",
            tgx.source
        );
        let _ = writeln!(
            js,
            "  \"beside_tgx\": {{\"tgx_source\": {}, \"scenes\": [{}]}},",
            json_str(&tgx.source),
            rows.join(", ")
        );
    }

    let mb = raw.join("microbit");
    let m0_log = read(&mb.join("console.log"))?;
    let m0_lines: Vec<_> = m0_log
        .lines()
        .filter(|l| l.starts_with("m0 "))
        .map(fields)
        .collect();
    let m0_counts = counts(&mb.join("counts.txt"))?;
    if m0_lines.is_empty() || m0_lines.len() != m0_counts.len() {
        return Err("microbit: one console line and one count per frame expected".into());
    }
    let m0_size = read(&mb.join("size.txt"))?;
    let _ = writeln!(
        md,
        "## Cortex-M0, 16 KB of RAM (QEMU `microbit`)\n\n\
         firmware/microbit renders S1, S2 and S4 at 320 × 240 with the band renderer \
         (a draw into `Bands`, {} rows per band, vertices recomputed per band: no per-vertex storage) \
         and streams each band to the host through its `DrawTarget` as it is done; every frame \
         is byte-identical to the host's whole-frame render. S3's mesh (about 560 KB as kernel \
         statics) does not fit the 256 KB of flash. Instructions per frame are counted around \
         the render call (the renderer's set-up and the draw), streaming included. .text {} B, .rodata {} B (meshes included), \
         .bss {} B (colour and depth band).\n\n\
         | frame | instructions | drawn pixels | stack high-water (B) | RAM never touched (B) |\n\
         | --- | ---: | ---: | ---: | ---: |",
        num(&m0_lines[0], "rows")?,
        text_bytes(&m0_size),
        section(&m0_size, ".rodata"),
        section(&m0_size, ".bss"),
    );
    let mut m0_js = Vec::new();
    for (line, count) in m0_lines.iter().zip(&m0_counts) {
        let name = line.get("frame").ok_or("microbit: no frame name")?;
        let _ = writeln!(
            md,
            "| {name} | {count} | {} | {} | {} |",
            num(line, "pixels")?,
            num(line, "stack")?,
            num(line, "free")?
        );
        m0_js.push(format!(
            "{{\"frame\": \"{name}\", \"instructions\": {count}, \"stack\": {}}}",
            num(line, "stack")?
        ));
    }
    let _ = writeln!(md);
    let _ = writeln!(
        js,
        "  \"microbit_m0\": {{\"rows_per_band\": {}, \"bss\": {}, \"frames\": [{}]}},",
        num(&m0_lines[0], "rows")?,
        section(&m0_size, ".bss"),
        m0_js.join(", ")
    );
    let microbit_s1 = m0_lines
        .iter()
        .zip(&m0_counts)
        .find(|(l, _)| l.get("frame").map(String::as_str) == Some("m0_s1_gouraud"))
        .map(|(_, c)| *c)
        .ok_or("microbit: no m0_s1_gouraud frame")?;
    budgets::target_table(raw, &m4, &m0, microbit_s1, &mut md, &mut js)?;
    let _ = writeln!(
        md,
        "## Where the instructions go\n\n\
         `scripts/firmware_profile.sh TARGET FRAME`: per linked function (callees not included), \
         then per innermost function including inlined ones, then per execution count \
         (`N × k`: k instructions that each ran N times; in S1, 1 225 is once a vertex, 2 208 \
         once a triangle, 594 once a triangle set up). Frame 0 is S1, frame 1 is S2.\n"
    );
    fn s1(v: &[Frame]) -> Option<&Frame> {
        v.iter().find(|f| f.name == "s1_gouraud")
    }
    if let (Some(a), Some(b)) = (s1(&m4), s1(&m0)) {
        budgets::stage_table(raw, a, b, &mut md)?;
    }
    for (t, core) in TARGETS {
        for n in 0..2 {
            if let Ok(p) = read(&raw.join(t).join(format!("profile_{n}.txt"))) {
                let _ = writeln!(md, "{core}, {}:\n\n```text\n{}```\n", ["S1", "S2"][n], p);
            }
        }
    }
    let cfg = raw.join("config");
    let mut problems = Vec::new();
    if cfg.is_dir() {
        configurations(&cfg, &mut md, &mut js)?;
        problems = draw_call::draw_call_cost(raw, &mut md)?;
    } else {
        let _ = writeln!(
            md,
            "## Flash and RAM per scene configuration\n\n\
             Not built in this run (`FIRMWARE_QUICK=1`).\n"
        );
        js.push_str("  \"configurations\": null\n");
    }
    js.push_str("}\n");
    fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    fs::write(out.join("firmware_counts.json"), js).map_err(|e| e.to_string())?;
    fs::write(out.join("firmware.md"), md).map_err(|e| e.to_string())?;
    println!(
        "wrote {0}/firmware_counts.json and {0}/firmware.md",
        out.display()
    );
    if problems.is_empty() {
        Ok(())
    } else {
        Err(format!(
            "the draw call's build differs from the explicit call's: {}",
            problems.join("; ")
        ))
    }
}

/// The symbols of `arm-none-eabi-nm -S -C` output: size, kind (`t`, `b`,
/// …) and name.
fn symbols(nm: &str) -> impl Iterator<Item = (u64, &str, &str)> {
    nm.lines().filter_map(|l| {
        let mut w = l.splitn(4, ' ');
        let (_, size, kind, name) = (w.next()?, w.next()?, w.next()?, w.next()?);
        Some((u64::from_str_radix(size, 16).ok()?, kind, name))
    })
}

/// Bytes of the symbols of `arm-none-eabi-nm -S -C` output whose name
/// satisfies `pick`.
fn symbol_bytes(nm: &str, pick: impl Fn(&str) -> bool) -> u64 {
    symbols(nm)
        .filter(|&(_, _, name)| pick(name))
        .map(|(size, _, _)| size)
        .sum()
}

/// The flash/RAM table of the scene configurations under `cfg`
/// (`cfg/TARGET/LEVEL/`), into the markdown and the JSON.
fn configurations(cfg: &Path, md: &mut String, js: &mut String) -> Result<(), String> {
    // What the statics are, from the S1 configuration's symbols (the
    // largest set: mesh, vertex cache, frame and depth buffer).
    let nm = read(&cfg.join(TARGETS[1].0).join("s1").join("nm.txt"))?;
    let mesh = symbol_bytes(&nm, |n| n.contains("scenes::SPHERE48_"));
    let cache = symbol_bytes(&nm, |n| n == "fixshade_config::CACHE");
    let frame = symbol_bytes(&nm, |n| n == "fixshade_config::FRAME");
    let depth = symbol_bytes(&nm, |n| n == "fixshade_config::DEPTH");
    js.push_str("  \"configurations\": {\n");
    let _ = writeln!(
        md,
        "## Flash and RAM per scene configuration\n\n\
         `src/bin/config.rs` in firmware/qemu: S1's sphere (1225 vertices, 2208 triangles), \
         each row down to \"+ Phong shading\" adding one term to the row above; the last row, \
         S1 as the standard scene draws it, is the \"+ directional specular\" row with the depth \
         buffer and without the point and spot lights (its frame's checksum is checked against \
         the host's S1 frame). Bytes from `arm-none-eabi-size -A`; .text includes the vector \
         table; .rodata includes the mesh ({mesh} bytes); .bss holds the 320 × 240 frame \
         ({frame}), the vertex cache (1225 × {} = {cache}) and, in the \"depth\", \"phong\" and \
         S1 rows, the depth buffer ({depth}). Stack: high-water mark of the render call \
         (painted, rendered, scanned). Instructions: the render call.\n",
        cache / 1225
    );
    for (ti, (t, core)) in TARGETS.iter().enumerate() {
        let _ = writeln!(
            md,
            "### {core} (`{t}`)\n\n| configuration | .text | Δ .text | .rodata | Δ .rodata | .bss | stack | instructions | pixels |\n| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
        );
        let _ = writeln!(js, "    \"{t}\": [");
        let mut done: BTreeMap<&str, Config> = BTreeMap::new();
        for (li, (level, what, base)) in LEVELS.iter().enumerate() {
            let c = config(&cfg.join(t).join(level))?;
            let (dt, dr) = match base.and_then(|b| done.get(b)) {
                Some(p) => (
                    format!("{:+}", c.text as i64 - p.text as i64),
                    format!("{:+}", c.rodata as i64 - p.rodata as i64),
                ),
                None => (String::new(), String::new()),
            };
            let _ = writeln!(
                md,
                "| {what} | {} | {dt} | {} | {dr} | {} | {} B | {} | {} |",
                c.text,
                c.rodata,
                c.bss,
                c.stack,
                c.instructions.map(|n| n.to_string()).unwrap_or_default(),
                c.pixels
            );
            let _ = writeln!(
                js,
                "      {{\"level\": \"{level}\", \"text\": {}, \"rodata\": {}, \"bss\": {}, \"stack\": {}, \"instructions\": {}}}{}",
                c.text,
                c.rodata,
                c.bss,
                c.stack,
                opt(c.instructions),
                if li + 1 < LEVELS.len() { "," } else { "" }
            );
            done.insert(level, c);
        }
        let _ = writeln!(js, "    ]{}", if ti + 1 < TARGETS.len() { "," } else { "" });
        md.push('\n');
    }
    js.push_str("  }\n");
    Ok(())
}
