//! Fast primary rays for scenes of planes (infinite, tiled, finite, triangles) and
//! spheres, under the crate's rules.
//!
//! The reference path ([`crate::shade::trace_pixel`]) normalises every primary ray and
//! divides once per plane. Here, per frame, `num = D' − N·eye` is computed once per plane
//! (the eye is every primary ray's base), and per pixel the ray's direction is left
//! unnormalised, `D = screen point − eye` (its x stepped along the scanline). `N·D` is
//! linear along the scanline: it is kept as the unrounded double-width sum
//! (`KernelArith::Acc`) and grows by the per-frame `N.x × step` per pixel, so that a
//! pixel costs no product for it (in the fixed formats bit for bit the wide dot product
//! of the stepped `D`). Spheres keep `oc·D` the same way (`oc = eye − centre`) and test
//! the discriminant's sign exactly (`sphere_root`). The plane test of `docs/scene-format.md`
//! is then evaluated in an equivalent form without dividing:
//!
//! - parallel, `|N·d| < EPS` with `d = D/|D|`  ⇔  `(N·D)² < EPS·(EPS·|D|²)`;
//! - behind, `t < 0`  ⇔  `num` and `N·D` of opposite signs;
//! - in front of the screen, `hit.z > 0`  ⇔  `t' = num/(N·D) < 1` (the screen point is at
//!   `t' = 1` exactly, since `D` ends on the screen)  ⇔  `|num| < |N·D|`;
//! - nearest: `t'_i < t'_j`  ⇔  `|num_i|·|N·D_j| < |num_j|·|N·D_i|` (exact products,
//!   [`crate::Scalar::cmp_products`]).
//!
//! Only the winning plane is divided (`t' = num/N·D`, hit = eye + t'·D), and a finite
//! plane's bounds are checked on its own hit. Results are those of the definition up to
//! rounding: pixels can differ only where two planes meet, at the epsilon and at the
//! screen (`tests/fast.rs` compares every pixel with the reference path). A pixel whose
//! winner does not fit the format falls back to the reference path, so range misses are
//! exactly the reference's.

use heapless::Vec;

use core::cmp::Ordering;

use crate::geometry::ShadowCone;
use crate::shade::{SIDE_BITS_LIGHTS, SideBits};
use crate::{Scalar, SceneView, Shape, Vec3};

/// A term of the fast path: which object and, for a plane, `num = D' − N·eye`, for a
/// sphere `num = |oc|² − r²` with `oc = eye − centre` (positive: the eye is outside).
/// The vector the scanline dots `D` with (the normal, `oc`) is read from the scene: on a
/// 16 KB chip a copy of every one is RAM the stack needs.
#[derive(Debug, Clone, Copy)]
struct Term<S> {
    index: u8,
    num: S,
    sphere: bool,
    /// The rows the term can be hit on (first, last): every row for a plane; for a
    /// sphere the rows whose plane of rays passes near it ([`sphere_rows`]), so that a
    /// pixel on another row skips its test.
    rows: (u16, u16),
    /// The columns likewise ([`sphere_columns`]): a sphere is tested only inside its
    /// box on the screen.
    columns: (u16, u16),
}

/// What a term dots `D` with: the unit normal of a plane-like object, `eye − centre` of
/// a sphere.
#[inline]
fn axis_of<S: Scalar>(scene: &SceneView<'_, S>, index: u8) -> Option<Vec3<S>> {
    match &scene.objects.get(usize::from(index))?.shape {
        Shape::Sphere(s) => scene.camera.viewpoint.diff(s.center()),
        shape @ (Shape::Plane(_)
        | Shape::Tiled { .. }
        | Shape::Finite(_)
        | Shape::Textured(_)
        | Shape::Triangle(_)
        | Shape::Revsurf(_)) => Some(shape.plane()?.normal()),
    }
}

/// The most pixels a scanline steps `D.x` by addition before restarting from the exact
/// screen coordinate ([`resync_pixels`]; a multiple of every format's).
pub const RESYNC_PIXELS: u16 = 16;

/// How many pixels a scanline of format `S` steps `D.x` by addition before restarting
/// from the exact screen coordinate (one `mul_ratio`, a 64-bit division): the trade
/// between the drift of the stepped coordinate (≤ ½ DELTA per step), the cost of the
/// exact one, and how long a certified block can be ([`Primary::certify_block`]: at
/// most this many pixels). 16 in the formats with at least 16 fraction bits (and the
/// floats), 8 in the coarser ones (I20F12), whose drift is 16 times larger: there, 16
/// moves many more of the default scene's pixels away from f64 and the specular scene's
/// past its budget. 16 rather than 8: fewer restarts and half as many blocks to certify;
/// not 32: more blocks would hold a crossing, and fail.
pub(crate) const fn resync_pixels<S: Scalar>() -> u16 {
    // (`as` widens a `u32` here: `usize::from` is not `const`.)
    if core::mem::size_of::<S>() * 8 < S::INT_BITS as usize + 16 {
        RESYNC_PIXELS / 2
    } else {
        RESYNC_PIXELS
    }
}

/// Where a scanline outside a certified block tries to start one: every this many
/// columns (a restart's, and half-way to the next, so that a block that fails for a
/// crossing in one half may hold in the other).
pub(crate) const fn block_starts<S: Scalar>() -> u16 {
    resync_pixels::<S>() / 2
}

/// The per-frame part of the fast path; `None` from [`Primary::new`] when the scene is not
/// made of planes and spheres (the eye outside them) or a per-frame quantity does not fit
/// the format.
#[derive(Debug, Clone)]
pub struct Primary<S: Scalar> {
    terms: Vec<Term<S>, FAST_OBJECTS>,
    /// `N_i.x × step_x` of every term, unrounded: what `N·D` grows by from pixel to
    /// pixel (`KernelArith::Acc`).
    steps: Vec<S::Acc, FAST_OBJECTS>,
    /// `D'_i − N_i·light_j` at `j × objects + i` (the lights' sides of every plane, for
    /// shadow segments: [`crate::shade::PlaneSides`]); empty when they do not fit
    /// [`MAX_SIDES`] or the format.
    at_lights: Vec<S, MAX_SIDES>,
    /// Per light (the first [`SIDE_BITS_LIGHTS`]), which of its `at_lights` are
    /// positive, as bits (one per object; read only where `at_lights` is kept).
    light_positive: [u8; SIDE_BITS_LIGHTS],
    /// The spheres among the terms, as bits.
    sphere_bits: u8,
    /// Whether a scanline may draw a block of pixels with one certified winner
    /// ([`Primary::certify_block`]): every object a plain or tiled plane, in a format
    /// whose products are exact.
    blocks: bool,
    /// The spheres' shadow cones from the lights ([`ShadowCone`]).
    cones: Vec<ShadowCone<S>, MAX_CONES>,
    /// Whether a term is a sphere (the scanline then keeps `D·D`).
    spheres: bool,
    /// The terms whose vector has `x = 0` (a floor's or a back wall's normal), as bits:
    /// their `N·D` is the same at every pixel of a scanline (its step is `0 × step`), so
    /// a pixel does not step it and a restart of the same scanline keeps it.
    still: u8,
    /// Screen x step between pixel centres, `WX / W`.
    step_x: S,
    /// `resync_pixels·|step_x|`: how far `|D.x|` can move between two restarts of a
    /// scanline (`None`: too far for the format; each pixel then bounds itself).
    resync_span: Option<S>,
    /// `−eye.z`, the z of every `D`.
    dz: S,
    /// The screen's x unit where the window divides exactly (`Camera::x_unit`; zero:
    /// it does not): a restart's screen x is then a product, not a division.
    x_unit: S,
    /// Whether every term's `N·D` (and its unrounded sum, and the sum's rounding) fits
    /// the format at every `D` of the frame ([`Primary::frame_fits`]): a step then
    /// needs no overflow test (`KernelArith::acc_step_fitting`).
    fits: bool,
}

