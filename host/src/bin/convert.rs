//! Converts a mesh to the kernel's flash format (`fixshade::mesh`): from an
//! OBJ file or one of the generators, to Rust source (`static`s for
//! `include!`) or to the bytes that `fixshade::include_mesh!` reads.
//!
//! ```text
//! cargo run --example convert_mesh -- INPUT OUTPUT [--name NAME] [--derive-normals]
//! ```
//!
//! * `INPUT`: an OBJ file, or a generator: `sphere:LON,LAT,RADIUS`,
//!   `cube:SIZE`, `torus:R,r,U,V`, `plane:SIZE,SEGMENTS`.
//! * `OUTPUT`: a `.rs` file gets Rust source, any other name the bytes.
//! * `--name NAME`: the statics' name (default: the output file's stem).
//! * `--derive-normals`: a mesh without normals gets the kernel's vertex
//!   normals (otherwise the device derives them with
//!   `fixshade::mesh::vertex_normals`).
//!
//! It prints the box, the largest quantisation error per axis against the
//! input and the sizes. Bad input prints one line on stderr and exits with
//! code 2; failing to write the output exits with code 1.

use std::path::Path;
use std::process::ExitCode;

use fixshade_host::generate;
use fixshade_host::mesh_convert::MeshData;
use fixshade_host::scene_desc::MeshDesc;

const USAGE: &str = "usage: convert_mesh INPUT.obj|sphere:LON,LAT,RADIUS|cube:SIZE|torus:R,r,U,V|plane:SIZE,SEGMENTS OUTPUT[.rs] [--name NAME] [--derive-normals]";

/// The numbers after `kind:`, exactly `n` of them.
fn numbers(spec: &str, n: usize) -> Result<Vec<f64>, String> {
    let v: Vec<f64> = spec
        .split(',')
        .map(|t| {
            t.trim()
                .parse::<f64>()
                .map_err(|_| format!("`{t}` is not a number"))
        })
        .collect::<Result<_, _>>()?;
    if v.len() != n || v.iter().any(|x| !x.is_finite()) {
        return Err(format!("`{spec}`: expected {n} finite numbers"));
    }
    Ok(v)
}

/// The mesh an `INPUT` argument names.
fn input(arg: &str) -> Result<MeshDesc, String> {
    let (kind, spec) = arg.split_once(':').unwrap_or((arg, ""));
    // Segment counts: the generators clamp them; saturate the cast first.
    let count = |x: f64| x.clamp(0.0, u32::MAX as f64) as u32;
    Ok(match kind {
        "sphere" => {
            let v = numbers(spec, 3)?;
            generate::sphere(count(v[0]), count(v[1]), v[2])
        }
        "cube" => generate::cube(numbers(spec, 1)?[0]),
        "torus" => {
            let v = numbers(spec, 4)?;
            generate::torus(v[0], v[1], count(v[2]), count(v[3]))
        }
        "plane" => {
            let v = numbers(spec, 2)?;
            generate::plane(v[0], count(v[1]))
        }
        _ => generate::read_obj(|| std::fs::File::open(arg).map(std::io::BufReader::new))
            .map_err(|e| format!("{arg}: {e}"))?,
    })
}

fn run() -> Result<(), (u8, String)> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let bad = |m: String| (2, m);
    let (mut files, mut name, mut derive) = (Vec::new(), None, false);
    let mut it = args.iter();
    while let Some(a) = it.next() {
        match a.as_str() {
            "--name" => name = Some(it.next().ok_or_else(|| bad(USAGE.into()))?.clone()),
            "--derive-normals" => derive = true,
            _ if a.starts_with("--") => return Err(bad(format!("unknown option {a}\n{USAGE}"))),
            _ => files.push(a.clone()),
        }
    }
    let [input_arg, out] = files.as_slice() else {
        return Err(bad(USAGE.into()));
    };
    let desc = input(input_arg).map_err(bad)?;
    let mut data = MeshData::from_desc(&desc).map_err(|e| bad(format!("{input_arg}: {e}")))?;
    if derive {
        data.derive_normals()
            .map_err(|e| bad(format!("{input_arg}: {e}")))?;
    }
    let out_path = Path::new(out);
    let rust = out_path.extension().is_some_and(|e| e == "rs");
    let bytes = if rust {
        let stem = out_path
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or("mesh");
        data.to_rust(name.as_deref().unwrap_or(stem)).into_bytes()
    } else {
        data.to_bytes()
    };
    std::fs::write(out_path, &bytes).map_err(|e| (1, format!("{out}: {e}")))?;

    let back = data.to_desc();
    let mut err = [0.0f64; 3];
    for (a, b) in desc.positions.iter().zip(&back.positions) {
        for k in 0..3 {
            err[k] = err[k].max((a[k] - b[k]).abs());
        }
    }
    let one = (1u64 << 24) as f64;
    println!(
        "{} vertices, {} triangles, normals: {}",
        data.positions.len(),
        data.indices.len(),
        if data.normals.is_some() { "yes" } else { "no" }
    );
    println!(
        "box: offset {:?}, half-extent {:?}; largest quantisation error per axis {:?}",
        data.bounds.offset.map(|o| o as f64 / one),
        data.bounds.scale.map(|s| s as f64 / one),
        err
    );
    println!(
        "{out}: {} bytes ({} as the byte layout)",
        bytes.len(),
        data.to_bytes().len()
    );
    Ok(())
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err((code, message)) => {
            eprintln!("convert_mesh: {message}");
            ExitCode::from(code)
        }
    }
}
