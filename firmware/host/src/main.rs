//! `fixshade-firmware-host --report RAW_DIR REPORT_DIR [PEERS_TSV]`: the
//! report of scripts/firmware.sh (see `report.rs`).
//!
//! `fixshade-firmware-host --checksum FILE`: prints the checksum that
//! firmware/qemu's `fixshade-config` prints of its frame (FNV-1a over the
//! little-endian RGB565 pixels), for a frame file written here.
//!
//! `fixshade-firmware-host OUT_DIR`: renders every frame the firmware
//! renders (firmware/common/scenes.rs) on the host with
//! `KernelScene::render_framebuffer`, and writes `OUT_DIR/NAME.bin` (raw
//! little-endian RGB565, the render example's `--raw` format).

use std::path::PathBuf;
use std::process::ExitCode;

use fixshade::framebuffer::Framebuffer;
use fixshade::render::CachedVertex;
use fixshade_host::scene_kernel::KernelScene;

mod report;

#[path = "../../common/scenes.rs"]
#[allow(dead_code)]
mod scenes;

fn main() -> ExitCode {
    let args: Vec<_> = std::env::args_os().collect();
    if (args.len() == 4 || args.len() == 5) && args[1] == "--report" {
        let peers = args.get(4).map(|p| p.as_ref());
        return match report::run(args[2].as_ref(), args[3].as_ref(), peers) {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => {
                eprintln!("report: {e}");
                ExitCode::FAILURE
            }
        };
    }
    if args.len() == 3 && args[1] == "--checksum" {
        return match std::fs::read(&args[2]) {
            Ok(bytes) => {
                println!("{:08x}", checksum(&bytes));
                ExitCode::SUCCESS
            }
            Err(e) => {
                eprintln!("{}: {e}", PathBuf::from(&args[2]).display());
                ExitCode::FAILURE
            }
        };
    }
    let Some(out) = std::env::args_os().nth(1).map(PathBuf::from) else {
        eprintln!("usage: fixshade-firmware-host OUT_DIR");
        return ExitCode::from(2);
    };
    if let Err(e) = std::fs::create_dir_all(&out) {
        eprintln!("{}: {e}", out.display());
        return ExitCode::FAILURE;
    }
    for v in scenes::variants().into_iter().chain(scenes::m0_variants()) {
        let scene = match KernelScene::new(&v.desc) {
            Ok(s) => s,
            Err(e) => {
                eprintln!("{}: {e}", v.name);
                return ExitCode::FAILURE;
            }
        };
        let n = (scene.width * scene.height) as usize;
        let mut px = vec![0u16; n];
        let mut depth = vec![0u16; n];
        let mut cache = vec![CachedVertex::default(); v.desc.mesh.positions.len()];
        let stats = {
            let mut fb = Framebuffer::new(&mut px, scene.width, scene.height).expect("size");
            match scene.render_framebuffer(&mut fb, &mut depth, &mut cache) {
                Ok(s) => s,
                Err(e) => {
                    eprintln!("{}: {e}", v.name);
                    return ExitCode::FAILURE;
                }
            }
        };
        let bytes: Vec<u8> = px.iter().flat_map(|p| p.to_le_bytes()).collect();
        let path = out.join(format!("{}.bin", v.name));
        if let Err(e) = std::fs::write(&path, bytes) {
            eprintln!("{}: {e}", path.display());
            return ExitCode::FAILURE;
        }
        println!(
            "frame {} triangles={} drawn={} clipped={} pixels={} lit={}",
            v.name, stats.triangles, stats.drawn, stats.clipped, stats.pixels, stats.lit
        );
    }
    ExitCode::SUCCESS
}

/// FNV-1a over a frame's pixels (little-endian RGB565, a trailing odd
/// byte ignored), as firmware/qemu's `fixshade-config` computes it.
fn checksum(bytes: &[u8]) -> u32 {
    bytes.chunks_exact(2).fold(0x811c_9dc5u32, |h, p| {
        (h ^ u32::from(u16::from_le_bytes([p[0], p[1]]))).wrapping_mul(0x0100_0193)
    })
}