/// Whether format `S` draws certified blocks ([`Primary::certify_block`]) on this target:
/// its products are exact (its stepped terms are the exact ones, its comparisons exact)
/// and it is a 32-bit format (a 64-bit format's scanline would carry the block's state
/// and the lookahead row's frame on a 16 KB chip where I32F32 has a few bytes to spare),
/// on a core without a long multiply, where the search they save is dear, and on hosted
/// targets, so that the host's tests, reports and simulator take the same path (the
/// pixels are the same either way). On the Cortex-M4F and RISC-V the search is cheap
/// and the blocks cost more than they save (on RISC-V, and on both cores for the scenes
/// with spheres).
pub(crate) const fn blocks_for<S: Scalar>() -> bool {
    S::EXACT_PRODUCTS
        && core::mem::size_of::<S>() <= 4
        && cfg!(any(no_long_multiply, not(target_os = "none")))
}

/// A scanline's certified block ([`Primary::start_block`]): the column after it (0:
/// none) and the term that wins throughout ([`NO_TERM`]: the background).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Block {
    stop: u16,
    winner: u8,
}

impl Block {
    /// Whether the block holds no pixel (none was certified).
    pub(crate) fn is_empty(&self) -> bool {
        self.stop == 0
    }

    /// The plane that wins throughout the block, if `column` is in it.
    #[inline(always)]
    pub(crate) fn plane_at(&self, column: u16) -> Option<usize> {
        (column < self.stop && self.winner != NO_TERM).then_some(usize::from(self.winner))
    }
}

impl Default for Block {
    fn default() -> Self {
        Self {
            stop: 0,
            winner: NO_TERM,
        }
    }
}

/// No term: a block of the background (a frame has at most [`FAST_OBJECTS`] terms).
const NO_TERM: u8 = u8::MAX;

/// The last pixel's winner, which a scanline's resync column certifies first
/// ([`Primary::start_block`]): an object's index, [`NO_TERM`] for the background, or
/// none known. One byte (an I32F32 scanline on a 16 KB chip has a few to spare).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Guess(u8);

/// No winner known ([`Guess`]).
const UNKNOWN: u8 = u8::MAX - 1;

// An object's index is never taken for one of the two marks.
// (`as` widens a `u8`: `usize::from` is not `const`.)
const _: () = assert!(FAST_OBJECTS < UNKNOWN as usize);

impl Default for Guess {
    fn default() -> Self {
        Self(UNKNOWN)
    }
}

impl Guess {
    /// The guess of a pixel's answer (`None`: not known; `Some(None)`: the background).
    pub(crate) fn of(found: Option<Option<usize>>) -> Self {
        Self(match found {
            Some(Some(i)) => u8::try_from(i)
                .ok()
                .filter(|i| *i < UNKNOWN)
                .unwrap_or(UNKNOWN),
            Some(None) => NO_TERM,
            None => UNKNOWN,
        })
    }

    /// The guessed winner (`Some(None)`: the background), if one is known.
    pub(crate) fn winner(self) -> Option<Option<usize>> {
        match self.0 {
            UNKNOWN => None,
            NO_TERM => Some(None),
            i => Some(Some(usize::from(i))),
        }
    }
}

/// How many sphere–light shadow cones a frame keeps (beyond, the exact test alone).
pub const MAX_CONES: usize = 3;

/// How many plane–light sides a frame keeps (objects × lights; beyond, shadow segments
/// compute their sides themselves): 48 bytes in I16F16, 96 in I32F32, a RAM budget a
/// 16 KB chip affords beside the rest of the frame (the shipped scenes need at most 9;
/// the frame's sphere terms and screen boxes share the same budget).
pub const MAX_SIDES: usize = 12;

/// The most objects the fast kernel takes: a scene with more is drawn on the reference
/// path. Its per-frame and per-scanline vectors (terms, steps, `N·D` and its unrounded
/// sum, the planes' sides at a hit) are sized by it, and on a 16 KB chip in I32F32 the
/// frame and the deepest shading stack must fit beside the scene.
pub const FAST_OBJECTS: usize = 8;

// A frame's still terms and a row's occluders are bits of a `u8`, one per object.
const _: () = assert!(FAST_OBJECTS <= 8);

/// A scanline's memo of its last still plane's hit ([`Primary::point_in`]): the key
/// (object, `|N·D|`, `D.y`) and its `t'`, `y` and `z`, and the distance bound for the
/// last `2|D|∞`. Kept by the stage sets whose scanlines keep a plane memo
/// (`Stages::Memo`).
#[derive(Debug, Clone)]
pub(crate) struct HitMemo<S> {
    /// Whether the last hit was a certified block's: every plane then lies out of the
    /// epsilon's margin at its pixel ([`Primary::certify_block`] checks both ends, and
    /// `|N·D|` is monotone between them).
    pub(crate) certified: bool,
    key: Option<(u8, S, S)>,
    t: S,
    y: S,
    z: S,
    bound: Option<(S, S)>,
}

impl<S: Scalar> Default for HitMemo<S> {
    fn default() -> Self {
        Self {
            certified: false,
            key: None,
            t: S::ZERO,
            y: S::ZERO,
            z: S::ZERO,
            bound: None,
        }
    }
}

/// The quiet planes of a scanline ([`Primary::quiet_planes`]).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Quiet<S> {
    /// The objects that are not quiet, as bits (one per object; all of them, `u8::MAX`,
    /// where the frame has another object than planes).
    pub(crate) loud: u8,
    /// Up to which `t'` the others are.
    pub(crate) t_max: S,
}

impl<S: Scalar> Default for Quiet<S> {
    fn default() -> Self {
        Self {
            loud: u8::MAX,
            t_max: S::ZERO,
        }
    }
}

/// What the fast path found at one pixel.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FastHit<S> {
    /// The object.
    pub index: usize,
    /// The hit point.
    pub point: Vec3<S>,
    /// An upper bound on the world distance `t` (for secondary-ray offsets).
    pub t_bound: S,
    /// The unnormalised ray direction `D`.
    pub dir: Vec3<S>,
    /// The hit's parameter along `D`, `t' = num/(N·D)` (the screen is at 1).
    pub param: S,
}

/// The per-scanline part: `N·D` (planes) or `oc·D` (spheres) of every term at the
/// current pixel (rounded, and the unrounded sum it steps), `D`, and `D.y² + D.z²`.
#[derive(Debug, Clone)]
pub struct Row<S: Scalar> {
    nd: Vec<S, FAST_OBJECTS>,
    acc: Vec<S::Acc, FAST_OBJECTS>,
    yz: S::Acc,
    dir: Vec3<S>,
    column: u16,
    row: u16,
    /// `ε·(dx_limit + |D.y| + |D.z|)` plus two ulps, set at each restart: a bound of
    /// `accepts_bounded` valid for every pixel whose `|D.x| ≤ dx_limit` (the next
    /// [`resync_pixels`]), so that a pixel needs no product for it. When it does not
    /// fit, `dx_limit` is negative and each pixel computes its own bound.
    eps_l1: S,
    dx_limit: S,
}

/// The plane test of the definition for a primary ray with unnormalised direction `D`:
/// `num = D' − N·eye`, `nd = N·D`, `eps_d2 = ε·|D|²`. Accepted unless the ray is parallel
/// within the epsilon, the plane is behind the eye, or the hit lies in front of the screen.
#[inline]
pub(crate) fn accepts<S: Scalar>(num: S, nd: S, eps: S, eps_d2: S) -> bool {
    // Parallel within the epsilon (also catches N·D = 0).
    if S::cmp_products(nd, nd, eps, eps_d2) == Some(Ordering::Less) || nd == S::ZERO {
        return false;
    }
    ahead(num, nd)
}

/// The rest of the plane test for a plane not parallel to the ray: not behind (`t' < 0`;
/// `num = 0` puts the hit at the eye, in front of the screen) and not in front of the
/// screen (`t' < 1`). `false` for `N·D = 0`.
#[inline]
fn ahead<S: Scalar>(num: S, nd: S) -> bool {
    nd != S::ZERO && num != S::ZERO && (num > S::ZERO) == (nd > S::ZERO) && num.abs() >= nd.abs()
}

/// `ε·(ax + |dy| + |dz|)` plus two ulps: the bound of [`accepts_bounded`] for every `D`
/// with `|D.x| ≤ ax` (`‖D‖₁` is at most `ax + |dy| + |dz|` there).
fn eps_l1_of<S: Scalar>(eps: S, ax: S, dy: S, dz: S) -> Option<S> {
    ax.checked_add(dy.abs())
        .and_then(|s| s.checked_add(dz.abs()))
        .and_then(|s| eps.checked_mul(s))
        .and_then(|b| b.checked_add(b.ulp()))
        .and_then(|b| b.checked_add(b.ulp()))
}

