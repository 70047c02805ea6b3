//! What the draw call costs: each firmware build drawn by the draw call
//! against its build drawn by the kernel's explicit call
//! (src/explicit.rs), function by function, .text and instructions.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;

use super::{config, counts, fields, read, symbols, text_bytes, Config, LEVELS, TARGETS};

/// The sizes of the functions (`t`/`T` symbols) of an `arm-none-eabi-nm
/// -S -C` listing, by name, sorted: the demangled name of a generic
/// function is the same for each of its instantiations.
fn functions(nm: &str) -> BTreeMap<String, Vec<u64>> {
    let mut f: BTreeMap<String, Vec<u64>> = BTreeMap::new();
    for (size, _, name) in symbols(nm).filter(|&(_, kind, _)| matches!(kind, "t" | "T")) {
        f.entry(name.to_string()).or_default().push(size);
    }
    for sizes in f.values_mut() {
        sizes.sort_unstable();
    }
    f
}

/// The functions of two `arm-none-eabi-nm -S -C` listings that differ in
/// size or are in one only, as table cells.
fn differing_functions(a: &str, e: &str) -> Vec<String> {
    let (fa, fe) = (functions(a), functions(e));
    let show = |v: Option<&Vec<u64>>| {
        v.map_or("none".to_string(), |v| {
            let b: Vec<String> = v.iter().map(u64::to_string).collect();
            format!("{} B", b.join(" + "))
        })
    };
    fa.keys()
        .chain(fe.keys().filter(|n| !fa.contains_key(*n)))
        .filter(|n| fa.get(*n) != fe.get(*n))
        .map(|n| format!("`{n}` {} / {}", show(fa.get(n)), show(fe.get(n))))
        .collect()
}

/// [`differing_functions`] of the `nm.txt` listings in two directories.
fn differing_builds(a: &Path, e: &Path) -> Result<Vec<String>, String> {
    Ok(differing_functions(
        &read(&a.join("nm.txt"))?,
        &read(&e.join("nm.txt"))?,
    ))
}

/// The items joined, or `none`.
fn none_or(items: &[String]) -> String {
    if items.is_empty() {
        "none".to_string()
    } else {
        items.join(", ")
    }
}

/// Whether a draw call's figure `x` is within 1 % of its explicit call's
/// `y`: how far the two may differ (the choices the draw call infers are
/// to cost nothing, but a compiler's layout of two builds may move a
/// count by an instruction, a copy's alignment or a branch's, without any
/// code of the draw differing).
fn within_one_percent(x: u64, y: u64) -> bool {
    x.abs_diff(y) * 100 <= y
}

/// `x (same)` or `x / y (±d)`.
fn pair(x: u64, y: u64) -> String {
    if x == y {
        format!("{x} (same)")
    } else {
        format!("{x} / {y} ({:+})", x as i64 - y as i64)
    }
}

/// The frame names of a firmware's console log, in the order of its
/// counts: `frame NAME …` lines (firmware/qemu), `m0 frame=NAME …` lines
/// (firmware/microbit).
fn frame_names(log: &str) -> Vec<String> {
    log.lines()
        .filter_map(|l| {
            if let Some(rest) = l.strip_prefix("frame ") {
                rest.split_whitespace().next().map(str::to_string)
            } else if l.starts_with("m0 ") {
                fields(l).get("frame").cloned()
            } else {
                None
            }
        })
        .collect()
}

/// The 16 KB Cortex-M0's firmware, compared with its explicit-call build
/// beside the two targets' whole-frame firmware.
const MICROBIT: (&str, &str) = (
    "microbit",
    "Cortex-M0, 16 KB: `Bands` into a `DrawTarget`, vertices recomputed",
);

