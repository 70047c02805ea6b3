// Written by fixshade's mesh converter (fixshade_host::mesh_convert): 4 vertices, 4 triangles.

/// `TETRAHEDRON`'s positions, `Q.15` fractions of its box.
pub static TETRAHEDRON_POSITIONS: [[i16; 3]; 4] = [
    [32767, 32767, 32767],
    [32767, -32768, -32768],
    [-32768, 32767, -32768],
    [-32768, -32768, 32767],
];

/// `TETRAHEDRON`'s normals, octahedral.
pub static TETRAHEDRON_NORMALS: [::fixshade::mesh::PackedNormal; 4] = [
    ::fixshade::mesh::PackedNormal::from_bits(10922, 10922),
    ::fixshade::mesh::PackedNormal::from_bits(21845, -21845),
    ::fixshade::mesh::PackedNormal::from_bits(-21845, 21845),
    ::fixshade::mesh::PackedNormal::from_bits(-10922, -10922),
];

/// `TETRAHEDRON`'s triangles.
pub static TETRAHEDRON_INDICES: [[u16; 3]; 4] = [
    [0, 1, 2],
    [0, 3, 1],
    [0, 2, 3],
    [1, 3, 2],
];

/// `TETRAHEDRON`, in its box (offset `I8F24`, scale `U8F24`, raw).
pub static TETRAHEDRON: ::fixshade::mesh::Mesh<'static> = ::fixshade::mesh::Mesh::new(
    &TETRAHEDRON_POSITIONS,
    ::fixshade::mesh::Bounds::from_bits([4194433, 129, 129], [8388737, 8388737, 8388737]),
    &TETRAHEDRON_INDICES,
)
.with_normals(&TETRAHEDRON_NORMALS);