/// [`accepts`] with a bound first: `|N·D| ≥ ε·‖D‖₁` (`eps_l1`, with a margin of two
/// roundings) implies `(N·D)² ≥ ε²·|D|²` since `|D| ≤ ‖D‖₁`, so a plane that far from
/// parallel skips the exact squared test (two double-width products), which only planes
/// within that margin of the epsilon take (`eps_d2` computes `ε·|D|²` for them).
/// `None` when `ε·|D|²` does not fit (the reference path decides).
#[inline(always)]
fn accepts_bounded<S: Scalar>(
    num: S,
    nd: S,
    eps: S,
    eps_l1: Option<S>,
    eps_d2: impl FnOnce() -> Option<S>,
) -> Option<bool> {
    match eps_l1 {
        Some(bound) if nd.abs() >= bound => Some(ahead(num, nd)),
        _ => eps_d2().map(|e| accepts(num, nd, eps, e)),
    }
}

/// A sphere's near root along `D` as the fraction `t' = p/q` (`q > 0`), without a
/// division: with `c = |oc|² − r² > 0` (the eye outside), `b = oc·D` and `a = D·D`, the
/// roots are `(−b ± √(b² − a·c))/a`; the ray meets the sphere ahead when `b < 0` and the
/// discriminant is not negative (compared exactly, [`Scalar::cmp_products`]), and the
/// near root is `c/q` with `q = √(b² − ac) − b` (`−b > 0`: no cancellation, as in
/// [`crate::Sphere`]). A root in front of the screen (`t' < 1`) is a miss, as on the
/// reference path. `Ok(None)` for a miss, `Err(())` when the discriminant does not fit
/// the format (the reference path decides).
#[inline]
fn sphere_root<S: Scalar>(c: S, b: S, a: S) -> Result<Option<(S, S)>, ()> {
    if b >= S::ZERO || S::cmp_products(b, b, a, c) == Some(Ordering::Less) {
        return Ok(None);
    }
    let bb = S::acc_mul(b, b).ok_or(())?;
    let ac = S::acc_mul(a, c.checked_neg().ok_or(())?).ok_or(())?;
    let disc = S::acc_round(S::acc_add(bb, ac).ok_or(())?).ok_or(())?;
    let q = disc
        .max(S::ZERO)
        .checked_sqrt()
        .and_then(|root| root.checked_sub(b))
        .ok_or(())?;
    if q <= S::ZERO || c < q {
        // t' = c/q < 1: in front of the screen.
        return Ok(None);
    }
    Ok(Some((c, q)))
}

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
fn sphere_rows<S: Scalar>(scene: &SceneView<'_, S>, oc: Vec3<S>, rr: S, dz: S) -> (u16, u16) {
    let all = (0, scene.camera.height.saturating_sub(1));
    if !bounded(oc, rr, dz) {
        return all;
    }
    let eye_y = scene.camera.viewpoint.y;
    // Whether row `j`'s plane passes farther than r·√(9/8) from the centre:
    // (dz·oc.y − dy·oc.z)² > (9/8)·r²·(dy² + dz²), in the format.
    let far = |j: u16| -> Option<bool> {
        let dy = scene.camera.screen_y(j)?.checked_sub(eye_y)?;
        let k = dz.checked_mul(oc.y)?.checked_sub(dy.checked_mul(oc.z)?)?;
        let nn = dy.checked_mul(dy)?.checked_add(dz.checked_mul(dz)?)?;
        let rhs = rr.checked_mul(nn)?.mul_ratio(9, 8)?;
        Some(k.checked_mul(k)? > rhs)
    };
    span(scene.camera.height, far)
}

/// The columns whose primary rays can meet a sphere: [`sphere_rows`] with the roles of
/// `x` and `y` exchanged. A column's rays `D = (dx, y − eye.y, dz)` all lie in the plane
/// through the eye with normal `(dz, 0, −dx)`, and the same test, margin and guard
/// decide. A pixel's `D.x` is stepped along its scanline, off the column's exact
/// `dx` by at most `RESYNC_PIXELS` (16) DELTAs (the step is rounded once per frame):
/// that moves the ray's squared distance from the centre by about
/// `2·RESYNC_PIXELS·r·DELTA·|oc|/|dz|`, inside the `r²/8` margin the guard leaves:
/// `r ≥ 16 √DELTA (1 + 2|oc|∞/|dz|) ≥ 32 √DELTA |oc|/|dz|`, at least
/// `256 DELTA |oc|/|dz|` for every format's `DELTA ≤ 2⁻⁶`. Bit for bit, as the rows. (The test is [`sphere_rows`]' own, written out again: a shared
/// helper costs the frames of three-sphere scenes more on the M0.)
fn sphere_columns<S: Scalar>(scene: &SceneView<'_, S>, oc: Vec3<S>, rr: S, dz: S) -> (u16, u16) {
    let all = (0, scene.camera.width.saturating_sub(1));
    if !bounded(oc, rr, dz) {
        return all;
    }
    let eye_x = scene.camera.viewpoint.x;
    // (dz·oc.x − dx·oc.z)² > (9/8)·r²·(dx² + dz²), in the format.
    let far = |i: u16| -> Option<bool> {
        let dx = scene.camera.screen_x(i)?.checked_sub(eye_x)?;
        let k = dz.checked_mul(oc.x)?.checked_sub(dx.checked_mul(oc.z)?)?;
        let nn = dx.checked_mul(dx)?.checked_add(dz.checked_mul(dz)?)?;
        let rhs = rr.checked_mul(nn)?.mul_ratio(9, 8)?;
        Some(k.checked_mul(k)? > rhs)
    };
    span(scene.camera.width, far)
}

