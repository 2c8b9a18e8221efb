//! Seeded random rays and planes, checked against f64: the property tests
//! (`tests/properties.rs`) assert on these statistics and `cargo xtask numerics` writes
//! them into `docs/numerics.md`. Part of the test-support module, shared with `xtask`.

use fixray::Scalar;
use fixray::geometry::{Hit, Miss, Plane, Ray, RayKind, Vec3};

/// SplitMix64: small, fast, and the same sequence on every machine.
pub struct SplitMix(pub u64);

impl SplitMix {
    pub fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in 0..n (n > 0).
    pub fn below(&mut self, n: usize) -> usize {
        usize::try_from(self.next() % u64::try_from(n).unwrap_or(u64::MAX)).unwrap_or(0)
    }

    /// Uniform in [lo, hi).
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        let unit = (self.next() >> 11) as f64 / (1u64 << 53) as f64;
        lo + (hi - lo) * unit
    }

    fn vector(&mut self, r: f64) -> [f64; 3] {
        [
            self.uniform(-r, r),
            self.uniform(-r, r),
            self.uniform(-r, r),
        ]
    }

    /// A random unit vector (rejection sampling in the unit ball).
    pub fn unit(&mut self) -> [f64; 3] {
        loop {
            let v = self.vector(1.0);
            let n = dot(v, v).sqrt();
            if n > 0.1 && n <= 1.0 {
                return [v[0] / n, v[1] / n, v[2] / n];
            }
        }
    }
}

pub fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn unit(a: [f64; 3]) -> [f64; 3] {
    let n = dot(a, a).sqrt();
    [a[0] / n, a[1] / n, a[2] / n]
}

/// Coordinates of points and bases are drawn from [−RANGE, RANGE].
pub const RANGE: f64 = 100.0;

/// What a run of random cases measured in one format.
#[derive(Debug, Default, Clone)]
pub struct Stats {
    /// Cases drawn.
    pub cases: u64,
    /// (a) Hits checked against f64 on the same quantised inputs.
    pub same_input_hits: u64,
    /// (a) Largest |Δt| / bound over them, and cases over the bound.
    pub max_bound_ratio: f64,
    pub over_bound: u64,
    /// (a) Largest |Δt| in DELTAs.
    pub max_dt_deltas: f64,
    /// (b) Hit/miss decisions that differ from f64 on the exact inputs: inside the
    /// documented bands (epsilon, range, t ≈ 0) and outside them.
    pub disagree_in_band: u64,
    pub disagree_outside_band: u64,
    /// (c) Secondary rays spawned off a hit, and how many hit the same plane again.
    pub spawned: u64,
    pub rehits: u64,
    /// (c) Largest hit-point residual |N·p − D'| / residual bound.
    pub max_residual_ratio: f64,
    /// The first failing case of (a), (b) and (c), for the message.
    pub first_failure: [Option<String>; 3],
}

/// The documented bound on |Δt| of one plane test on *given* inputs (the stored unit
/// normal, offset and unit direction): the arithmetic alone.
///
/// Fixed formats: `D' − N·b` and `N·d` each round once (wide, ≤ ½ DELTA), the division
/// once (≤ 1 DELTA): `|Δt| ≤ (½ + ½ t) DELTA / (|N·d| − ½ DELTA) + DELTA` (the computed
/// `N·d` in the denominator may be ½ DELTA smaller than the exact one).
/// Floats: each three-term dot product errs by ≤ 3ε × the sum of its term magnitudes, the
/// division by ε t: `|Δt| ≤ (3ε(|D'| + Σ|N_i b_i|) + 3ε t) / (|N·d| − 3ε) + ε t`.
pub fn same_input_bound<S: Scalar>(
    t: f64,
    n_dot_d: f64,
    n: [f64; 3],
    b: [f64; 3],
    d_off: f64,
) -> f64 {
    let delta = S::DELTA.to_f64();
    let float = S::from_i32(1000).is_some_and(|k| k.ulp() != S::DELTA);
    if float {
        let terms = d_off.abs()
            + n[0].abs() * b[0].abs()
            + n[1].abs() * b[1].abs()
            + n[2].abs() * b[2].abs();
        (3.0 * delta * terms + 3.0 * delta * t) / (n_dot_d.abs() - 3.0 * delta) + delta * t.max(1.0)
    } else {
        (0.5 + 0.5 * t) * delta / (n_dot_d.abs() - 0.5 * delta) + delta
    }
}

