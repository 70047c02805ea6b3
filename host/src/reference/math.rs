//! Small `f64` vector and matrix helpers private to the reference.

pub(crate) type V3 = [f64; 3];
pub(crate) type M4 = [[f64; 4]; 4];

pub(crate) fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

pub(crate) fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

pub(crate) fn scale(a: V3, s: f64) -> V3 {
    [a[0] * s, a[1] * s, a[2] * s]
}

pub(crate) fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub(crate) fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

pub(crate) fn length(a: V3) -> f64 {
    dot(a, a).sqrt()
}

/// Unit vector along `a`; the zero vector (or a non-finite length) gives zero.
pub(crate) fn normalize(a: V3) -> V3 {
    let len = length(a);
    if len > 0.0 && len.is_finite() {
        scale(a, 1.0 / len)
    } else {
        [0.0; 3]
    }
}

pub(crate) fn mat_mul(a: &M4, b: &M4) -> M4 {
    let mut m = [[0.0; 4]; 4];
    for (r, row) in m.iter_mut().enumerate() {
        for (c, out) in row.iter_mut().enumerate() {
            *out = (0..4).map(|k| a[r][k] * b[k][c]).sum();
        }
    }
    m
}

/// `m · (p, 1)`, all four components.
pub(crate) fn transform4(m: &M4, p: V3) -> [f64; 4] {
    let mut out = [0.0; 4];
    for (r, o) in out.iter_mut().enumerate() {
        *o = m[r][0] * p[0] + m[r][1] * p[1] + m[r][2] * p[2] + m[r][3];
    }
    out
}

/// `m · (p, 1)` keeping x, y, z (the matrices used here are affine).
pub(crate) fn transform_point(m: &M4, p: V3) -> V3 {
    let q = transform4(m, p);
    [q[0], q[1], q[2]]
}

/// The 3 × 3 part of `m` applied to `d`.
pub(crate) fn transform_dir(m: &M4, d: V3) -> V3 {
    [
        m[0][0] * d[0] + m[0][1] * d[1] + m[0][2] * d[2],
        m[1][0] * d[0] + m[1][1] * d[1] + m[1][2] * d[2],
        m[2][0] * d[0] + m[2][1] * d[1] + m[2][2] * d[2],
    ]
}

/// Inverse transpose of the 3 × 3 part of `m`, or `None` if singular.
pub(crate) fn normal_matrix(m: &M4) -> Option<[[f64; 3]; 3]> {
    let a = |r: usize, c: usize| m[r][c];
    // Cofactor matrix: inverse transpose = cofactors / det.
    let mut cof = [[0.0; 3]; 3];
    for (r, row) in cof.iter_mut().enumerate() {
        for (c, out) in row.iter_mut().enumerate() {
            let (r1, r2) = ((r + 1) % 3, (r + 2) % 3);
            let (c1, c2) = ((c + 1) % 3, (c + 2) % 3);
            *out = a(r1, c1) * a(r2, c2) - a(r1, c2) * a(r2, c1);
        }
    }
    let det = a(0, 0) * cof[0][0] + a(0, 1) * cof[0][1] + a(0, 2) * cof[0][2];
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    Some(cof.map(|row| row.map(|x| x / det)))
}

pub(crate) fn mul3(m: &[[f64; 3]; 3], v: V3) -> V3 {
    [dot(m[0], v), dot(m[1], v), dot(m[2], v)]
}
