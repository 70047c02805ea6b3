//! What the set-up and the walk hand to the span loops: a triangle's
//! attribute planes and the spans of its rows, in the `repr(C)` layouts
//! the loops in assembly read (`src/platform.rs`). Between the stages, so
//! that the set-up, the walk, the spans and the platform's loops all take
//! them from here.

/// A triangle's attribute planes: attribute `k` at pixel `(c, r)` is
/// `at[k] + gx[k]·c + gy[k]·(r − r₀)` (wrapping), `r₀` the walk's first
/// row. (`repr(C)`: the span loops in assembly read it, `src/platform.rs`.)
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub(crate) struct Planes<const N: usize> {
    pub(crate) at: [i32; N],
    pub(crate) gx: [i32; N],
    pub(crate) gy: [i32; N],
}

impl<const N: usize> Default for Planes<N> {
    fn default() -> Self {
        Planes {
            at: [0; N],
            gx: [0; N],
            gy: [0; N],
        }
    }
}

/// One row's span in a walk's table: columns `x0 ..= x0 + n − 1` (from
/// the set-up's origin), none where `n ≤ 0`. (`repr(C)`: the span loops in
/// assembly read the table, `src/platform.rs`.)
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Row {
    pub(crate) x0: i32,
    pub(crate) n: i32,
}
