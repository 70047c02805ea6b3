//! The `fixshade-convert` command under hostile input, run as a child
//! process with a time limit: its OBJ input is read as a scene's
//! `mesh.obj` is (what is not a regular file refused before it is opened,
//! a file past the size cap refused while it is read), a mesh without a
//! triangle is refused, every message is one line naming the file with
//! what it echoes escaped, and bad input exits with code 2 without writing
//! the output. A good input converts to the checked-in files.

use std::ffi::OsStr;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use crate::scene_file::scratch;

/// How long one run may take: the command converts a small file in
/// milliseconds, so a run past this has blocked (a FIFO nobody writes).
const LIMIT: Duration = Duration::from_secs(10);

/// What a run of the command gave.
struct Run {
    code: Option<i32>,
    stdout: String,
    stderr: String,
}

/// Runs `fixshade-convert args`; kills it and fails the test if it has not
/// ended within [`LIMIT`], so that a command that blocks fails the test
/// instead of hanging the run. Its output is small (a few lines), so it
/// cannot fill a pipe before the command ends.
fn convert<S: AsRef<OsStr>>(args: &[S]) -> Run {
    let mut child = Command::new(env!("CARGO_BIN_EXE_fixshade-convert"))
        .args(args)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the command starts");
    let start = Instant::now();
    while child.try_wait().expect("wait").is_none() {
        if start.elapsed() > LIMIT {
            let _ = child.kill();
            let _ = child.wait();
            panic!("fixshade-convert did not end within {LIMIT:?}: it blocked");
        }
        std::thread::sleep(Duration::from_millis(10));
    }
    let out = child.wait_with_output().expect("output");
    Run {
        code: out.status.code(),
        stdout: String::from_utf8_lossy(&out.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&out.stderr).into_owned(),
    }
}

/// Writes `text` as `dir/name` and checks that the converter refuses it
/// with a line naming the file and holding `needle`.
fn refuses_file(dir: &Path, name: &str, text: &[u8], needle: &str) {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    refuses(
        path.as_os_str(),
        &dir.join("out.fxm"),
        &format!("{}: ", path.display()),
        needle,
    );
}

/// Converts `input` to `output`, expecting bad input refused: exit code 2,
/// one line on stderr starting with `fixshade-convert: {prefix}` and
/// containing `needle`, nothing on stdout and no output written.
fn refuses(input: &OsStr, output: &Path, prefix: &str, needle: &str) {
    let run = convert(&[input, output.as_os_str()]);
    let err = &run.stderr;
    println!("{err}");
    assert_eq!(run.code, Some(2), "{err}");
    assert!(
        err.starts_with(&format!("fixshade-convert: {prefix}")),
        "`{err}` should start with `fixshade-convert: {prefix}`"
    );
    assert!(err.contains(needle), "`{err}` should contain `{needle}`");
    assert_eq!(err.lines().count(), 1, "`{err}` should be one line");
    assert!(run.stdout.is_empty(), "{}", run.stdout);
    assert!(!output.exists(), "{} was written", output.display());
}

