//! The host's tests of the kernel, one binary (the renderer is
//! monomorphised once for all of them), a module per concern.

mod common;
mod fuzz_scene;
mod heap;

mod bad_input;
mod bands;
mod convert_command;
mod fuzz_regressions;
mod kernel_vs_reference;
mod lighting_vs_reference;
mod mesh_format;
mod no_alloc;
mod properties;
mod reference;
mod scene_file;
mod stiff_cases;
mod watertight;
mod world_scale;
