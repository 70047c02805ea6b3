//! The crate's overview lists every public item (`lib.rs`, "Public
//! items"): each item declared `pub` at the top level of a public module's
//! file is named there.

/// The public modules' sources, by the modules whose path names their
/// items (the private `options` and `vertex` hold items that `render` and
/// `band` re-export).
const MODULES: [(&[&str], &str); 18] = [
    (&["band"], include_str!("../band.rs")),
    (&["camera"], include_str!("../camera.rs")),
    (&["color"], include_str!("../color.rs")),
    (&["depth"], include_str!("../depth.rs")),
    (&["framebuffer"], include_str!("../framebuffer.rs")),
    (&["illumination"], include_str!("../illumination.rs")),
    (&["light"], include_str!("../light.rs")),
    (&["illumination"], include_str!("../light_term.rs")),
    (&["material"], include_str!("../material.rs")),
    (&["mesh"], include_str!("../mesh.rs")),
    (&["num"], include_str!("../num/mini_float.rs")),
    (&["num"], include_str!("../num/wide_point.rs")),
    (&["render"], include_str!("../options.rs")),
    (&["band", "render"], include_str!("../vertex.rs")),
    (&["render"], include_str!("../render.rs")),
    (&["renderer"], include_str!("../output.rs")),
    (&["renderer"], include_str!("../renderer.rs")),
    (&["vector"], include_str!("../vector.rs")),
];

/// The names of the items declared `pub` at the start of a line (not
/// hidden from the documentation).
fn public_items(src: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut hidden = false;
    for line in src.lines() {
        if line.starts_with("#[doc(hidden)]") {
            hidden = true;
            continue;
        }
        let rest = [
            "pub struct ",
            "pub enum ",
            "pub trait ",
            "pub fn ",
            "pub const fn ",
            "pub const ",
            "pub type ",
        ]
        .iter()
        .find_map(|k| line.strip_prefix(k));
        if let Some(rest) = rest {
            let name: String = rest
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect();
            if !hidden {
                out.push(name);
            }
        }
        if !line.starts_with("#[") && !line.starts_with("///") {
            hidden = false;
        }
    }
    out
}

#[test]
fn every_public_item_is_listed_in_the_overview() {
    let lib = include_str!("../lib.rs");
    let list = &lib[lib.find("# Public items").expect("the overview's list")..];
    let mut seen = 0;
    for (modules, src) in MODULES {
        for name in public_items(src) {
            let listed = modules
                .iter()
                .any(|m| list.contains(&format!("[`{name}`]({m}::{name})")));
            assert!(listed, "{modules:?}::{name} is not in lib.rs's list");
            seen += 1;
        }
    }
    assert!(seen > 80, "only {seen} items found: the scan is broken");
}
