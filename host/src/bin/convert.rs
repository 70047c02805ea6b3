//! `fixshade-convert`: converts a mesh to the kernel's flash format
//! (`fixshade::mesh`), from an OBJ file or one of the generators, to Rust
//! source (`static`s for a `mod`) or to the bytes that
//! `fixshade::include_mesh!` reads.
//!
//! ```text
//! cargo run --release -p fixshade-host --bin fixshade-convert -- INPUT OUTPUT [--rust | --bytes] [--name NAME] [--derive-normals]
//! ```
//!
//! * `INPUT`: an OBJ file, or a generator: `sphere:LON,LAT,RADIUS`,
//!   `cube:SIZE`, `torus:R,r,U,V`, `plane:SIZE,SEGMENTS`. The OBJ file is
//!   read as a scene's `mesh.obj` is (`scene_file`'s [`read_obj_file`]):
//!   it must be a regular file (a device, a FIFO or a folder is refused
//!   before it is opened: opening a FIFO blocks until a writer comes) of at
//!   most 64 MiB (a larger one is refused while it is read), and its mesh
//!   must have a triangle.
//! * `OUTPUT`: the file written.
//! * `--rust`: Rust source, `pub static NAME: fixshade::mesh::Mesh` over
//!   `NAME_POSITIONS`, `NAME_NORMALS` and `NAME_INDICES`, for `mod` or
//!   `include!` (the default for an `OUTPUT` ending in `.rs`).
//! * `--bytes`: the byte layout, for `fixshade::include_mesh!` (the default
//!   for any other `OUTPUT`).
//! * `--name NAME`: the statics' name, upper-cased (default: the output
//!   file's stem); Rust source only.
//! * `--derive-normals`: a mesh without normals gets the kernel's vertex
//!   normals (Gouraud and Phong shading need normals; otherwise the device
//!   derives them with `fixshade::mesh::vertex_normals`, or draws `Flat`).
//! * `-h`, `--help`: the usage, on stdout.
//!
//! It prints the box, the largest quantisation error per axis against the
//! input and the sizes. A bad argument prints what is wrong and the usage
//! line on stderr, a bad input what is wrong, naming the file; both exit
//! with code 2. Failing to write the output prints what is wrong, naming
//! the file, and exits with code 1. Each message is one line: what it
//! echoes (paths, arguments, the file's text) has its control characters
//! escaped (`scene_file`'s [`one_line`]).

use std::io::Write as _;
use std::path::Path;
use std::process::ExitCode;

use fixshade_host::generate;
use fixshade_host::mesh_convert::MeshData;
use fixshade_host::scene_desc::MeshDesc;
use fixshade_host::scene_file::{one_line, read_obj_file};

/// The usage line, printed after a bad argument.
const USAGE: &str =
    "usage: fixshade-convert INPUT OUTPUT [--rust | --bytes] [--name NAME] [--derive-normals] (--help: more)";

/// `--help`.
const HELP: &str = "\
usage: fixshade-convert INPUT OUTPUT [--rust | --bytes] [--name NAME] [--derive-normals]

Converts a mesh to fixshade's flash format.

  INPUT             an OBJ file (a regular file of at most 64 MiB, with at
                    least one face), or a generated mesh: sphere:LON,LAT,RADIUS,
                    cube:SIZE, torus:R,r,U,V or plane:SIZE,SEGMENTS
  OUTPUT            the file to write
  --rust            Rust source: `pub static NAME: Mesh` over NAME_POSITIONS,
                    NAME_NORMALS and NAME_INDICES (default for OUTPUT *.rs)
  --bytes           the byte layout, for fixshade::include_mesh! (default
                    for any other OUTPUT, e.g. *.fxm)
  --name NAME       the statics' name, upper-cased (default: OUTPUT's stem);
                    Rust source only
  --derive-normals  give a mesh without normals the kernel's vertex normals
                    (Gouraud and Phong shading need normals)
  -h, --help        this text

Convert, include, draw:
  fixshade-convert bunny.obj src/bunny.fxm --derive-normals
      let mesh = fixshade::include_mesh!(\"bunny.fxm\")?;  // in src/main.rs
  or
  fixshade-convert bunny.obj src/model.rs --name bunny --derive-normals
      mod model;                                          // in src/main.rs
      let mesh = &model::BUNNY;
  then
      mesh.shaded(&renderer).with_model(spin).draw(&mut display)?;";

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
        _ => read_obj_file(Path::new(arg)).map_err(|e| format!("{arg}: {e}"))?,
    })
}

/// The output's format.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Format {
    Rust,
    Bytes,
}

/// What the command line asks for.
struct Args {
    input: String,
    output: String,
    format: Format,
    name: Option<String>,
    derive: bool,
}

