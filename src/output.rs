//! Where a draw's pixels go: the [`Output`] trait, which every target the
//! draw call takes implements (any `DrawTarget`, a [`Framebuffer`] written
//! in place, [`Bands`]), with the depth test a whole frame takes
//! ([`FrameDepth`]). Below both the draw call (`renderer`) and the
//! explicit call (`explicit`), which end in [`Output::render`]; the
//! `renderer` module re-exports its public items.

use core::convert::Infallible;

use embedded_graphics::draw_target::DrawTarget;
use embedded_graphics::pixelcolor::Rgb565;

use crate::band::{BandDepth, Bands, VertexMode};
use crate::depth::{DepthTest, NoDepth};
use crate::framebuffer::Framebuffer;
use crate::illumination::Viewer;
use crate::light::LightSet;
use crate::material::Specular;
use crate::mesh::Mesh;
use crate::render::{DrawStats, Prepared, RenderError, ShadingKind, ShadingMode};

/// `NoNormals` for a mesh without normals in a mode that needs them (a
/// mesh error first, as the draw reports it), before the draw's constants
/// are made.
#[inline(always)]
pub(crate) fn normals_for<M: ShadingMode>(mesh: &Mesh) -> Result<(), RenderError<Infallible>> {
    if M::KIND != ShadingKind::Flat && mesh.normals.is_none() {
        mesh.validate().map_err(RenderError::Mesh)?;
        return Err(RenderError::NoNormals);
    }
    Ok(())
}

mod sealed {
    pub trait Sealed {}
}

/// Where a draw's pixels go, and with which depth test `D`: a whole frame
/// into any `DrawTarget<Color = Rgb565>` or a [`Framebuffer`] (a
/// [`DepthBuffer`](crate::depth::DepthBuffer) or none), or the frame in
/// [`Bands`] (a [`DepthBand`](crate::depth::DepthBand) or none).
pub trait Output<D>: sealed::Sealed {
    /// The target's error.
    type Error;

    /// Draws `mesh` with `p`'s constants (the renderer's internals).
    #[doc(hidden)]
    fn render<S, V, L, M, C>(
        &mut self,
        p: &Prepared<'_, S, V, L>,
        mesh: &Mesh,
        depth: &mut D,
        vertices: &mut C,
    ) -> Result<DrawStats, RenderError<Self::Error>>
    where
        S: Specular,
        V: Viewer,
        L: LightSet,
        M: ShadingMode,
        C: VertexMode;
}

/// A depth test for a whole frame: none, or a buffer of the target's size.
pub trait FrameDepth: DepthTest {
    #[doc(hidden)]
    type Test: DepthTest;
    #[doc(hidden)]
    fn test(&mut self) -> &mut Self::Test;
}
impl FrameDepth for NoDepth {
    type Test = NoDepth;
    #[inline(always)]
    fn test(&mut self) -> &mut NoDepth {
        self
    }
}
impl<'a> FrameDepth for crate::depth::DepthBuffer<'a> {
    type Test = crate::depth::DepthBuffer<'a>;
    #[inline(always)]
    fn test(&mut self) -> &mut Self::Test {
        self
    }
}
impl<Z: FrameDepth> FrameDepth for &mut Z {
    type Test = Z::Test;
    #[inline(always)]
    fn test(&mut self) -> &mut Z::Test {
        (**self).test()
    }
}

impl<T: DrawTarget<Color = Rgb565>> sealed::Sealed for T {}
impl<T: DrawTarget<Color = Rgb565>, D: FrameDepth> Output<D> for T {
    type Error = T::Error;
    #[inline(always)]
    fn render<S, V, L, M, C>(
        &mut self,
        p: &Prepared<'_, S, V, L>,
        mesh: &Mesh,
        depth: &mut D,
        vertices: &mut C,
    ) -> Result<DrawStats, RenderError<T::Error>>
    where
        S: Specular,
        V: Viewer,
        L: LightSet,
        M: ShadingMode,
        C: VertexMode,
    {
        p.draw_target::<M, T, D::Test, C>(mesh, self, depth.test(), vertices)
    }
}

impl sealed::Sealed for Framebuffer<'_> {}
impl<D: FrameDepth> Output<D> for Framebuffer<'_> {
    type Error = Infallible;
    #[inline(always)]
    fn render<S, V, L, M, C>(
        &mut self,
        p: &Prepared<'_, S, V, L>,
        mesh: &Mesh,
        depth: &mut D,
        vertices: &mut C,
    ) -> Result<DrawStats, RenderError<Infallible>>
    where
        S: Specular,
        V: Viewer,
        L: LightSet,
        M: ShadingMode,
        C: VertexMode,
    {
        p.draw_framebuffer::<M, D::Test, C>(mesh, self, depth.test(), vertices)
    }
}

impl<T> sealed::Sealed for Bands<'_, '_, T> {}
impl<T: DrawTarget<Color = Rgb565>, D: BandDepth> Output<D> for Bands<'_, '_, T> {
    type Error = T::Error;
    #[inline(always)]
    fn render<S, V, L, M, C>(
        &mut self,
        p: &Prepared<'_, S, V, L>,
        mesh: &Mesh,
        depth: &mut D,
        vertices: &mut C,
    ) -> Result<DrawStats, RenderError<T::Error>>
    where
        S: Specular,
        V: Viewer,
        L: LightSet,
        M: ShadingMode,
        C: VertexMode,
    {
        p.draw_bands::<M, T, D, C>(mesh, self, depth, vertices)
    }
}
