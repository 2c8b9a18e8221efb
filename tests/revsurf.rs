//! The course's surfaces of revolution (`revsurf`: the cone of `surfer 1`; the hourglass
//! and the vase of `surfer 2` and `3` below) against f64 on
//! 200 000 seeded random rays per format (every format of the one list,
//! `fixray::num::formats::FORMATS`): hit and miss agree wherever the f64 root is clear of
//! tangency and of the profile's ends, `|Δt|` stays within the bound `docs/numerics.md`
//! states, and near tangency, the apex and the ends (the hard cases) the root is good to
//! a few `√δ` (the two roots coalesce there) and nothing panics.

mod common;

use common::probes::{dot_rounds_once, sqrt_error, sqrt_is_rounded};
use common::sampling::{revsurf_stats, wave_stats};

use fixray::Scalar;
use fixray::num::formats::FORMATS;

/// The stated bounds (`cargo xtask numerics` prints the measured maxima beside them).
const CLEAR_BOUND: f64 = 256.0; // |Δt| ≤ 256 (1 + t)(1 + |B|/√disc) δ, clear roots
const NEAR_BOUND: f64 = 256.0; // |Δt| ≤ 256 √δ, near tangency, the apex and the ends
/// The hourglass and the vase: `|Δt| |d·n| ≤ 1024 (1 + t) δ` at clear hits, `|Δt| ≤ 256 √δ` elsewhere.
const WAVE_CLEAR_BOUND: f64 = 1024.0;
const WAVE_NEAR_BOUND: f64 = 256.0;

/// The cone in format `S` against f64; whether every bound applied.
fn check<S: Scalar>() -> bool {
    let st = revsurf_stats::<S>(200_000, 0x2E75_2026);
    println!("{}: {st:?} (√ error {:e})", S::NAME, sqrt_error::<S>());
    assert!(
        st.hits > st.rays / 5,
        "{}: the sampler must hit: {st:?}",
        S::NAME
    );
    if !sqrt_is_rounded::<S>() {
        // Its roots are as far off as its square root: shown in `docs/numerics.md`, not
        // bounded here.
        return false;
    }
    // Hit/miss: clear roots agree but for the rounding near the profile's and the
    // silhouette's edges (at most 1 in 10³ rays; I20F12 rounds at 1/4096).
    assert!(st.disagree_clear * 1_000 <= st.rays, "{}: {st:?}", S::NAME);
    assert!(st.max_clear <= CLEAR_BOUND, "{}: {st:?}", S::NAME);
    if !dot_rounds_once::<S>() {
        // Near tangency the root is the square root of a discriminant that narrow
        // products (each rounded towards −∞) put several DELTAs off: the near bound does
        // not cover it (`i16f16n`: 1557 √δ measured), so it is shown, not bounded.
        return false;
    }
    assert!(st.max_near <= NEAR_BOUND, "{}: {st:?}", S::NAME);
    true
}

#[test]
#[cfg_attr(debug_assertions, ignore = "a million cases: run in release")]
fn the_cone_agrees_with_f64_in_every_format() {
    let mut bounded = Vec::new();
    for name in FORMATS {
        if fixray::with_format!(name, check()).unwrap() {
            bounded.push(name);
        }
    }
    // Not vacuous: every bound applies to every main format.
    for name in fixray::num::formats::MAIN {
        assert!(bounded.contains(&name), "{name}");
    }
}

/// The hourglass and the vase in format `S` against f64 (bounds as `docs/numerics.md`
/// states them); whether every bound applied.
fn check_waves<S: Scalar>() -> bool {
    let mut bounded = true;
    for surfer in [2, 3] {
        let st = wave_stats::<S>(surfer, 10_000, 0x5EAF_2026 + surfer as u64);
        println!("{} surfer {surfer}: {st:?}", S::NAME);
        assert!(
            st.hits > st.rays / 5,
            "{}: the sampler must hit: {st:?}",
            S::NAME
        );
        // f64's search against a scan at 1/1024: only grazing slivers are stepped over.
        assert!(st.stepped_over * 1_000 <= st.rays, "{}: {st:?}", S::NAME);
        if !sqrt_is_rounded::<S>() {
            bounded = false;
            continue;
        }
        assert!(st.disagree_clear * 1_000 <= st.rays, "{}: {st:?}", S::NAME);
        assert!(st.max_clear <= WAVE_CLEAR_BOUND, "{}: {st:?}", S::NAME);
        assert!(st.max_near <= WAVE_NEAR_BOUND, "{}: {st:?}", S::NAME);
    }
    bounded
}

#[test]
#[cfg_attr(debug_assertions, ignore = "many root searches: run in release")]
fn the_hourglass_and_the_vase_agree_with_f64_in_every_format() {
    let mut bounded = Vec::new();
    for name in FORMATS {
        if fixray::with_format!(name, check_waves()).unwrap() {
            bounded.push(name);
        }
    }
    for name in fixray::num::formats::MAIN {
        assert!(bounded.contains(&name), "{name}");
    }
}
