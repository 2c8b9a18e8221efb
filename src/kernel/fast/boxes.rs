//! The spheres' boxes on the screen: the rows and columns whose primary rays can meet a
//! sphere, so that a pixel outside them skips its test (bit for bit: the margin is far
//! wider than every rounding); and a sphere's chord of one scanline, the part of its box
//! where the row's rays pass near it ([`Primary::sphere_chords_on_row`]).

use super::{Primary, Term};
use crate::{Scalar, SceneView, Shape, Vec3};

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

/// The columns of a scanline whose rays `D = (x − eye.x, dy, dz)` can meet the sphere of
/// term `t` (a sphere whose box holds the row): its box's columns narrowed to its chord.
/// `None`: no chord is certified (the box's columns then).
///
/// A column is far when its ray (the column's exact `D.x`) passes farther than
/// `r·√(9/8)` from the centre ([`RowRays::far`]): there the ray test finds no hit, by the
/// boxes' argument (the sphere `bounded`; the pixel's stepped `D.x` off the exact one by
/// at most 16 DELTAs, as for a column's box). The chord's ends are guessed from where the
/// row's line of rays meets the cone of `r·√(9/8)` (two roots), then certified: the
/// column before the first and the one after the last are far, and a column between
/// passes within `r·√(17/16)` of the centre. Along the line the squared distance from the
/// centre has one minimum, one maximum (`|oc|²`, the ray square to `oc`) and tends to
/// `oc.y² + oc.z²` at both ends, which is kept at least `(5/4)r²`; so from a far column
/// outward, away from a nearer one, every column is far (the roundings of these tests are
/// a few DELTAs against a margin of `r²/16`). Checked at every pixel of random sphere
/// scenes (`fast/invariants.rs`).
pub(super) fn sphere_chord<S: Scalar>(
    scene: &SceneView<'_, S>,
    p: &Primary<S>,
    t: &Term<S>,
    (dy, dz): (S, S),
) -> Option<(u16, u16)> {
    let Shape::Sphere(sphere) = &scene.objects.get(usize::from(t.index))?.shape else {
        return None;
    };
    let eye = scene.camera.viewpoint;
    let oc = eye.diff(sphere.center())?;
    let rr = sphere.radius_sq();
    // The far ends of the line: `oc.y² + oc.z² ≥ (5/4)r²`.
    let side =
        oc.y.checked_mul(oc.y)?
            .checked_add(oc.z.checked_mul(oc.z)?)?;
    if !t.bounded || side.checked_mul_int(4)? < rr.checked_mul_int(5)? {
        return None;
    }
    // The guess: `(oc·D)² = K·|D|²` with `K = |oc|² − (9/8)r²` (`t.num` is `|oc|² − r²`),
    // i.e. `A·s² + 2·oc.x·B·s + B² − K·m = 0` with `A = oc.x² − K < 0`,
    // `B = oc.y·dy + oc.z·dz` and `m = dy² + dz²`; a root `s = (−oc.x·B ± √K·√Q)/A`
    // (`Q = B² + A·m`) is the column `(s − D.x₀)/step`.
    let k = t.num.checked_sub(rr.mul_ratio(1, 8)?)?;
    let a = oc.x.checked_mul(oc.x)?.checked_sub(k)?;
    let b = oc.y.checked_mul(dy)?.checked_add(oc.z.checked_mul(dz)?)?;
    let rays = RowRays::new(scene, p, oc, rr, (dy, dz))?;
    let q = b.checked_mul(b)?.checked_add(a.checked_mul(rays.m)?)?;
    if k <= S::ZERO || a >= S::ZERO || q <= S::ZERO {
        return None;
    }
    let root = k.checked_sqrt()?.checked_mul(q.checked_sqrt()?)?;
    let base =
        oc.x.checked_mul(b)?
            .checked_add(a.checked_mul(rays.dx(0)?)?)?;
    let den = a.checked_mul(p.next_dx_after(S::ZERO)?)?;
    let column = |v: S| v.checked_div(den)?.floor_to_i32();
    let (box_lo, box_hi) = (i32::from(t.columns.0), i32::from(t.columns.1));
    let first = column(root.checked_sub(base)?)?.max(box_lo);
    let last = column(S::ZERO.checked_sub(base)?.checked_sub(root)?)?
        .checked_add(1)?
        .min(box_hi);
    if first > last {
        return None;
    }
    let far = |c: i32| c < box_lo || c > box_hi || rays.far(c) == Some(Some(true));
    let near = rays.far(first + (last - first) / 2) == Some(Some(false));
    if !(near && far(first - 1) && far(last + 1)) {
        return None;
    }
    Some((u16::try_from(first).ok()?, u16::try_from(last).ok()?))
}

