//! Unit tests of the kernel's internal modules that span a whole module:
//! properties and accuracy sweeps (the smaller tests sit beside their code).

mod coverage;
mod normalize;
mod public_items;
mod span_shaders;
mod specular_table;
