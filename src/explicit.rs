//! The draw as one explicit call: every argument at once and every choice
//! a type parameter, with none of the draw call's builders
//! ([`Renderer`](crate::Renderer), [`Shaded`](crate::Shaded)), which end
//! in it once taken apart. Public only with `--cfg
//! fixshade_explicit_draw`, never part of the crate's API: it is the
//! baseline `scripts/firmware.sh` holds the draw call to, each firmware
//! draw built both ways and their code compared function by function.

use crate::band::VertexMode;
use crate::camera::Camera;
use crate::color::Rgb;
use crate::illumination::Viewer;
use crate::light::LightSet;
use crate::material::{Material, Specular};
use crate::mesh::Mesh;
use crate::output::{normals_for, Output};
use crate::render::{DrawStats, Prepared, RenderError, RenderOptions, ShadingMode};
use crate::vector::Mat4;

/// Draws `mesh` under `lights` with shading mode `M` and viewer `V` into
/// `output`, with depth test `depth` (as `with_depth` takes it: a `&mut`
/// to a depth buffer or band, or [`NoDepth`](crate::depth::NoDepth)) and
/// vertex storage `vertices`: what
/// `mesh.shaded(&renderer).with_model(model)…draw(output)` does, its
/// arguments in the order the builders take them.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub fn draw<M, V, S, L, O, D, C>(
    camera: &Camera,
    material: &Material<S>,
    lights: &L,
    ambient: Rgb,
    options: RenderOptions,
    mesh: &Mesh,
    model: Mat4,
    mut depth: D,
    vertices: &mut C,
    output: &mut O,
) -> Result<DrawStats, RenderError<O::Error>>
where
    M: ShadingMode,
    V: Viewer,
    S: Specular,
    L: LightSet,
    O: Output<D>,
    C: VertexMode,
{
    normals_for::<M>(mesh).map_err(RenderError::lift)?;
    let p = Prepared::<S, V, L>::new(camera, &model, material, ambient, lights, options);
    output.render::<S, V, L, M, C>(&p, mesh, &mut depth, vertices)
}
