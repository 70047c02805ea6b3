//! Unit tests of the kernel's internal modules that span a whole module:
//! properties and accuracy sweeps (the smaller tests sit beside their code).

mod clip_feature;
mod coverage;
mod dir;
mod normalize;
mod public_items;
mod row_stores;
mod span_shaders;
mod specular_table;

/// A xorshift64 generator: the tests' reproducible random numbers.
pub(crate) fn xorshift(mut x: u64) -> impl FnMut() -> u64 {
    move || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        x
    }
}