/// Draws `n` random planes and rays (half of them with |N·d| close to the epsilon) and
/// checks (a) the arithmetic against f64 on the same inputs, (b) the hit/miss decision
/// against f64 on the exact inputs, (c) that a secondary ray spawned off a hit never hits
/// the same plane again.
pub fn run<S: Scalar>(n: u64, seed: u64) -> Stats {
    let mut rng = SplitMix(seed);
    let mut st = Stats::default();
    let eps = S::DEFAULT_EPSILON;
    let eps_f = eps.to_f64();
    let delta = S::DELTA.to_f64();
    let max = S::MAX.to_f64();
    let q = |v: [f64; 3]| Vec3::<S>::from_f64(v);
    for _ in 0..n {
        st.cases += 1;
        let normal = rng.vector(1.0);
        let point = rng.vector(RANGE);
        let base = rng.vector(RANGE);
        let nu = unit(normal);
        // Half the rays graze: N·d within ±50 % of the epsilon, either sign.
        let dir = if rng.next() & 1 == 0 {
            rng.unit()
        } else {
            let a = eps_f * rng.uniform(0.5, 1.5) * if rng.next() & 1 == 0 { 1.0 } else { -1.0 };
            let r = rng.unit();
            let perp = [
                r[0] - dot(r, nu) * nu[0],
                r[1] - dot(r, nu) * nu[1],
                r[2] - dot(r, nu) * nu[2],
            ];
            if dot(perp, perp) < 1e-6 {
                continue;
            }
            let p = unit(perp);
            let s = (1.0 - a * a).sqrt();
            [
                a * nu[0] + s * p[0],
                a * nu[1] + s * p[1],
                a * nu[2] + s * p[2],
            ]
        };
        let (Some(qn), Some(qp), Some(qb), Some(qd)) =
            (q(normal), q(point), q(base), q(dir).and_then(Vec3::unit))
        else {
            continue;
        };
        let Ok(plane) = Plane::new(qn, qp) else {
            continue;
        };
        let ray = Ray {
            base: qb,
            dir: qd,
            kind: RayKind::Secondary,
        };
        let got = plane.intersect(&ray, eps);

        // (a) Same inputs: f64 evaluation of the stored N, D', b, d.
        let (nf, df, bf, off) = (
            plane.normal().to_f64(),
            qd.to_f64(),
            qb.to_f64(),
            plane.offset().to_f64(),
        );
        let nd = dot(nf, df);
        if let Ok(Hit { t, .. }) = got {
            let t_ref = (off - dot(nf, bf)) / nd;
            let bound = same_input_bound::<S>(t_ref.abs(), nd, nf, bf, off);
            let dt = (t.to_f64() - t_ref).abs();
            st.same_input_hits += 1;
            st.max_bound_ratio = st.max_bound_ratio.max(dt / bound);
            st.max_dt_deltas = st.max_dt_deltas.max(dt / delta);
            if dt > bound {
                st.over_bound += 1;
                st.first_failure[0].get_or_insert(format!(
                    "(a) |Δt| {dt:e} > bound {bound:e}: t {t_ref}, N·d {nd}"
                ));
            }
        }

        // (b) Exact inputs: the decision of the same test in f64 on the unquantised values.
        let off_exact = dot(nu, point);
        let nd_exact = dot(nu, dir);
        let t_exact = (off_exact - dot(nu, base)) / nd_exact;
        let exact_hit = nd_exact.abs() >= eps_f && t_exact >= 0.0;
        let hit_fits = exact_hit && {
            let p = [
                base[0] + t_exact * dir[0],
                base[1] + t_exact * dir[1],
                base[2] + t_exact * dir[2],
            ];
            t_exact < max && p.iter().all(|c| c.abs() < max)
        };
        if got.is_ok() != hit_fits {
            // Documented bands where the two may disagree: |N·d| within 16 ulp of the
            // epsilon (quantised inputs move N·d by a few DELTAs); t within its error of
            // 0, where the error of t on exact inputs includes the quantised unit normal
            // (≤ 2 ulp per component) times the distances ‖P‖₁ + ‖b‖₁; and t or the hit
            // point within a factor 2 of the format's range.
            let ulp = S::from_f64(RANGE).map_or(delta, |v| v.ulp().to_f64());
            let l1 = |v: [f64; 3]| v[0].abs() + v[1].abs() + v[2].abs();
            let t_band = (4.0 * (l1(point) + l1(base)) + 64.0 * (1.0 + t_exact.abs())) * ulp
                / nd_exact.abs().max(eps_f);
            let in_band = (nd_exact.abs() - eps_f).abs() <= 16.0 * delta
                || t_exact.abs() <= t_band
                || t_exact.abs() >= max / 2.0
                || matches!(got, Err(Miss::OutOfRange))
                || (0..3).any(|i| (base[i] + t_exact * dir[i]).abs() >= max / 2.0);
            if in_band {
                st.disagree_in_band += 1;
            } else {
                st.disagree_outside_band += 1;
                st.first_failure[1].get_or_insert(format!(
                    "(b) {:?} vs exact hit {hit_fits}: N·d {nd_exact}, t {t_exact}",
                    got
                ));
            }
        }

        // (c) Spawn a secondary ray off the hit in a random direction.
        if let Ok(hit) = got {
            let residual = (dot(nf, hit.point.to_f64()) - off).abs();
            if let Some(bound) = plane.residual_bound(&ray, &hit) {
                st.max_residual_ratio = st.max_residual_ratio.max(residual / bound.to_f64());
            }
            let Some(d2) = q(rng.unit()).and_then(Vec3::unit) else {
                continue;
            };
            if let Some(spawned) = plane.spawn(&ray, &hit, d2) {
                st.spawned += 1;
                if let Ok(again) = plane.intersect(&spawned, S::ZERO) {
                    st.rehits += 1;
                    st.first_failure[2]
                        .get_or_insert(format!("(c) re-hit at t {:?} from {:?}", again.t, hit));
                }
            }
        }
    }
    st
}

