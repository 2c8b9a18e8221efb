//! The spheres' boxes on the screen: the rows and columns whose primary rays can meet a
//! sphere, so that a pixel outside them skips its test (bit for bit: the margin is far
//! wider than every rounding).

use super::Primary;
use crate::{Scalar, SceneView, Vec3};

/// The rows whose primary rays can meet a sphere (centre `eye − oc`, radius² `rr`):
/// `(first, last)`, or `(1, 0)` (none). A scanline's rays `D = (x − eye.x, dy, dz)` all
/// lie in the plane through the eye with normal `n = (0, −dz, dy)`; a ray misses the
/// sphere when the centre lies farther than `r` from that plane, and every row from
/// which the centre is farther than `r·√(9/8)` is left out. There the ray test's
/// discriminant `b² − ac = |D|²(r² − dist²) ≤ −|D|²r²/8` is negative by far more than
/// the rounding of `b`, `a = |D|²` and `c`, and than this test's own: in units of
/// `|D|²`, both are a few `DELTA·(1 + |oc|/|dz|)²` (`|D| ≥ |dz|`, `|b| ≤ |oc||D|`,
/// `c ≤ |oc|²`), and a sphere's rows are bounded only when `r² ≥ 256 DELTA (1 +
/// 2|oc|∞/|dz|)²`, so `r²/8` is at least 32 times that (any other sphere, or a quantity
/// that does not fit, keeps every row). The skipped pixels draw what the test would
/// have: bit for bit.
pub(super) fn sphere_rows<S: Scalar>(
    scene: &SceneView<'_, S>,
    oc: Vec3<S>,
    rr: S,
    dz: S,
) -> (u16, u16) {
    let camera = &scene.camera;
    let eye_y = camera.viewpoint.y;
    lines_near(
        camera.height,
        |j| camera.screen_y(j)?.checked_sub(eye_y),
        (oc, oc.y),
        rr,
        dz,
    )
}

/// The columns whose primary rays can meet a sphere: [`sphere_rows`] with the roles of
/// `x` and `y` exchanged. A column's rays `D = (dx, y − eye.y, dz)` all lie in the plane
/// through the eye with normal `(dz, 0, −dx)`, and the same test, margin and guard
/// decide. A pixel's `D.x` is stepped along its scanline, off the column's exact
/// `dx` by at most `RESYNC_PIXELS` (16) DELTAs (the step is rounded once per frame):
/// that moves the ray's squared distance from the centre by about
/// `2·RESYNC_PIXELS·r·DELTA·|oc|/|dz|`, inside the `r²/8` margin the guard leaves:
/// `r ≥ 16 √DELTA (1 + 2|oc|∞/|dz|) ≥ 32 √DELTA |oc|/|dz|`, at least
/// `256 DELTA |oc|/|dz|` for every format's `DELTA ≤ 2⁻⁶`. Bit for bit, as the rows.
pub(super) fn sphere_columns<S: Scalar>(
    scene: &SceneView<'_, S>,
    oc: Vec3<S>,
    rr: S,
    dz: S,
) -> (u16, u16) {
    let camera = &scene.camera;
    let eye_x = camera.viewpoint.x;
    lines_near(
        camera.width,
        |i| camera.screen_x(i)?.checked_sub(eye_x),
        (oc, oc.x),
        rr,
        dz,
    )
}

/// The first and last of the screen's `n` rows or columns whose plane of rays passes
/// within `r·√(9/8)` of a sphere's centre ([`sphere_rows`], [`sphere_columns`]): `d(i)`
/// is line `i`'s `D.y` (a row) or `D.x` (a column), `oc_c` the same coordinate of
/// `oc`. A line is far where `(dz·oc_c − d·oc_z)² > (9/8)·r²·(d² + dz²)`,
/// in the format; every line is kept where the sphere is too small for the margin
/// ([`bounded`]). Inlined into both: one copy of the source, and the set-up of a frame
/// with three spheres costs no call per line on the M0.
#[inline(always)]
fn lines_near<S: Scalar>(
    n: u16,
    d: impl Fn(u16) -> Option<S>,
    (oc, oc_c): (Vec3<S>, S),
    rr: S,
    dz: S,
) -> (u16, u16) {
    let oc_z = oc.z;
    if !bounded(oc, rr, dz) {
        return (0, n.saturating_sub(1));
    }
    let far = |i: u16| -> Option<bool> {
        let d = d(i)?;
        let k = dz.checked_mul(oc_c)?.checked_sub(d.checked_mul(oc_z)?)?;
        let nn = d.checked_mul(d)?.checked_add(dz.checked_mul(dz)?)?;
        let rhs = rr.checked_mul(nn)?.mul_ratio(9, 8)?;
        Some(k.checked_mul(k)? > rhs)
    };
    span(n, far)
}

/// Whether a sphere is large enough for [`sphere_rows`]' and [`sphere_columns`]' margin:
/// `r² ≥ 256 DELTA (1 + 2|oc|∞/|dz|)²`.
pub(super) fn bounded<S: Scalar>(oc: Vec3<S>, rr: S, dz: S) -> bool {
    let bound = oc
        .max_abs()
        .checked_mul_int(2)
        .and_then(|m| m.checked_div(dz.abs()))
        .and_then(|q| S::ONE.checked_add(q))
        .and_then(|g| g.checked_mul(g))
        .and_then(|g| g.checked_mul(S::DELTA.checked_mul_int(256)?));
    bound.is_some_and(|b| rr >= b)
}

/// The first and last of `0..n` that `far` does not call far (`(1, 0)`: none).
pub(super) fn span(n: u16, far: impl Fn(u16) -> Option<bool>) -> (u16, u16) {
    let mut found = (1, 0);
    for j in 0..n {
        if far(j) != Some(true) {
            if found.0 > found.1 {
                found = (j, j);
            } else {
                found.1 = j;
            }
        }
    }
    found
}

impl<S: Scalar> Primary<S> {
    /// The columns of scanline `row` where a sphere can be met (the union of the boxes
    /// of [`sphere_rows`] and [`sphere_columns`] of the spheres on the row; `(1, 0)`:
    /// none).
    pub(crate) fn sphere_columns_on_row(&self, row: u16) -> (u16, u16) {
        self.sphere_columns_on_row_of(row, u8::MAX)
    }

    /// Every sphere's box on the screen, `(rows, columns)`, first and last inclusive
    /// ([`sphere_rows`], [`sphere_columns`]): outside it no primary ray meets the sphere.
    #[cfg(feature = "sampling")]
    pub(crate) fn sphere_boxes(&self) -> impl Iterator<Item = ((u16, u16), (u16, u16))> + '_ {
        self.terms
            .iter()
            .filter(|t| t.sphere)
            .map(|t| (t.rows, t.columns))
    }

    /// [`Primary::sphere_columns_on_row`] for the spheres among the objects `objects`
    /// (bit `i`: object `i`).
    pub(crate) fn sphere_columns_on_row_of(&self, row: u16, objects: u8) -> (u16, u16) {
        self.terms
            .iter()
            .filter(|t| {
                t.sphere
                    && objects
                        .checked_shr(u32::from(t.index))
                        .is_some_and(|b| b & 1 == 1)
            })
            .filter(|t| row >= t.rows.0 && row <= t.rows.1)
            .filter(|t| t.columns.0 <= t.columns.1)
            .fold((1, 0), |(a, b), t| {
                if a > b {
                    t.columns
                } else {
                    (a.min(t.columns.0), b.max(t.columns.1))
                }
            })
    }
}
