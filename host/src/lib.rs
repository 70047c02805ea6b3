//! fixshade's host tools: what holds the `no_std` kernel ([`fixshade`]) to
//! the f64 reference, and what brings scenes and meshes to it.
//!
//! - [`reference`](mod@reference): the f64 reference model and rasterizer (SPEC.md).
//! - [`scene_desc`], [`scene_file`]: a scene in `f64`, and its JSON files
//!   (SCENE_FORMAT.md).
//! - [`scene_kernel`]: a scene converted to the kernel's formats and drawn.
//! - [`generate`], [`standard_scenes`]: meshes and the standard scenes.
//! - [`error_measure`]: the error figures of SPEC.md 7.
//! - [`mesh_convert`]: OBJ to the kernel's mesh bytes or Rust source (the
//!   `fixshade-convert` command).

pub mod error_measure;
pub mod generate;
pub mod mesh_convert;
pub mod reference;
pub mod scene_desc;
pub mod scene_file;
pub mod scene_kernel;
pub mod standard_scenes;