/// Whether a sphere is large enough for [`sphere_rows`]' and [`sphere_columns`]' margin:
/// `r² ≥ 256 DELTA (1 + 2|oc|∞/|dz|)²`.
fn bounded<S: Scalar>(oc: Vec3<S>, rr: S, dz: S) -> bool {
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
fn span(n: u16, far: impl Fn(u16) -> Option<bool>) -> (u16, u16) {
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

/// Every sphere's shadow cone from every light that fits ([`ShadowCone`]), up to
/// [`MAX_CONES`].
fn shadow_cones<S: Scalar>(
    scene: &SceneView<'_, S>,
    terms: &[Term<S>],
) -> Vec<ShadowCone<S>, MAX_CONES> {
    let mut cones = Vec::new();
    for (j, light) in scene.lights.iter().enumerate() {
        for term in terms.iter().filter(|t| t.sphere) {
            let Some(Shape::Sphere(s)) =
                scene.objects.get(usize::from(term.index)).map(|o| o.shape)
            else {
                continue;
            };
            let cone = ShadowCone::new(j, term.index, &s, light.location);
            if let Some(c) = cone
                && cones.push(c).is_err()
            {
                return cones;
            }
        }
    }
    cones
}

impl<S: Scalar> Primary<S> {
    /// Prepares a frame, or `None` when the fast path does not apply (the eye inside a
    /// sphere, more than
    /// [`FAST_OBJECTS`] objects, or a quantity out of range): the caller then uses the
    /// reference path.
    pub fn new(scene: &SceneView<'_, S>) -> Option<Self> {
        let eye = scene.camera.viewpoint;
        let step_x = scene
            .camera
            .world_width
            .mul_ratio(1, i32::from(scene.camera.width))?;
        let mut terms = Vec::new();
        let mut steps = Vec::new();
        let mut spheres = false;
        let mut still = 0u8;
        let mut sphere_bits = 0u8;
        for (index, object) in scene.objects.iter().enumerate() {
            let all_rows = (0, scene.camera.height.saturating_sub(1));
            let all_columns = (0, scene.camera.width.saturating_sub(1));
            let (num, axis, sphere, rows, columns) = match &object.shape {
                Shape::Sphere(s) => {
                    // Only with the eye outside every sphere (the near root is then the
                    // one, and c/q has no cancellation), and with the sphere code built in.
                    if !cfg!(feature = "spheres") {
                        return None;
                    }
                    let oc = eye.diff(s.center())?;
                    let c =
                        S::sub_dot3(s.radius_sq(), oc.to_array(), oc.to_array())?.checked_neg()?;
                    if c <= S::ZERO {
                        return None;
                    }
                    spheres = true;
                    let dz = S::ZERO.checked_sub(eye.z)?;
                    let rr = s.radius_sq();
                    let rows = sphere_rows(scene, oc, rr, dz);
                    (c, oc, true, rows, sphere_columns(scene, oc, rr, dz))
                }
                // The kernel has no term for a surface of revolution: the reference path.
                Shape::Revsurf(_) => return None,
                shape @ (Shape::Plane(_)
                | Shape::Tiled { .. }
                | Shape::Finite(_)
                | Shape::Textured(_)
                | Shape::Triangle(_)) => {
                    let plane = shape.plane()?;
                    let num =
                        S::sub_dot3(plane.offset(), plane.normal().to_array(), eye.to_array())?;
                    (num, plane.normal(), false, all_rows, all_columns)
                }
            };
            let index = u8::try_from(index).ok()?;
            terms
                .push(Term {
                    index,
                    num,
                    sphere,
                    rows,
                    columns,
                })
                .ok()?;
            if axis.x == S::ZERO {
                still |= 1 << (terms.len() - 1);
            }
            if sphere {
                sphere_bits |= 1 << (terms.len() - 1);
            }
            steps.push(S::acc_mul(axis.x, step_x)?).ok()?;
        }
        let mut at_lights = Vec::new();
        // The lights' positive sides as bits, per light (`SideBits::lights`).
        let mut light_positive = [0u8; SIDE_BITS_LIGHTS];
        let sides = terms.len().checked_mul(scene.lights.len());
        if sides.is_some_and(|n| n <= MAX_SIDES) {
            'lights: for (j, light) in scene.lights.iter().enumerate() {
                let mut positive = 0u8;
                for (i, term) in terms.iter().enumerate() {
                    if term.sphere {
                        // A sphere's shadow test does not use sides (`meets_segment_with`):
                        // a place holder keeps the list indexed by object.
                        at_lights.push(S::ZERO).ok()?;
                        continue;
                    }
                    let object = scene.objects.get(usize::from(term.index))?;
                    let plane = object.shape.plane()?;
                    let side = S::sub_dot3(
                        plane.offset(),
                        plane.normal().to_array(),
                        light.location.to_array(),
                    );
                    match side {
                        Some(a1) => {
                            if a1 > S::ZERO {
                                positive |= 1 << i;
                            }
                            at_lights.push(a1).ok()?;
                        }
                        None => {
                            at_lights.clear();
                            break 'lights;
                        }
                    }
                }
                // Beyond `SIDE_BITS_LIGHTS` lights, those lights have no bits.
                if let Some(slot) = light_positive.get_mut(j) {
                    *slot = positive;
                }
            }
        }
        let blocks = blocks_for::<S>()
            && scene
                .objects
                .iter()
                .all(|o| matches!(o.shape, Shape::Plane(_) | Shape::Tiled { .. }));
        let cones = if spheres {
            shadow_cones(scene, &terms)
        } else {
            Vec::new()
        };
        let mut primary = Self {
            terms,
            steps,
            at_lights,
            light_positive,
            cones,
            spheres,
            sphere_bits,
            blocks,
            still,
            step_x,
            resync_span: S::from_i32(i32::from(resync_pixels::<S>()))
                .and_then(|n| n.checked_mul(step_x.abs())),
            dz: S::ZERO.checked_sub(eye.z)?,
            x_unit: scene.camera.x_unit().unwrap_or(S::ZERO),
            fits: false,
        };
        primary.fits = primary.frame_fits(scene);
        Some(primary)
    }

    /// Whether every term fits at every `D` a scanline of the frame can take: `D.x`
    /// within [`Primary::dx_range`] (the stepped drift included), `D.y` between the first
    /// and the last row's, `D.z` the frame's. A term is affine in `D`, so its unrounded
    /// sum lies between its values at the four corners, and if each of those rounds
    /// into the format (half a DELTA added, no overflow) so does every sum between.
    fn frame_fits(&self, scene: &SceneView<'_, S>) -> bool {
        let fits = || -> Option<()> {
            let camera = &scene.camera;
            let (lo, hi) = self.dx_range(scene, camera.width)?;
            let dy = |row: u16| camera.screen_y(row)?.checked_sub(camera.viewpoint.y);
            let (top, bottom) = (dy(0)?, dy(camera.height.checked_sub(1)?)?);
            for term in &self.terms {
                let axis = axis_of(scene, term.index)?.to_array();
                for d in [[lo, top], [lo, bottom], [hi, top], [hi, bottom]] {
                    S::acc_round(S::acc_dot3(axis, [d[0], d[1], self.dz])?)?;
                }
            }
            Some(())
        };
        fits().is_some()
    }

    /// Starts scanline `row` at column `column`.
    pub fn row(&self, scene: &SceneView<'_, S>, row: u16, column: u16) -> Option<Row<S>> {
        let mut r = Row {
            nd: Vec::new(),
            acc: Vec::new(),
            yz: S::acc_mul(S::ZERO, S::ZERO)?,
            dir: Vec3::new(S::ZERO, S::ZERO, S::ZERO),
            column,
            // No row yet (rows are below `u16::MAX`): `restart` forms its `D.y`.
            row: u16::MAX,
            eps_l1: S::ZERO,
            dx_limit: S::ZERO,
        };
        self.restart(scene, row, column, &mut r)?;
        Some(r)
    }

    /// [`Primary::row`] into an existing row (in place: a row is hundreds of bytes, and
    /// a scanline restarts every [`resync_pixels`]). On `None` the row is unusable.
    pub(crate) fn restart(
        &self,
        scene: &SceneView<'_, S>,
        row: u16,
        column: u16,
        r: &mut Row<S>,
    ) -> Option<()> {
        // The same scanline with every term in place: its still terms stay as they are
        // (bit for bit what they would be recomputed to: `0·D.x` adds nothing). Otherwise
        // the terms are cleared first, so that a restart that fails leaves fewer of them
        // (and the next one recomputes them all); a kept restart that fails has left the
        // still terms as they were.
        let keep = r.row == row && r.nd.len() == self.terms.len();
        if !keep {
            r.nd.clear();
            r.acc.clear();
        }
        // The same scanline keeps its `D.y` (`restart_dir_in_row` sets `D` and the row
        // together): no division for it.
        if r.row == row {
            self.restart_dir_in_row(scene, row, r.dir.y, column, r)?;
        } else {
            self.restart_dir(scene, row, column, r)?;
        }
        if self.spheres && !keep {
            r.yz = S::acc_add(S::acc_mul(r.dir.y, r.dir.y)?, S::acc_mul(r.dir.z, r.dir.z)?)?;
        }
        self.terms_at(scene, r, keep)
    }

    /// The part of [`Primary::restart`] that is not the terms: `D` from the exact screen
    /// point, the column and row, the epsilon bound. A scanline whose terms are not
    /// needed at this pixel (`kernel/rows.rs`, outside the spheres' columns) restarts
    /// with this alone and brings its terms up to date with [`Primary::refresh`] where
    /// it needs them.
    pub(crate) fn restart_dir(
        &self,
        scene: &SceneView<'_, S>,
        row: u16,
        column: u16,
        r: &mut Row<S>,
    ) -> Option<()> {
        let dy = scene
            .camera
            .screen_y(row)?
            .checked_sub(scene.camera.viewpoint.y)?;
        self.restart_dir_in_row(scene, row, dy, column, r)
    }

    /// [`Primary::restart_dir`] with the row's `D.y` (`screen_y(row) − eye.y`, the same at
    /// every pixel of the row) given: a scanline that keeps it restarts without its
    /// division (`kernel/rows.rs`, every [`resync_pixels`]).
    #[inline]
    pub(crate) fn restart_dir_in_row(
        &self,
        scene: &SceneView<'_, S>,
        row: u16,
        dy: S,
        column: u16,
        r: &mut Row<S>,
    ) -> Option<()> {
        let eye = scene.camera.viewpoint;
        let unit = (self.x_unit > S::ZERO).then_some(self.x_unit);
        let x = scene.camera.screen_x_in(unit, column)?;
        r.dir = Vec3::new(x.checked_sub(eye.x)?, dy, self.dz);
        r.column = column;
        r.row = row;
        // The epsilon bound for this pixel and the next `resync_pixels` (|D.x| grows by at
        // most a step each; a larger bound only sends more planes to the exact test).
        let limit = self.resync_span.and_then(|m| m.checked_add(r.dir.x.abs()));
        let bound = limit.and_then(|m| Some((m, eps_l1_of(scene.epsilon, m, r.dir.y, r.dir.z)?)));
        (r.dx_limit, r.eps_l1) = bound.unwrap_or((S::ONE.checked_neg()?, S::ZERO));
        Some(())
    }

    /// Every term's `N·D` (and its unrounded sum) for the row's current `D`, the still
    /// ones only when not `keep`.
    fn terms_at(&self, scene: &SceneView<'_, S>, r: &mut Row<S>, keep: bool) -> Option<()> {
        for (i, term) in self.terms.iter().enumerate() {
            let still = self.still & (1 << i) != 0;
            if keep && still {
                continue;
            }
            let sum = S::acc_dot3(axis_of(scene, term.index)?.to_array(), r.dir.to_array())?;
            let nd = S::acc_round(sum)?;
            match (r.nd.get_mut(i), r.acc.get_mut(i)) {
                (Some(n), Some(a)) if keep => (*n, *a) = (nd, sum),
                _ => {
                    r.nd.push(nd).ok()?;
                    r.acc.push(sum).ok()?;
                }
            }
        }
        Some(())
    }

    /// Brings a scanline's terms up to date with its `D` after [`Primary::advance_dir`]
    /// or [`Primary::restart_dir`]: in the formats whose products are exact
    /// (`KernelArith::EXACT_PRODUCTS`) bit for bit what [`Primary::advance`] would have stepped
    /// them to (both are the exact `N·D` of the same `D`). `None` where a term does not
    /// fit, or the row does not hold every term (it must be restarted whole).
    pub(crate) fn refresh(&self, scene: &SceneView<'_, S>, r: &mut Row<S>) -> Option<()> {
        if r.nd.len() != self.terms.len() {
            return None;
        }
        self.terms_at(scene, r, true)
    }

    /// Every pixel's `D.z` (`−eye.z`: the screen is the plane `z = 0`).
    #[inline(always)]
    pub(crate) fn dz(&self) -> S {
        self.dz
    }

    /// The `D.x` [`Primary::advance_dir`] would step the row to, without stepping it.
    #[inline(always)]
    pub(crate) fn next_dx(&self, row: &Row<S>) -> Option<S> {
        row.dir.x.checked_add(self.step_x)
    }

    /// [`Primary::advance`] `m` times in one go, bit for bit in the fixed formats: `D.x`
    /// and the unrounded terms move by `m` steps, the terms are rounded once at the end
    /// (`None` where a step does not fit).
    fn advance_by(&self, row: &mut Row<S>, m: u16) -> Option<()> {
        // `m` steps as `m·step` (`D.x`) and as the sum of `step`'s doublings picked by
        // `m`'s bits (the terms): the same integers in the fixed formats, whose sums are
        // exact, where the blocks are drawn (`blocks_for`). A product or a doubling that
        // does not fit says `None`: the block is then not certified.
        row.dir.x = row
            .dir
            .x
            .checked_add(self.step_x.checked_mul_int(i32::from(m))?)?;
        let terms = row.nd.iter_mut().zip(row.acc.iter_mut()).zip(&self.steps);
        for (i, ((nd, acc), step)) in terms.enumerate() {
            if self.still & (1 << i) == 0 {
                let (mut a, mut power, mut bits) = (*acc, *step, m);
                while bits != 0 {
                    if bits & 1 != 0 {
                        a = S::acc_add(a, power)?;
                    }
                    bits >>= 1;
                    if bits != 0 {
                        power = S::acc_add(power, power)?;
                    }
                }
                *acc = a;
                *nd = S::acc_round(a)?;
            }
        }
        row.column = row.column.checked_add(m)?;
        Some(())
    }

    /// Whether a scanline may step one term alone and bring the others up to date later
    /// ([`Primary::advance_one`], [`Primary::refresh`], bit for bit): the format's sums
    /// and products are exact, and every term fits throughout the frame (so that the
    /// refresh cannot fail where the steps would not have).
    #[inline(always)]
    pub(crate) fn steps_freely(&self) -> bool {
        S::EXACT_SUMS && S::EXACT_PRODUCTS && self.fits
    }

    /// [`Primary::advance`] of `D.x` and the term of object `index` alone (the others are
    /// then stale until [`Primary::refresh`]): for a pixel of a certified block, whose
    /// hit needs only its plane's `N·D`.
    #[inline(always)]
    pub(crate) fn advance_one(&self, row: &mut Row<S>, index: usize) -> Option<()> {
        row.dir.x = row.dir.x.checked_add(self.step_x)?;
        if self.still & 1u8.checked_shl(u32::try_from(index).ok()?)? == 0 {
            let (acc, nd) = (row.acc.get_mut(index)?, row.nd.get_mut(index)?);
            let step = *self.steps.get(index)?;
            if S::EXACT_SUMS && self.fits {
                (*acc, *nd) = S::acc_step_fitting(*acc, step);
            } else {
                *acc = S::acc_add(*acc, step)?;
                *nd = S::acc_round(*acc)?;
            }
        }
        row.column = row.column.checked_add(1)?;
        Some(())
    }

    /// [`Primary::advance`] without the terms: `D.x` and the column only (the terms are
    /// then stale until [`Primary::refresh`]).
    pub(crate) fn advance_dir(&self, row: &mut Row<S>) -> Option<()> {
        row.dir.x = row.dir.x.checked_add(self.step_x)?;
        row.column = row.column.checked_add(1)?;
        Some(())
    }

    /// Whether every term of scanline `first` (started at column 0, holding every term)
    /// fits the format at every `D.x` its pixels can take (the first and last column's,
    /// widened by the drift of the stepped coordinate): a term is linear in `D.x`, so it
    /// fits between two values that fit. Then a pixel whose terms are skipped
    /// ([`Primary::advance_dir`]) is one where [`Primary::advance`] would not have failed.
    pub(crate) fn terms_fit_row(
        &self,
        scene: &SceneView<'_, S>,
        first: &Row<S>,
        width: u16,
    ) -> bool {
        let fits = || -> Option<()> {
            if first.nd.len() != self.terms.len() {
                return None;
            }
            let (lo, hi) = self.dx_range(scene, width)?;
            for x in [lo, hi] {
                let d = Vec3::new(x, first.dir.y, first.dir.z);
                for (i, term) in self.terms.iter().enumerate() {
                    if self.still & (1 << i) == 0 {
                        let axis = axis_of(scene, term.index)?;
                        S::acc_round(S::acc_dot3(axis.to_array(), d.to_array())?)?;
                    }
                }
            }
            Some(())
        };
        fits().is_some()
    }

    /// The least and greatest `D.x` a scanline can take at its `width` pixels: the first
    /// and last column's (`screen_x − eye.x`, as a restart forms them), widened by the
    /// drift of the stepped coordinate (`resync_pixels·|step_x|`). `None` when that does
    /// not fit.
    pub(crate) fn dx_range(&self, scene: &SceneView<'_, S>, width: u16) -> Option<(S, S)> {
        let camera = &scene.camera;
        let dx = |column: u16| camera.screen_x(column)?.checked_sub(camera.viewpoint.x);
        let (first, last) = (dx(0)?, dx(width.checked_sub(1)?)?);
        let span = self.resync_span?;
        let (lo, hi) = if first <= last {
            (first, last)
        } else {
            (last, first)
        };
        Some((lo.checked_sub(span)?, hi.checked_add(span)?))
    }

    /// The column the row is at.
    pub fn column(row: &Row<S>) -> u16 {
        row.column
    }

    /// The row's current unnormalised direction `D`.
    pub(crate) fn dir(row: &Row<S>) -> Vec3<S> {
        row.dir
    }

    /// The scanline a row is on.
    #[inline(always)]
    pub(crate) fn row_index(row: &Row<S>) -> u16 {
        row.row
    }

    /// The row's `N·D` of object `index` at its current pixel (its term's position is
    /// its index: every object is a term).
    #[inline(always)]
    pub(crate) fn nd(row: &Row<S>, index: usize) -> Option<S> {
        row.nd.get(index).copied()
    }

    /// Moves a scanline to its next pixel: `D.x` grows by the pixel step (rounded once
    /// per frame; callers restart the row from the exact screen x every
    /// [`resync_pixels`] pixels, so the drift stays below half as many DELTAs), and
    /// `N·D` grows by the unrounded `N.x × step` (`KernelArith::Acc`): in the fixed formats
    /// bit for bit the wide dot product of the new `D` (consistent with `D`, so the hit
    /// point lies on the ray through that screen point), with no product per pixel.
    pub fn advance(&self, row: &mut Row<S>) -> Option<()> {
        row.dir.x = row.dir.x.checked_add(self.step_x)?;
        let terms = row.nd.iter_mut().zip(row.acc.iter_mut()).zip(&self.steps);
        for (i, ((nd, acc), step)) in terms.enumerate() {
            // A still term's step is zero: it stays as it is.
            if self.still & (1 << i) == 0 {
                if S::EXACT_SUMS && self.fits {
                    // Within the frame's checked range (`frame_fits`), in a format whose
                    // sums are exact: no test.
                    (*acc, *nd) = S::acc_step_fitting(*acc, *step);
                } else {
                    *acc = S::acc_add(*acc, *step)?;
                    *nd = S::acc_round(*acc)?;
                }
            }
        }
        row.column = row.column.checked_add(1)?;
        Some(())
    }

    /// The nearest accepted plane at the row's current pixel: `Ok(None)` for the
    /// background, `Err(())` when the reference path must decide (the winner does not fit
    /// the format).
    #[allow(clippy::result_unit_err)]
    pub fn nearest(
        &self,
        scene: &SceneView<'_, S>,
        row: &Row<S>,
    ) -> Result<Option<FastHit<S>>, ()> {
        self.nearest_with(scene, row, None)
    }

    /// [`Primary::nearest`] with a scanline's [`HitMemo`] (the same answer).
    #[allow(clippy::result_unit_err)]
    #[inline(always)]
    pub(crate) fn nearest_with(
        &self,
        scene: &SceneView<'_, S>,
        row: &Row<S>,
        memo: Option<&mut HitMemo<S>>,
    ) -> Result<Option<FastHit<S>>, ()> {
        let mut memo = memo;
        if let Some(m) = memo.as_deref_mut() {
            m.certified = false;
        }
        match self.search(scene, row)? {
            Some((term, p, q)) => self.hit(scene, row, term, p, q, memo).map(Some).ok_or(()),
            None => Ok(None),
        }
    }

    /// [`Primary::nearest`]'s search: the winning term and its `t' = p/q`, without the
    /// hit point.
    // Out of line where the blocks use it too (`blocks_for`: one copy, on the Cortex-M0
    // whose flash is short; the call is cheap beside the search); elsewhere inlined into
    // `nearest`, its one caller.
    #[cfg_attr(any(no_long_multiply, not(target_os = "none")), inline(never))]
    #[cfg_attr(not(any(no_long_multiply, not(target_os = "none"))), inline(always))]
    #[allow(clippy::type_complexity)]
    fn search(
        &self,
        scene: &SceneView<'_, S>,
        row: &Row<S>,
    ) -> Result<Option<(&Term<S>, S, S)>, ()> {
        let eps = scene.epsilon;
        let d = row.dir;
        let eps_d2 = || d.dot(d).and_then(|d2| eps.checked_mul(d2));
        let eps_l1 = if d.x.abs() <= row.dx_limit {
            Some(row.eps_l1)
        } else {
            eps_l1_of(eps, d.x.abs(), d.y, d.z)
        };
        // `D·D`, for spheres: `D.x²` added to the row's `D.y² + D.z²` (once, when a
        // sphere on this row asks for it).
        let mut dd = None;
        let mut dd = || -> Result<S, ()> {
            if let Some(v) = dd {
                return Ok(v);
            }
            let v = S::acc_round(S::acc_add(row.yz, S::acc_mul(d.x, d.x).ok_or(())?).ok_or(())?)
                .ok_or(())?;
            dd = Some(v);
            Ok(v)
        };
        // The best so far: (term, its t' as the fraction p/q with q > 0).
        let mut best: Option<(&Term<S>, S, S)> = None;
        for (term, &nd) in self.terms.iter().zip(&row.nd) {
            let (p, q) = if term.sphere {
                if row.row < term.rows.0
                    || row.row > term.rows.1
                    || row.column < term.columns.0
                    || row.column > term.columns.1
                {
                    // The row's or the column's plane of rays passes far from the
                    // sphere: `sphere_rows`, `sphere_columns`.
                    continue;
                }
                match sphere_root(term.num, nd, dd()?)? {
                    Some(pq) => pq,
                    None => continue,
                }
            } else {
                if !accepts_bounded(term.num, nd, eps, eps_l1, eps_d2).ok_or(())? {
                    continue;
                }
                (term.num.abs(), nd.abs())
            };
            if let Some((_, b_p, b_q)) = best
                && S::cmp_products(p, b_q, b_p, q) != Some(Ordering::Less)
            {
                continue;
            }
            if let Some(shape @ (Shape::Finite(_) | Shape::Textured(_) | Shape::Triangle(_))) =
                scene.objects.get(usize::from(term.index)).map(|o| &o.shape)
            {
                let (point, _, _) = self.point(scene, p, q, d).ok_or(())?;
                if !shape.bounds_contain(point) {
                    continue;
                }
            }
            best = Some((term, p, q));
        }
        Ok(best)
    }

    /// The nearest plane of scanline `row` when every plane's `N·D` is the same at each
    /// of its pixels (`N.x = 0`: the row's `N·D` steps by `N.x × step = 0`) and every
    /// plane's test decides the same at each of them: `Some((object, p, q))` with the
    /// winner's `t' = p/q`, `Some` of `None` when no plane is accepted, and `None` when the
    /// row cannot be decided once (a plane with `N.x ≠ 0`, or one within the margin of the
    /// epsilon at some pixel of the row, `N·D = 0` included: [`nearest`](Self::nearest)
    /// then decides each pixel). `first` is the row started at column 0, `width` its
    /// pixels. Spheres are left out: the caller tests them inside their screen boxes
    /// ([`Self::sphere_columns_on_row`]). The same tests and the same tie rule as
    /// `nearest`, so that a pixel's plane is `nearest`'s (`kernel/rows.rs`).
    pub(crate) fn level_row(
        &self,
        scene: &SceneView<'_, S>,
        first: &Row<S>,
        width: u16,
    ) -> Option<Option<(usize, S, S)>> {
        let eps = scene.epsilon;
        let eye_x = scene.camera.viewpoint.x;
        // The largest |D.x| of the row, with the drift of the stepped coordinate.
        let last = scene
            .camera
            .screen_x(width.checked_sub(1)?)?
            .checked_sub(eye_x)?;
        let widest = first.dir.x.abs().max(last.abs());
        let widest = self.resync_span.and_then(|m| m.checked_add(widest))?;
        let bound = eps_l1_of(eps, widest, first.dir.y, first.dir.z)?;
        let mut best: Option<(&Term<S>, S, S)> = None;
        for (term, &nd) in self.terms.iter().zip(&first.nd) {
            if term.sphere {
                continue;
            }
            if axis_of(scene, term.index)?.x != S::ZERO {
                return None;
            }
            // Accepted at every pixel, or at none (`N·D = 0`); otherwise each pixel decides.
            // (`N·D = 0` too: a pixel rejects it only after forming `ε·|D|²`, which may
            // not fit and hand the pixel to the reference path.)
            if nd.abs() < bound {
                return None;
            }
            if !ahead(term.num, nd) {
                continue;
            }
            let (p, q) = (term.num.abs(), nd.abs());
            if let Some((_, b_p, b_q)) = best
                && S::cmp_products(p, b_q, b_p, q) != Some(Ordering::Less)
            {
                continue;
            }
            if !matches!(
                scene.objects.get(usize::from(term.index)).map(|o| &o.shape),
                Some(Shape::Plane(_) | Shape::Tiled { .. })
            ) {
                return None;
            }
            best = Some((term, p, q));
        }
        Some(best.map(|(term, p, q)| (usize::from(term.index), p, q)))
    }

    /// The columns of scanline `row` where a sphere can be met (the union of the boxes
    /// of [`sphere_rows`] and [`sphere_columns`] of the spheres on the row; `(1, 0)`:
    /// none).
    pub(crate) fn sphere_columns_on_row(&self, row: u16) -> (u16, u16) {
        self.terms
            .iter()
            .filter(|t| t.sphere && row >= t.rows.0 && row <= t.rows.1)
            .filter(|t| t.columns.0 <= t.columns.1)
            .fold((1, 0), |(a, b), t| {
                if a > b {
                    t.columns
                } else {
                    (a.min(t.columns.0), b.max(t.columns.1))
                }
            })
    }

    /// The lights' sides of every plane, per frame (empty when not kept).
    pub(crate) fn at_lights(&self) -> &[S] {
        &self.at_lights
    }

    /// The spheres' shadow cones, per frame.
    pub(crate) fn cones(&self) -> &[ShadowCone<S>] {
        &self.cones
    }

    /// `D'_i − N_i·P` of every plane at the hit `P = eye + t'·D` of the row's current
    /// pixel: `num_i − t'·(N_i·D)`, one product each. `None` when one does not fit (the
    /// shadow segments then compute them). Written into `sides` (a buffer the scanline
    /// keeps: a returned one would be copied whole, capacity and all, per pixel); returned:
    /// which sides are positive and which objects are spheres, as bits
    /// ([`SideBits`]).
    pub(crate) fn sides_at(
        &self,
        row: &Row<S>,
        param: S,
        sides: &mut Vec<S, FAST_OBJECTS>,
    ) -> Option<SideBits> {
        self.sides_but(row, param, usize::MAX, sides)
    }

    /// [`Primary::sides_at`] but for object `own` (the hit's own plane), whose side is
    /// left zero without its product (and its bit clear) where it fits for certain
    /// (`|num| < MAX/2`: `t'·(N·D)` lies within a few DELTAs of `num`, so that
    /// `sides_at` would not have failed on it): for a caller that leaves the hit's own
    /// plane out of its shadow tests (`reference::lit_plane_color`).
    #[inline(always)]
    pub(crate) fn sides_but(
        &self,
        row: &Row<S>,
        param: S,
        own: usize,
        sides: &mut Vec<S, FAST_OBJECTS>,
    ) -> Option<SideBits> {
        sides.clear();
        let mut positive = 0u8;
        for (i, (term, &nd)) in self.terms.iter().zip(&row.nd).enumerate() {
            let side = if term.sphere {
                // Not read for a sphere (see `Primary::new`).
                S::ZERO
            } else if i == own && S::MAX.checked_sub(term.num.abs())? > term.num.abs() {
                S::ZERO
            } else {
                term.num.checked_sub(param.checked_mul(nd)?)?
            };
            if side > S::ZERO {
                positive |= 1 << i;
            }
            sides.push(side).ok()?;
        }
        Some(SideBits {
            positive,
            spheres: self.sphere_bits,
            lights: self.light_positive,
        })
    }

    /// The planes that no shadow segment from a plane hit on this scanline can be
    /// stopped by (`Quiet::loud`: the others, as bits), and the largest `t'` for which that holds
    /// (`Quiet::t_max`), where the row's pixels keep every plane out of the epsilon's
    /// margin ([`Primary::clear_of_margin`]); `Quiet::default()` (none) where the frame
    /// has another object than plain and tiled planes, or a quantity does not fit.
    ///
    /// A plane is quiet when the eye and every light lie strictly on one side of it and
    /// so do the screen points of the row's rays (its two ends, the stepped drift
    /// included, by at least 2 DELTAs: `num − N·D` is affine in `D`). Then a ray of the
    /// row does not cross the plane between the eye and the screen; beyond the screen it
    /// would cross it only as an accepted plane (out of the margin the search accepts by
    /// `ahead` alone), at or beyond the hit, the nearest. So the plane's exact side at
    /// the hit (`numᵢ − t'·(N·D)ᵢ` with the hit's exact `t'`) has the eye's sign, the
    /// lights'; the formed one (`sides_at`'s) lies within `(|N·D|ᵢ + 1)·DELTA` of it
    /// (an exact quotient, `KernelArith::EXACT_QUOTIENTS`), inside the segments' tolerance;
    /// so `sides_differ` passes the plane over towards every light, as it does the hit's
    /// own plane (`reference::lit_plane_color`). `t_max`: up to it, `t'·(N·D)ᵢ` and the
    /// side fit the format (`sides_at` would not have failed): `|numᵢ| ≤ MAX/4` and
    /// `t'·|N·D|ᵢ ≤ MAX/4`.
    pub(crate) fn quiet_planes(&self, scene: &SceneView<'_, S>, row: &Row<S>) -> Quiet<S> {
        let quiet = || -> Option<Quiet<S>> {
            let quarter = S::MAX.mul_ratio(1, 4)?;
            let margin = S::DELTA.checked_mul_int(2)?;
            let (lo, hi) = self.dx_range(scene, scene.camera.width)?;
            let mut planes = 0u8;
            let mut widest = S::DELTA;
            for (i, term) in self.terms.iter().enumerate() {
                let object = scene.objects.get(usize::from(term.index))?;
                if !matches!(object.shape, Shape::Plane(_) | Shape::Tiled { .. }) {
                    return None;
                }
                let num = term.num;
                if num == S::ZERO || num.abs() > quarter {
                    continue;
                }
                let plane = object.shape.plane()?;
                let n = plane.normal().to_array();
                let lights_aside = scene.lights.iter().all(|l| {
                    S::sub_dot3(plane.offset(), n, l.location.to_array())
                        .is_some_and(|a| a != S::ZERO && (a > S::ZERO) == (num > S::ZERO))
                });
                let mut screen_aside = true;
                for dx in [lo, hi] {
                    let d = [dx, row.dir.y, self.dz];
                    match S::sub_dot3(num, n, d) {
                        Some(v) if (v > S::ZERO) == (num > S::ZERO) && v.abs() >= margin => {
                            // |N·D| at this end: |num − v|.
                            widest = widest.max(num.checked_sub(v)?.abs());
                        }
                        _ => screen_aside = false,
                    }
                }
                if lights_aside && screen_aside {
                    planes |= 1 << i;
                }
            }
            // Every object is a term (at most eight: `FAST_OBJECTS`).
            let all = u8::MAX.checked_shr(u32::try_from(8 - self.terms.len()).ok()?)?;
            Some(Quiet {
                loud: all & !planes,
                t_max: quarter.checked_div(widest)?,
            })
        };
        quiet().unwrap_or_default()
    }

    /// Whether every plane but `own` lies out of the epsilon's margin at the row's
    /// current pixel (`|N·D| ≥` the bound by which the search accepts it by `ahead`
    /// alone, the row's, where it holds).
    #[inline(always)]
    pub(crate) fn clear_of_margin(row: &Row<S>, own: usize) -> bool {
        if row.dir.x.abs() > row.dx_limit {
            return false;
        }
        row.nd
            .iter()
            .enumerate()
            .all(|(i, nd)| i == own || nd.abs() >= row.eps_l1)
    }

    /// The row's current pixel (a resync column, just restarted) and the pixels after it
    /// up to `last` and the next restart ([`resync_pixels`]), if [`Primary::nearest`] answers
    /// `winner` (an object's index, `None`: the background) at every one of them: that
    /// block (the column after it, and the term that wins throughout or [`NO_TERM`]).
    /// `None` where that is not certain. `winner` may be a guess (the last pixel's): the
    /// checks below are `nearest`'s own tests at both ends, so a block is certified only
    /// where it is that pixel's answer too.
    ///
    /// Why it holds: inside the block `D.x` steps by a constant, so every plane's unrounded
    /// `N·D` is linear in the column and its rounded `N·D` monotone. The block's last
    /// pixel is formed as the scanline would step to it (`advance_by`: the same steps, the
    /// terms rounded once at the end). Every plane must keep one side of zero and stay
    /// at least the epsilon bound away from it at both ends (so that no pixel between
    /// takes the exact parallel test, and its acceptance, monotone, is the same
    /// throughout). The winner must beat every other accepted plane at both ends by a
    /// margin that the roundings of `N·D` cannot eat (`KernelArith::products_clearly_greater`:
    /// the comparison with unrounded terms is linear, so it holds between the ends too).
    #[inline(never)]
    fn certify_block(&self, a: &Row<S>, winner: Option<usize>, last: u16) -> Option<Block> {
        // Up to the scanline's next restart (the stepped terms hold until then).
        let m = last
            .checked_sub(a.column)?
            .min(resync_pixels::<S>() - 1 - a.column % resync_pixels::<S>());
        if m == 0 || a.nd.len() != self.terms.len() {
            return None;
        }
        let mut e = a.clone();
        self.advance_by(&mut e, m)?;
        // No search at the block's end: the checks below are its tests there (every
        // plane beyond the epsilon bound, so accepted by `ahead` alone; the winner
        // accepted; every other accepted plane clearly farther, so that neither order
        // of the tie rule lets it win), so they imply its answer.
        // Both ends (and so every pixel between: |D.x| is largest at an end) take the
        // row's epsilon bound.
        let bound = a.eps_l1;
        if a.dx_limit < a.dir.x.abs() || a.dx_limit < e.dir.x.abs() {
            return None;
        }
        // A term's position is its object's index (every object is a term). The winner
        // must be accepted (at the start; the loop below makes both ends agree): a guess
        // may name a plane behind the eye, whose `|t'|` would win the comparisons.
        let w = match winner {
            Some(i) => {
                let (num, na) = (self.terms.get(i)?.num, *a.nd.get(i)?);
                if !ahead(num, na) {
                    return None;
                }
                Some((i, num.abs(), na, *e.nd.get(i)?))
            }
            None => None,
        };
        for (k, (term, (&na, &ne))) in self.terms.iter().zip(a.nd.iter().zip(&e.nd)).enumerate() {
            // (Not zero either: a caller may give the view a negative epsilon.)
            if na.abs() < bound
                || ne.abs() < bound
                || na == S::ZERO
                || ne == S::ZERO
                || (na > S::ZERO) != (ne > S::ZERO)
            {
                return None;
            }
            let accepted = ahead(term.num, na);
            if accepted != ahead(term.num, ne) {
                return None;
            }
            match w {
                Some((i, pw, wa, we)) if accepted && k != i => {
                    let pb = term.num.abs();
                    let clear = S::products_clearly_greater(pb, wa.abs(), pw, na.abs())
                        && S::products_clearly_greater(pb, we.abs(), pw, ne.abs());
                    if !clear {
                        return None;
                    }
                }
                // The background at both ends, yet a plane accepted: cannot be.
                None if accepted => return None,
                _ => {}
            }
        }
        Some(Block {
            stop: e.column.checked_add(1)?,
            winner: match winner {
                Some(k) => u8::try_from(k).ok()?,
                None => NO_TERM,
            },
        })
    }

    /// The pixels of a scanline from a resync column (just restarted there) as a
    /// certified block of `winner` ([`Primary::certify_block`]) into `block` where they
    /// can be one (else an empty block); `last`: the scanline's last column. Inside the
    /// block [`Primary::block_hit`] answers for [`Primary::nearest`].
    #[inline(never)]
    pub(crate) fn start_block(
        &self,
        row: &Row<S>,
        winner: Option<usize>,
        last: u16,
        block: &mut Block,
    ) {
        *block = if self.blocks {
            self.certify_block(row, winner, last).unwrap_or_default()
        } else {
            Block::default()
        };
    }

    /// The frame without certified blocks: every pixel searched (the tests' oracle).
    #[cfg(test)]
    pub(crate) fn without_blocks(mut self) -> Self {
        self.blocks = false;
        self
    }

    /// [`Primary::nearest`]'s answer at a pixel of the certified block `block`, bit for bit
    /// (`None`: the pixel is not in the block). Reset `block` at every restart of the
    /// scanline: a block holds for the pixels stepped from its start.
    #[inline(always)]
    pub(crate) fn block_hit(
        &self,
        scene: &SceneView<'_, S>,
        row: &Row<S>,
        block: &Block,
        memo: Option<&mut HitMemo<S>>,
    ) -> Option<Result<Option<FastHit<S>>, ()>> {
        if row.column >= block.stop {
            return None;
        }
        let mut memo = memo;
        if let Some(m) = memo.as_deref_mut() {
            m.certified = true;
        }
        Some(match block.winner {
            NO_TERM => Ok(None),
            // A plane's `t'` as `search` forms it: `|num| / |N·D|`.
            k => {
                let k = usize::from(k);
                match (self.terms.get(k), row.nd.get(k)) {
                    (Some(term), Some(nd)) => self
                        .hit(scene, row, term, term.num.abs(), nd.abs(), memo)
                        .map(Some)
                        .ok_or(()),
                    _ => Err(()),
                }
            }
        })
    }

    /// The hit of `term` at the row's current pixel, its `t' = p/q`: the point, its
    /// distance bound and `t'` ([`Primary::nearest`]'s, and a certified block's winner's).
    /// `None` where they do not fit (`nearest` then says `Err`).
    #[inline(always)]
    fn hit(
        &self,
        scene: &SceneView<'_, S>,
        row: &Row<S>,
        term: &Term<S>,
        p: S,
        q: S,
        memo: Option<&mut HitMemo<S>>,
    ) -> Option<FastHit<S>> {
        let d = row.dir;
        let still = self.still & 1u8.checked_shl(u32::from(term.index)).unwrap_or(0) != 0;
        let (point, t_bound, param) = match memo {
            Some(m) if still => self.point_in(scene, term.index, p, q, d, m)?,
            _ => self.point(scene, p, q, d)?,
        };
        Some(FastHit {
            index: usize::from(term.index),
            point,
            t_bound,
            dir: d,
            param,
        })
    }

    /// [`Primary::point`] for a still term (`N.x = 0`, object `index`), with a scanline's
    /// memo of the last one: the same operations, bit for bit, where the memo holds
    /// this term's `t' = p/q` for this `q` and `D.y` (along a scanline a still plane's
    /// `N·D` does not change, a back wall's nowhere in the frame): its `t'` and the
    /// hit's `y` and `z` are kept, and the distance bound for the last `2|D|∞`; a pixel
    /// forms its hit's `x` alone.
    #[inline(never)]
    fn point_in(
        &self,
        scene: &SceneView<'_, S>,
        index: u8,
        p: S,
        q: S,
        d: Vec3<S>,
        memo: &mut HitMemo<S>,
    ) -> Option<(Vec3<S>, S, S)> {
        let eye = scene.camera.viewpoint;
        if memo.key != Some((index, q, d.y)) {
            memo.key = None;
            let t = p.checked_div(q)?;
            memo.y = eye.y.checked_add(t.checked_mul(d.y)?)?;
            memo.z = eye.z.checked_add(t.checked_mul(d.z)?)?;
            memo.t = t;
            memo.bound = None;
            memo.key = Some((index, q, d.y));
        }
        let t = memo.t;
        let x = eye.x.checked_add(t.checked_mul(d.x)?)?;
        let twice = d.max_abs().checked_add(d.max_abs())?;
        let t_bound = match memo.bound {
            Some((k, b)) if k == twice => b,
            _ => {
                let b = t.checked_mul(twice)?;
                memo.bound = Some((twice, b));
                b
            }
        };
        Some((Vec3::new(x, memo.y, memo.z), t_bound, t))
    }

    /// The hit point `eye + t'·D` of a term, a bound on its world distance, and `t'`.
    fn point(&self, scene: &SceneView<'_, S>, p: S, q: S, d: Vec3<S>) -> Option<(Vec3<S>, S, S)> {
        let t = p.checked_div(q)?;
        let point = scene.camera.viewpoint.sum(d.scale(t)?)?;
        // |D| ≤ √3 |D|∞ < 2 |D|∞: the world distance t'·|D| is below t'·2|D|∞.
        let t_bound = t.checked_mul(d.max_abs().checked_add(d.max_abs())?)?;
        Some((point, t_bound, t))
    }
}
