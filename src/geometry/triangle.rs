//! The triangle: a plane through three vertices, cut to the triangle between them (the
//! course's `triangle` and `tri`, `COURSE-RULES.md` §14).

use super::{Hit, Miss, Plane, Ray, Vec3};
use crate::Scalar;

/// Why a triangle cannot be built.
///
/// ```
/// use fixray::geometry::{Triangle, TriangleError, Vec3};
/// use fixray::I16F16;
///
/// let v = |x, y, z| Vec3::<I16F16>::from_f64([x, y, z]).unwrap();
/// let on_a_line = [v(0.0, 0.0, -5.0), v(1.0, 1.0, -5.0), v(2.0, 2.0, -5.0)];
/// assert_eq!(Triangle::new(on_a_line), Err(TriangleError::Degenerate));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TriangleError {
    /// Two vertices coincide, or the three lie on one line (within the format's
    /// resolution): the triangle has no plane.
    Degenerate,
    /// `N·vertex` does not fit the number format.
    OffsetOutOfRange,
}

/// How far outside an edge, in units of [`Scalar::ulp`] of the coordinates' magnitude, a
/// point still counts as on it: the rounding of a computed hit point (a few ulps, as for
/// [`Plane::residual_bound`]) with margin, so that a ray through an edge or a vertex hits,
/// and two triangles sharing an edge leave no crack between them.
pub const EDGE_SLACK_ULPS: i32 = 32;

/// A triangle with vertices `a`, `b`, `c`: the plane through them with the normal
/// `N = unit(unit(b − a) × unit(c − a))` (the course's formula; its `tri` entity's
/// `(b − a) × (c − b)` has the same direction), and the region inside the three edges,
/// edges and vertices included.
///
/// ```
/// use fixray::{I16F16, Scalar};
/// use fixray::geometry::{Ray, RayKind, Triangle, Vec3};
///
/// let v = |x, y, z| Vec3::<I16F16>::from_f64([x, y, z]).unwrap();
/// let tri = Triangle::new([v(0.0, 0.0, -5.0), v(4.0, 0.0, -5.0), v(0.0, 4.0, -5.0)]).unwrap();
/// let down = |x, y| Ray { base: v(x, y, 5.0), dir: v(0.0, 0.0, -1.0), kind: RayKind::Primary };
/// assert_eq!(tri.intersect(&down(1.0, 1.0), I16F16::DEFAULT_EPSILON).unwrap().t, 10);
/// assert!(tri.intersect(&down(2.0, 2.0), I16F16::DEFAULT_EPSILON).is_ok()); // on an edge
/// assert!(tri.intersect(&down(3.0, 3.0), I16F16::DEFAULT_EPSILON).is_err());
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Triangle<S> {
    plane: Plane<S>,
    /// Per edge `from → to`: the inward unit normal `N × unit(to − from)` in the plane
    /// and its offset `inward·from`, so that a point's side of the edge is
    /// `inward·p − offset` (one wide dot product: the edge's unit vector and the cross
    /// product are per triangle, not per test).
    edges: [(Vec3<S>, S); 3],
}

impl<S: Scalar> Triangle<S> {
    /// The triangle through `vertices`.
    ///
    /// # Errors
    /// [`TriangleError::Degenerate`] when the vertices span no plane,
    /// [`TriangleError::OffsetOutOfRange`] when its offset does not fit.
    pub fn new(vertices: [Vec3<S>; 3]) -> Result<Self, TriangleError> {
        let [a, b, c] = vertices;
        let edge = |p: Vec3<S>| p.diff(a).and_then(Vec3::unit);
        let normal = edge(b)
            .zip(edge(c))
            .and_then(|(ab, ac)| ab.cross(ac))
            .filter(|n| n.max_abs() > S::ZERO)
            .ok_or(TriangleError::Degenerate)?;
        let plane = Plane::new(normal, a).map_err(|e| match e {
            super::PlaneError::ZeroNormal => TriangleError::Degenerate,
            super::PlaneError::OffsetOutOfRange => TriangleError::OffsetOutOfRange,
        })?;
        let n = plane.normal();
        let edge = |from: Vec3<S>, to: Vec3<S>| -> Option<(Vec3<S>, S)> {
            let inward = n.cross(to.diff(from)?.unit()?)?;
            Some((inward, inward.dot(from)?))
        };
        let edges = [edge(a, b), edge(b, c), edge(c, a)];
        let [Some(ab), Some(bc), Some(ca)] = edges else {
            return Err(TriangleError::OffsetOutOfRange);
        };
        Ok(Self {
            plane,
            edges: [ab, bc, ca],
        })
    }

    /// The triangle's plane.
    pub fn plane(&self) -> &Plane<S> {
        &self.plane
    }

    /// Whether a point of the triangle's plane lies inside it, edges and vertices
    /// included: on the inner side of each edge's line, or less than
    /// [`EDGE_SLACK_ULPS`] outside it. Each edge's side is the signed distance
    /// `(N × unit(edge))·(p − start)` in world units, evaluated as `inward·p − offset`
    /// with both per-triangle parts computed once (one wide dot product per edge).
    /// `false` where a quantity does not fit the format.
    pub fn contains(&self, p: Vec3<S>) -> bool {
        // The magnitude of the values compared: the point's and the edges' offsets.
        let m = self
            .edges
            .iter()
            .fold(p.max_abs().max(S::ONE), |m, e| m.max(e.1.abs()));
        let Some(slack) = S::from_i32(EDGE_SLACK_ULPS).and_then(|k| k.checked_mul(m.ulp())) else {
            return false;
        };
        // side = inward·p − offset ≥ −slack, i.e. offset − inward·p ≤ slack (rounded once).
        self.edges.iter().all(|&(inward, offset)| {
            S::sub_dot3(offset, inward.to_array(), p.to_array()).is_some_and(|d| d <= slack)
        })
    }

    /// Intersects a ray: the plane test of [`Plane::intersect`] (the precision epsilon,
    /// the screen rule), then [`Triangle::contains`] on the hit point.
    ///
    /// # Errors
    /// The plane's [`Miss`], or [`Miss::OutsideBounds`] off the triangle.
    pub fn intersect(&self, ray: &Ray<S>, epsilon: S) -> Result<Hit<S>, Miss> {
        let hit = self.plane.intersect(ray, epsilon)?;
        if self.contains(hit.point) {
            Ok(hit)
        } else {
            Err(Miss::OutsideBounds)
        }
    }
}