/// What [`revsurf_stats`] measured in one format against f64 on the same inputs.
#[derive(Debug, Default, Clone, Copy)]
pub struct RevsurfStats {
    /// Rays cast.
    pub rays: u64,
    /// Rays f64 finds a hit for.
    pub hits: u64,
    /// Hit/miss disagreements where the f64 root is clear of tangency
    /// (`disc ≥ 10⁻² B²`) and of the profile's ends (`s` more than 10⁻³ height inside).
    pub disagree_clear: u64,
    /// Hit/miss disagreements near tangency, the apex or an end.
    pub disagree_near: u64,
    /// Largest `|Δt| / ((1 + t)(1 + |B|/√disc) δ)` over clear hits both found.
    pub max_clear: f64,
    /// Largest `|Δt| / √δ` over the other hits both found (the roots coalesce there).
    pub max_near: f64,
}

/// Seeded random cones (`surfer 1`: random base in ±8, axis, height 1..8) and rays aimed
/// near them (from ±16, towards a point within the cone's bounding ball): the cone test
/// in format `S` against f64 on the same (converted) inputs.
pub fn revsurf_stats<S: Scalar>(n: u64, seed: u64) -> RevsurfStats {
    let mut rng = SplitMix(seed);
    let mut st = RevsurfStats::default();
    let back = |v: Vec3<S>| [v.x.to_f64(), v.y.to_f64(), v.z.to_f64()];
    while st.rays < n {
        let Some((cone, exact)) = random_revsurf::<S>(&mut rng, 1) else {
            continue;
        };
        let (bf, af, hf) = (back(cone.base()), back(cone.axis()), cone.height().to_f64());
        for _ in 0..16 {
            let Some((ray, exact_ray)) =
                aimed_ray::<S>(&mut rng, axis_middle(&cone), 4.0f64.max(hf))
            else {
                continue;
            };
            let (of, df) = (back(ray.base), back(ray.dir));
            st.rays += 1;
            let want = exact.intersect(&exact_ray);
            let got = cone.intersect(&ray);
            // The f64 root's conditioning, recomputed here independently.
            let taper = 4.0 / hf;
            let w0 = [of[0] - bf[0], of[1] - bf[1], of[2] - bf[2]];
            let (s0, sd) = (dot(w0, af), dot(df, af));
            let q0 = [w0[0] - s0 * af[0], w0[1] - s0 * af[1], w0[2] - s0 * af[2]];
            let qd = [df[0] - sd * af[0], df[1] - sd * af[1], df[2] - sd * af[2]];
            let r0 = 4.0 - taper * s0;
            let big_a = dot(qd, qd) - taper * taper * sd * sd;
            let big_b = dot(q0, qd) + taper * sd * r0;
            let big_c = dot(q0, q0) - r0 * r0;
            let disc = big_b * big_b - big_a * big_c;
            let clear_of_ends = |t: f64| {
                let s = s0 + t * sd;
                s > 1e-3 * hf && s < hf * (1.0 - 1e-3)
            };
            let clear = disc >= 1e-2 * big_b * big_b
                && match want {
                    Ok(hit) => clear_of_ends(hit.t),
                    Err(_) => true,
                };
            if want.is_ok() {
                st.hits += 1;
            }
            match (want, got) {
                (Ok(w), Ok(g)) => {
                    let dt = (w.t - g.t.to_f64()).abs();
                    if clear {
                        let cond = 1.0 + big_b.abs() / disc.sqrt();
                        st.max_clear = st
                            .max_clear
                            .max(dt / ((1.0 + w.t) * cond * S::DELTA.to_f64()));
                    } else {
                        st.max_near = st.max_near.max(dt / S::DELTA.to_f64().sqrt());
                    }
                }
                (Ok(_), Err(_)) | (Err(_), Ok(_)) => {
                    if clear {
                        st.disagree_clear += 1;
                    } else {
                        st.disagree_near += 1;
                    }
                }
                _ => {}
            }
        }
    }
    st
}