/// A FIFO nobody writes, a device that never ends and a folder are refused
/// at once, before they are opened (opening the FIFO would block until a
/// writer came).
#[cfg(unix)]
#[test]
fn refuses_what_is_not_a_regular_file() {
    let dir = scratch("convert-irregular");
    let fifo = dir.join("fifo");
    let made = Command::new("mkfifo").arg(&fifo).status();
    assert!(made.is_ok_and(|s| s.success()), "mkfifo failed");
    let out = dir.join("out.fxm");
    for path in [fifo.clone(), PathBuf::from("/dev/zero"), dir.clone()] {
        let name = path.display().to_string();
        refuses(
            path.as_os_str(),
            &out,
            &format!("{name}: "),
            "not a regular file",
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// An OBJ file longer than `MAX_FILE_BYTES` is refused while it is read
/// (valid text followed by comment lines: without the cap it converts).
#[test]
fn refuses_a_file_past_the_size_cap() {
    use fixshade_host::scene_file::MAX_FILE_BYTES;
    let dir = scratch("convert-cap");
    let mut obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n".to_vec();
    let comment = format!("#{}\n", " ".repeat(60_000));
    while (obj.len() as u64) <= MAX_FILE_BYTES {
        obj.extend_from_slice(comment.as_bytes());
    }
    refuses_file(
        &dir,
        "past.obj",
        &obj,
        &format!("larger than {MAX_FILE_BYTES} bytes"),
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// An OBJ file with no face (empty, comments only, vertices only) is
/// refused naming the file, instead of becoming a mesh of no triangle.
#[test]
fn refuses_a_mesh_without_triangles() {
    let dir = scratch("convert-empty");
    for (name, text) in [
        ("empty.obj", ""),
        ("comments.obj", "# a comment\n\n# another\n"),
        ("vertices.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\n"),
    ] {
        refuses_file(&dir, name, text.as_bytes(), "no triangle");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// What a message echoes (the input path, the file's text, the output
/// path, an argument) has its control characters escaped: a line break in
/// a name cannot break the message over lines.
#[test]
fn echoed_text_is_escaped() {
    let dir = scratch("convert-escaped");
    let out = dir.join("out.fxm");
    let missing = dir.join("a\nb.obj");
    refuses(
        missing.as_os_str(),
        &out,
        &format!("{}/a\\nb.obj: ", dir.display()),
        "",
    );
    let esc = dir.join("escape.obj");
    std::fs::write(&esc, "v 0 0 0\nf 1 1 \u{1b}[2J\n").unwrap();
    refuses(
        esc.as_os_str(),
        &out,
        &format!("{}: line 2: ", esc.display()),
        "`\\u{1b}[2J`",
    );
    // An output that cannot be written: code 1, one line.
    let tetrahedron = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/tetrahedron.obj");
    let unwritable = dir.join("no such dir/x\ny.fxm");
    let run = convert(&[tetrahedron.as_os_str(), unwritable.as_os_str()]);
    assert_eq!(run.code, Some(1), "{}", run.stderr);
    assert!(
        run.stderr.starts_with(&format!(
            "fixshade-convert: {}/no such dir/x\\ny.fxm: ",
            dir.display()
        )),
        "{}",
        run.stderr
    );
    assert_eq!(run.stderr.lines().count(), 1, "{}", run.stderr);
    // A bad argument: its message one line, then the usage line.
    let run = convert(&["--a\nb"]);
    assert_eq!(run.code, Some(2), "{}", run.stderr);
    let lines: Vec<&str> = run.stderr.lines().collect();
    assert_eq!(lines.len(), 2, "{}", run.stderr);
    assert_eq!(lines[0], "fixshade-convert: unknown option --a\\nb");
    assert!(
        lines[1].starts_with("usage: fixshade-convert "),
        "{}",
        lines[1]
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// Bad OBJ text the reader already refused stays refused, each in one line
/// naming the file and its line: non-finite and out-of-range numbers,
/// faces of fewer than 3 vertices, index 0, negative indices past the
/// start, text that is not UTF-8, more vertices than a mesh may have.
#[test]
fn refuses_bad_obj_text() {
    let dir = scratch("convert-bad-text");
    let many: String = (0..70_000).map(|i| format!("v {i} 0 0\n")).collect();
    let cases: [(&str, &[u8], &str); 10] = [
        (
            "nan.obj",
            b"v 0 0 NaN\n",
            "line 1: `NaN` is not a finite number",
        ),
        (
            "inf.obj",
            b"v 0 0 -inf\n",
            "line 1: `-inf` is not a finite number",
        ),
        (
            "big.obj",
            b"v 0 0 1e400\n",
            "line 1: `1e400` is not a finite number",
        ),
        (
            "face0.obj",
            b"v 0 0 0\nf\n",
            "line 2: a face needs at least 3 vertices, found 0",
        ),
        (
            "face2.obj",
            b"v 0 0 0\nf 1 1\n",
            "line 2: a face needs at least 3 vertices, found 2",
        ),
        ("zero.obj", b"v 0 0 0\nf 1 1 0\n", "line 2: index 0"),
        (
            "back.obj",
            b"v 0 0 0\nf 1 1 -2\n",
            "line 2: position index -2 out of range",
        ),
        ("latin1.obj", b"v 0 0 0 # caf\xe9\n", "line 1: not UTF-8"),
        (
            "far.obj",
            b"v 0 0 0\nv 200 0 0\nv 0 1 0\nf 1 2 3\n",
            "position 1: ",
        ),
        (
            "many.obj",
            many.as_bytes(),
            "line 65537: more than 65536 vertices",
        ),
    ];
    for (name, text, needle) in cases {
        refuses_file(&dir, name, text, needle);
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// The command writes what `mesh_format.rs` checks the checked-in files
/// against: the tetrahedron's bytes and Rust source (named after the
/// output's stem).
#[test]
fn converts_to_the_checked_in_files() {
    let dir = scratch("convert-good");
    let host = Path::new(env!("CARGO_MANIFEST_DIR"));
    let obj = host.join("tests/data/tetrahedron.obj");
    for (out, want) in [
        (
            dir.join("tetrahedron.fxm"),
            host.join("../tests/data/tetrahedron.fxm"),
        ),
        (
            dir.join("tetrahedron.rs"),
            host.join("tests/data/tetrahedron.rs"),
        ),
    ] {
        let run = convert(&[obj.as_os_str(), out.as_os_str()]);
        assert_eq!(run.code, Some(0), "{}", run.stderr);
        assert!(run.stderr.is_empty(), "{}", run.stderr);
        assert!(
            run.stdout.starts_with("4 vertices, 4 triangles, "),
            "{}",
            run.stdout
        );
        assert_eq!(
            std::fs::read(&out).unwrap(),
            std::fs::read(&want).unwrap(),
            "{}",
            want.display()
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}