/// Parses the arguments; `Ok(None)` for `--help`.
fn parse(args: &[String]) -> Result<Option<Args>, String> {
    let (mut files, mut format, mut name, mut derive) = (Vec::new(), None, None, false);
    let mut it = args.iter();
    while let Some(a) = it.next() {
        let set = |format: &mut Option<Format>, f: Format| match format {
            Some(g) if *g != f => Err("--rust and --bytes exclude each other".to_string()),
            _ => {
                *format = Some(f);
                Ok(())
            }
        };
        match a.as_str() {
            "-h" | "--help" => return Ok(None),
            "--rust" => set(&mut format, Format::Rust)?,
            "--bytes" => set(&mut format, Format::Bytes)?,
            "--name" => {
                name = Some(
                    it.next()
                        .ok_or_else(|| "--name needs a value".to_string())?
                        .clone(),
                )
            }
            "--derive-normals" => derive = true,
            _ if a.starts_with('-') && a.len() > 1 => return Err(format!("unknown option {a}")),
            _ => files.push(a.clone()),
        }
    }
    let [input, output] = <[String; 2]>::try_from(files).map_err(|f| {
        format!(
            "expected INPUT and OUTPUT, got {} file argument{}",
            f.len(),
            if f.len() == 1 { "" } else { "s" }
        )
    })?;
    let by_extension = if Path::new(&output).extension().is_some_and(|e| e == "rs") {
        Format::Rust
    } else {
        Format::Bytes
    };
    let format = format.unwrap_or(by_extension);
    if format == Format::Bytes && name.is_some() {
        return Err(
            "--name names Rust statics: it needs --rust (or an OUTPUT ending in .rs)".into(),
        );
    }
    Ok(Some(Args {
        input,
        output,
        format,
        name,
        derive,
    }))
}

/// Why the command failed.
struct Failure {
    /// The exit code: 2 for bad input, 1 for an output not written.
    code: u8,
    /// What is wrong, unescaped: [`main`] escapes it to one line.
    message: String,
    /// Whether the usage line follows (after a bad argument).
    usage: bool,
}

fn run() -> Result<(), Failure> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let Some(a) = parse(&args).map_err(|message| Failure {
        code: 2,
        message,
        usage: true,
    })?
    else {
        // Not `println!`, which panics when `--help | head` closes the pipe.
        let _ = writeln!(std::io::stdout(), "{HELP}");
        return Ok(());
    };
    let bad = |message: String| Failure {
        code: 2,
        message,
        usage: false,
    };
    let desc = input(&a.input).map_err(bad)?;
    // A mesh without a triangle would draw nothing: an OBJ file without a
    // face (empty, or comments only) is a mistake, not a mesh. The
    // generators always make triangles.
    if desc.indices.is_empty() {
        return Err(bad(format!(
            "{}: no triangle to convert (an OBJ mesh needs an `f` line)",
            a.input
        )));
    }
    let mut data = MeshData::from_desc(&desc).map_err(|e| bad(format!("{}: {e}", a.input)))?;
    if a.derive {
        data.derive_normals()
            .map_err(|e| bad(format!("{}: {e}", a.input)))?;
    }
    let out_path = Path::new(&a.output);
    let bytes = match a.format {
        Format::Rust => {
            let stem = out_path
                .file_stem()
                .and_then(|s| s.to_str())
                .unwrap_or("mesh");
            data.to_rust(a.name.as_deref().unwrap_or(stem)).into_bytes()
        }
        Format::Bytes => data.to_bytes(),
    };
    std::fs::write(out_path, &bytes).map_err(|e| Failure {
        code: 1,
        message: format!("{}: {e}", a.output),
        usage: false,
    })?;

    let back = data.to_desc();
    let mut err = [0.0f64; 3];
    for (a, b) in desc.positions.iter().zip(&back.positions) {
        for k in 0..3 {
            err[k] = err[k].max((a[k] - b[k]).abs());
        }
    }
    let one = (1u64 << 24) as f64;
    let mut stdout = std::io::stdout().lock();
    let _ = writeln!(
        stdout,
        "{} vertices, {} triangles, normals: {}",
        data.positions.len(),
        data.indices.len(),
        match (&data.normals, a.derive) {
            (None, _) => "no (Flat shading only; --derive-normals adds them)",
            (Some(_), true) if desc.normals.is_none() => "derived",
            (Some(_), _) => "yes",
        }
    );
    let _ = writeln!(
        stdout,
        "box: offset {:?}, half-extent {:?}; largest quantisation error per axis {:?}",
        data.bounds.offset.map(|o| o as f64 / one),
        data.bounds.scale.map(|s| s as f64 / one),
        err
    );
    let _ = writeln!(
        stdout,
        "{}: {} ({} bytes; {} as the byte layout, what flash holds)",
        one_line(&a.output),
        match a.format {
            Format::Rust => "Rust source",
            Format::Bytes => "mesh bytes",
        },
        bytes.len(),
        data.to_bytes().len()
    );
    Ok(())
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(f) => {
            eprintln!("fixshade-convert: {}", one_line(&f.message));
            if f.usage {
                eprintln!("{USAGE}");
            }
            ExitCode::from(f.code)
        }
    }
}