/// Hit/miss and `t` of the hourglass and the vase (`surfer 2`, `3`) in a format against
/// f64 on the same inputs, and f64's own root search against a dense scan.
#[derive(Debug, Default, Clone, Copy)]
pub struct WaveStats {
    /// Rays cast.
    pub rays: u64,
    /// Rays f64 hits.
    pub hits: u64,
    /// Hit/miss disagreements where the hit (whichever side found it) is clear: the ray
    /// meets the surface at more than 0.1 of a right angle (`|d·n| ≥ 0.1`) and `s` lies
    /// more than 10⁻³ height from an end.
    pub disagree_clear: u64,
    /// Hit/miss disagreements at grazing angles or the ends.
    pub disagree_near: u64,
    /// Largest `|Δt| |d·n| / ((1 + t) δ)` over clear hits both found (first order,
    /// `Δt ≈ ΔF / |F'|` and `|F'| = |∇F| |d·n|`).
    pub max_clear: f64,
    /// Largest `|Δt| / √δ` over the other hits both found.
    pub max_near: f64,
    /// Rays on which a scan of `F` in f64 at 1/1024 steps finds a sign change before
    /// f64's hit (or on a ray f64 misses): slivers the search stepped over.
    pub stepped_over: u64,
}

/// `(F(t), s(t), |d·n|)` of profile `surfer` (2 or 3) in f64: `F = |q|² − r(s)²`, `n` the
/// surface's unit normal.
fn wave_terms(
    surfer: i64,
    (base, axis): ([f64; 3], [f64; 3]),
    (o, d): ([f64; 3], [f64; 3]),
    t: f64,
) -> (f64, f64, f64) {
    let p = [o[0] + d[0] * t, o[1] + d[1] * t, o[2] + d[2] * t];
    let w = [p[0] - base[0], p[1] - base[1], p[2] - base[2]];
    let s = dot(w, axis);
    let q = [w[0] - s * axis[0], w[1] - s * axis[1], w[2] - s * axis[2]];
    let (r, dr) = if surfer == 2 {
        (1.0 + s.cos() / 2.0, -s.sin() / 2.0)
    } else {
        (1.0 + s.sin() / 2.0, s.cos() / 2.0)
    };
    let g = [
        q[0] - r * dr * axis[0],
        q[1] - r * dr * axis[1],
        q[2] - r * dr * axis[2],
    ];
    let gn = dot(g, g).sqrt();
    (dot(q, q) - r * r, s, dot(g, d).abs() / gn)
}