/// A scanline's rays `D = (dx, dy, dz)` against a sphere (`oc = eye − centre`, `rr = r²`):
/// the parts of `|oc × D|²` and `|D|²` the row's rays share.
struct RowRays<'a, S: Scalar> {
    scene: &'a SceneView<'a, S>,
    unit: Option<S>,
    oc: Vec3<S>,
    rr: S,
    /// `oc.y·dz − oc.z·dy`, `oc.x·dz`, `oc.x·dy` and `m = dy² + dz²`.
    c1: S,
    xz: S,
    xy: S,
    m: S,
}

impl<'a, S: Scalar> RowRays<'a, S> {
    fn new(
        scene: &'a SceneView<'a, S>,
        p: &Primary<S>,
        oc: Vec3<S>,
        rr: S,
        (dy, dz): (S, S),
    ) -> Option<Self> {
        Some(Self {
            scene,
            unit: (p.x_unit > S::ZERO).then_some(p.x_unit),
            oc,
            rr,
            c1: oc.y.checked_mul(dz)?.checked_sub(oc.z.checked_mul(dy)?)?,
            xz: oc.x.checked_mul(dz)?,
            xy: oc.x.checked_mul(dy)?,
            m: dy.checked_mul(dy)?.checked_add(dz.checked_mul(dz)?)?,
        })
    }

    /// Column `c`'s exact `D.x` (`Primary::restart_dir`'s).
    fn dx(&self, c: u16) -> Option<S> {
        let camera = &self.scene.camera;
        camera
            .screen_x_in(self.unit, c)?
            .checked_sub(camera.viewpoint.x)
    }

    /// Whether column `c`'s ray passes farther than `r·√(9/8)` from the centre
    /// (`Some(true)`), within `r·√(17/16)` (`Some(false)`), or between (`None` inside):
    /// `|oc × D|²` against `r²·|D|²`.
    fn far(&self, c: i32) -> Option<Option<bool>> {
        let (oc, dx) = (self.oc, self.dx(u16::try_from(c).ok()?)?);
        let c2 = oc.z.checked_mul(dx)?.checked_sub(self.xz)?;
        let c3 = self.xy.checked_sub(oc.y.checked_mul(dx)?)?;
        let g = self.c1.checked_mul(self.c1)?;
        let g = g
            .checked_add(c2.checked_mul(c2)?)?
            .checked_add(c3.checked_mul(c3)?)?;
        let near = self
            .rr
            .checked_mul(dx.checked_mul(dx)?.checked_add(self.m)?)?;
        Some(if g.checked_mul_int(8)? > near.checked_mul_int(9)? {
            Some(true)
        } else if g.checked_mul_int(16)? < near.checked_mul_int(17)? {
            Some(false)
        } else {
            None
        })
    }
}

/// `hull` widened to hold the columns `a..=b` (none when `a > b`).
pub(crate) fn hull(hull: &mut Option<(u16, u16)>, (a, b): (u16, u16)) {
    if a <= b {
        *hull = Some(hull.map_or((a, b), |(c, d)| (c.min(a), d.max(b))));
    }
}

impl<S: Scalar> Primary<S> {
    /// The columns of scanline `row` where a sphere can be met: each box of a sphere on
    /// the row ([`sphere_rows`], [`sphere_columns`]) narrowed to its chord of the row
    /// ([`sphere_chord`]); `(1, 0)`: none. Out of line: a scanline's set-up keeps its own
    /// code (the M0's copies of its state).
    #[inline(never)]
    pub(crate) fn sphere_chords_on_row(&self, scene: &SceneView<'_, S>, row: u16) -> (u16, u16) {
        let mut columns = None;
        // The row's `D.y` and `D.z` (`Primary::restart_dir`'s).
        let camera = &scene.camera;
        let dir = camera
            .screen_y(row)
            .and_then(|y| y.checked_sub(camera.viewpoint.y))
            .map(|dy| (dy, self.dz));
        for t in self.terms.iter().filter(|t| {
            t.sphere && row >= t.rows.0 && row <= t.rows.1 && t.columns.0 <= t.columns.1
        }) {
            let chord = dir.and_then(|dir| sphere_chord(scene, self, t, dir));
            hull(&mut columns, chord.unwrap_or(t.columns));
        }
        columns.unwrap_or((1, 0))
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

    /// The columns of scanline `row` where a sphere among the objects `objects` (bit `i`:
    /// object `i`) can be met: the union of the boxes of [`sphere_rows`] and
    /// [`sphere_columns`] of those spheres on the row; `(1, 0)`: none.
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