/// The draw call against the explicit call (src/explicit.rs): each
/// configuration under `raw/config` built again under
/// `raw/config-explicit`, and each firmware (`raw/TARGET`, `raw/microbit`)
/// under `raw/explicit`, side by side: .text, instructions, and the functions
/// whose code differs. The problems found, for [`run`](super::run) to fail on once
/// the report is written: .text or a draw's instructions more than 1 %
/// apart ([`within_one_percent`]; the draw call is to add no byte and no
/// instruction, nor to save any, which would mean the baseline is not the
/// same draw). Every difference is listed.
pub(super) fn draw_call_cost(raw: &Path, md: &mut String) -> Result<Vec<String>, String> {
    let (cfg, explicit) = (raw.join("config"), raw.join("config-explicit"));
    let _ = writeln!(
        md,
        "## What the draw call costs\n\n\
         Each firmware build drawn twice: by the draw call \
         (`mesh.shaded(&renderer).with_model(..).with_depth(..).with_cache(..).draw(output)`, \
         every type inferred), and by one explicit call of the same kernel with every argument \
         given at once and every choice a type parameter (`fixshade::explicit::draw`, public \
         only with `--cfg fixshade_explicit_draw`). The same frames; .text; instructions of \
         the render calls; \"functions that differ\": the functions of the two builds \
         (`arm-none-eabi-nm -S`) that differ in size or are in one only. Every difference \
         is listed; scripts/firmware.sh fails where .text or a draw's instructions differ by \
         more than 1 %.\n\n\
         | firmware | .text, draw call / explicit | instructions, draw call / explicit | functions that differ |\n\
         | --- | ---: | --- | --- |"
    );
    let mut problems = Vec::new();
    let firmware = TARGETS
        .iter()
        .map(|&(t, core)| {
            let what = format!(
                "{core}: every frame of the first table, whole-frame `Framebuffer`, vertex cache"
            );
            (t, what)
        })
        .chain([(MICROBIT.0, MICROBIT.1.to_string())]);
    for (dir, what) in firmware {
        let (ad, ed) = (raw.join(dir), raw.join("explicit").join(dir));
        let text = |d: &Path| read(&d.join("size.txt")).map(|s| text_bytes(&s));
        let (at, et) = (text(&ad)?, text(&ed)?);
        let (ac, ec) = (
            counts(&ad.join("counts.txt"))?,
            counts(&ed.join("counts.txt"))?,
        );
        let names = frame_names(&read(&ad.join("console.log"))?);
        if ac.len() != ec.len() || ac.len() != names.len() {
            return Err(format!(
                "{dir}: {} counts, {} counts of the explicit call's build, {} frames in the console log",
                ac.len(),
                ec.len(),
                names.len()
            ));
        }
        let frames: Vec<String> = names
            .iter()
            .zip(ac.iter().zip(&ec))
            .filter(|(_, (a, e))| a != e)
            .map(|(n, (&a, &e))| format!("{n} {}", pair(a, e)))
            .collect();
        let differ = differing_builds(&ad, &ed)?;
        let close = within_one_percent(at, et)
            && ac.iter().zip(&ec).all(|(&a, &e)| within_one_percent(a, e));
        let frames = if frames.is_empty() {
            format!("all {} frames the same", ac.len())
        } else {
            frames.join(", ")
        };
        if !close {
            problems.push(format!(
                "{what}: .text {}; instructions {frames}; functions {}",
                pair(at, et),
                none_or(&differ)
            ));
        }
        let _ = writeln!(
            md,
            "| {what} | {} | {frames} | {} |",
            pair(at, et),
            none_or(&differ)
        );
    }
    let _ = writeln!(
        md,
        "\nThe scene configurations above, one draw each:\n\n\
         | configuration | core | .text, draw call / explicit | instructions, draw call / explicit | functions that differ |\n\
         | --- | --- | ---: | ---: | --- |"
    );
    for (level, what, _) in LEVELS.iter().skip(1) {
        // (The S1 row's note on its Δ columns does not apply here.)
        let what = what.split(" (Δ").next().unwrap_or(what);
        for (t, core) in TARGETS {
            let (ad, ed) = (cfg.join(t).join(level), explicit.join(t).join(level));
            let (a, e) = (config(&ad)?, config(&ed)?);
            let count = |c: &Config, d: &Path| {
                c.instructions
                    .ok_or_else(|| format!("{}: no instruction count", d.display()))
            };
            let (ai, ei) = (count(&a, &ad)?, count(&e, &ed)?);
            let differ = differing_builds(&ad, &ed)?;
            if !within_one_percent(a.text, e.text) || !within_one_percent(ai, ei) {
                problems.push(format!(
                    "{core} {level}: .text {}; instructions {}; functions {}",
                    pair(a.text, e.text),
                    pair(ai, ei),
                    none_or(&differ)
                ));
            }
            let _ = writeln!(
                md,
                "| {what} | {core} | {} | {} | {} |",
                pair(a.text, e.text),
                pair(ai, ei),
                none_or(&differ)
            );
        }
    }
    md.push('\n');
    Ok(problems)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two instantiations of one generic function, as `nm -S -C` lists
    /// them: the same demangled name.
    const NM: &str = "00000010 00000120 t fixshade::band::draw_bands
00000200 00000300 t fixshade::band::draw_bands
00000500 00000040 T main
00000600 00000004 b fixshade_fw::CACHE
";

    #[test]
    fn the_same_listing_does_not_differ() {
        assert!(differing_functions(NM, NM).is_empty());
    }

    #[test]
    fn an_instantiation_more_or_resized_differs() {
        // Inserted before the last instantiation: a map keeping one size a
        // name would keep 768 in both and see no difference.
        let more = NM.replacen(
            "00000200 ",
            "00000900 00000120 t fixshade::band::draw_bands\n00000200 ",
            1,
        );
        assert_eq!(
            differing_functions(NM, &more),
            ["`fixshade::band::draw_bands` 288 + 768 B / 288 + 288 + 768 B"]
        );
        let resized = NM.replace("00000300 t", "00000304 t");
        assert_eq!(differing_functions(NM, &resized).len(), 1);
        // Data symbols are not functions.
        let data = NM.replace("00000004 b", "00000008 b");
        assert!(differing_functions(NM, &data).is_empty());
    }

    #[test]
    fn a_function_in_one_build_only_differs() {
        let fewer: String = NM
            .lines()
            .filter(|l| !l.contains("main"))
            .map(|l| format!("{l}\n"))
            .collect();
        assert_eq!(differing_functions(NM, &fewer), ["`main` 64 B / none"]);
        assert_eq!(differing_functions(&fewer, NM), ["`main` none / 64 B"]);
    }

    #[test]
    fn frame_names_of_both_consoles() {
        let qemu =
            "frame s1_gouraud triangles=2208 drawn=594\nnoise\nframe s2_gouraud triangles=2\n";
        assert_eq!(frame_names(qemu), ["s1_gouraud", "s2_gouraud"]);
        let microbit = "m0 frame=m0_s1_gouraud bands=60 rows=4\nm0 frame=m0_s4_phong bands=60\n";
        assert_eq!(frame_names(microbit), ["m0_s1_gouraud", "m0_s4_phong"]);
    }

    /// One per cent either way passes, a unit more fails.
    #[test]
    fn one_percent_apart_at_most() {
        assert!(within_one_percent(8_823_255, 8_823_256));
        assert!(within_one_percent(101, 100) && within_one_percent(99, 100));
        assert!(!within_one_percent(102, 100) && !within_one_percent(98, 100));
        assert!(within_one_percent(0, 0) && !within_one_percent(1, 0));
    }

    #[test]
    fn pairs_show_the_difference() {
        assert_eq!(pair(5, 5), "5 (same)");
        assert_eq!(pair(5891055, 5891053), "5891055 / 5891053 (+2)");
        assert_eq!(pair(3, 7), "3 / 7 (-4)");
    }
}