/// Seeded random hourglasses and vases (random base in ±8, axis, height 1..8) and rays
/// aimed near them (from ±16, towards a point within 2 of the axis' middle): the test in
/// format `S` against f64 on the same (converted) inputs.
pub fn wave_stats<S: Scalar>(surfer: i64, n: u64, seed: u64) -> WaveStats {
    let mut rng = SplitMix(seed);
    let mut st = WaveStats::default();
    let back = |v: Vec3<S>| [v.x.to_f64(), v.y.to_f64(), v.z.to_f64()];
    while st.rays < n {
        let Some((shape, exact)) = random_revsurf::<S>(&mut rng, surfer) else {
            continue;
        };
        // The scan's axis: f64's unit axis (a format whose square root is approximate
        // hands back a vector a little off unit length).
        let (bf, hf) = (back(shape.base()), shape.height().to_f64());
        let af = [exact.axis().x, exact.axis().y, exact.axis().z];
        for _ in 0..16 {
            let Some((ray, exact_ray)) = aimed_ray::<S>(&mut rng, axis_middle(&exact), 2.0) else {
                continue;
            };
            let (of, df) = (back(ray.base), back(ray.dir));
            st.rays += 1;
            let want = exact.intersect(&exact_ray);
            let got = shape.intersect(&ray);
            let terms = |t: f64| wave_terms(surfer, (bf, af), (of, df), t);
            let clear_at = |t: f64| {
                let (_, s, c) = terms(t);
                c >= 0.1 && s > 1e-3 * hf && s < hf * (1.0 - 1e-3)
            };
            // The dense scan: a sign change of F between 0 and the hit (or 40 units).
            let end = want.map_or(40.0, |w| w.t);
            // Sign changes of F between samples both between the end planes (an open
            // end is not the surface).
            let steps = (end * 1024.0) as u64;
            let mut last: Option<bool> = None;
            for k in 1..steps.saturating_sub(2) {
                let (f, s, _) = terms(k as f64 / 1024.0);
                if !(0.0..=hf).contains(&s) {
                    last = None;
                    continue;
                }
                if last.is_some_and(|l| l != (f < 0.0)) {
                    st.stepped_over += 1;
                    break;
                }
                last = Some(f < 0.0);
            }
            if want.is_ok() {
                st.hits += 1;
            }
            match (want, got) {
                (Ok(w), Ok(g)) => {
                    let dt = (w.t - g.t.to_f64()).abs();
                    if clear_at(w.t) {
                        let c = terms(w.t).2;
                        let e = dt * c / ((1.0 + w.t) * S::DELTA.to_f64());
                        st.max_clear = st.max_clear.max(e);
                    } else {
                        st.max_near = st.max_near.max(dt / S::DELTA.to_f64().sqrt());
                    }
                }
                (Ok(w), Err(_)) => {
                    if clear_at(w.t) {
                        st.disagree_clear += 1;
                    } else {
                        st.disagree_near += 1;
                    }
                }
                (Err(_), Ok(g)) => {
                    if clear_at(g.t.to_f64()) {
                        st.disagree_clear += 1;
                    } else {
                        st.disagree_near += 1;
                    }
                }
                _ => {}
            }
        }
    }
    st
}

/// A random surface of revolution of profile `surfer` (base within ±8, a random axis,
/// height 1..8) in format `S`, and the same one built in f64 from its values converted
/// back.
fn random_revsurf<S: Scalar>(
    rng: &mut SplitMix,
    surfer: i64,
) -> Option<(fixray::geometry::Revsurf<S>, fixray::geometry::Revsurf<f64>)> {
    let base = rng.vector(8.0);
    let axis = rng.unit();
    let height = rng.uniform(1.0, 8.0);
    let shape = fixray::geometry::Revsurf::new(
        surfer,
        Vec3::<S>::from_f64(base)?,
        Vec3::<S>::from_f64(axis)?,
        S::from_f64(height)?,
    )
    .ok()?;
    let exact = fixray::geometry::Revsurf::<f64>::new(
        surfer,
        to_f64(shape.base()),
        to_f64(shape.axis()),
        shape.height().to_f64(),
    )
    .ok()?;
    Some((shape, exact))
}

/// A vector of format `S` in f64.
fn to_f64<S: Scalar>(v: Vec3<S>) -> Vec3<f64> {
    Vec3::new(v.x.to_f64(), v.y.to_f64(), v.z.to_f64())
}

/// A secondary ray from a random point within ±16 towards `mid` moved by a random offset
/// within `spread`, in format `S`, and the same ray converted back to f64.
fn aimed_ray<S: Scalar>(
    rng: &mut SplitMix,
    mid: [f64; 3],
    spread: f64,
) -> Option<(Ray<S>, Ray<f64>)> {
    let from = rng.vector(16.0);
    let target = rng.vector(spread);
    let dir = unit([
        mid[0] + target[0] - from[0],
        mid[1] + target[1] - from[1],
        mid[2] + target[2] - from[2],
    ]);
    let ray = Ray {
        base: Vec3::<S>::from_f64(from)?,
        dir: Vec3::<S>::from_f64(dir)?,
        kind: RayKind::Secondary,
    };
    let exact = Ray {
        base: to_f64(ray.base),
        dir: to_f64(ray.dir),
        kind: RayKind::Secondary,
    };
    Some((ray, exact))
}

/// The middle of a surface of revolution's axis, in f64.
fn axis_middle<S: Scalar>(shape: &fixray::geometry::Revsurf<S>) -> [f64; 3] {
    let (b, a, h) = (
        to_f64(shape.base()),
        to_f64(shape.axis()),
        shape.height().to_f64(),
    );
    [
        b.x + a.x * h / 2.0,
        b.y + a.y * h / 2.0,
        b.z + a.z * h / 2.0,
    ]
}
