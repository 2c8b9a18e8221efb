//! The advisor (`fixray::advise`): its choice holds the budget and nothing cheaper does,
//! its accuracy figures are the frames', and its costs follow the calibrated counts (the
//! render example's `--advise` is tested in `tests/cli.rs`).

use fixray::advise::{
    Budget, Core, MODELS, Model, RP2040_CYCLES_PER_INSTRUCTION, advise, model_price, work,
};
use fixray::{I16F16, Sampling, Scene};

const SPHERES: &str = include_str!("../scenes/spheres.scene");
const DEFAULT: &str = include_str!("../scenes/default.scene");

#[test]
fn every_core_and_main_format_has_a_model() {
    for core in Core::ALL {
        for format in ["i16f16", "i20f12", "i32f32", "f32"] {
            let m = Model::of(core, format).unwrap_or_else(|| panic!("{core:?} {format}"));
            assert!(m.frames >= 13, "{core:?} {format}: {} frames", m.frames);
            assert!(m.error.0 <= m.error.1);
        }
    }
    assert!(
        MODELS
            .iter()
            .all(|m| m.coefficients.iter().all(|c| *c >= 0.0))
    );
    // The RP2040 is priced in cycles: the M0's instructions for the same work times the
    // calibrated ratio of the board's cycles to the M0's count. That ratio is the board's
    // frame, drawn for its RGB565 panel, over the M0's count of the exact frame: below
    // the core's own cycles per instruction (about 1.5), as the board's frame skips work
    // the count does; outside 0.8 to 2 the calibration has gone wrong.
    let scene = Scene::<I16F16>::parse(DEFAULT).unwrap();
    let (_, w) = work(&scene, Sampling::Exact);
    let m0 = model_price(Core::CortexM0, "i16f16", false, &w).unwrap().0;
    let rp = model_price(Core::Rp2040, "i16f16", false, &w).unwrap().0;
    assert!(
        (rp / m0 - RP2040_CYCLES_PER_INSTRUCTION).abs() < 1e-9,
        "{rp} cycles against {m0} instructions"
    );
    assert!(
        (0.8..2.0).contains(&RP2040_CYCLES_PER_INSTRUCTION),
        "{RP2040_CYCLES_PER_INSTRUCTION} cycles per instruction"
    );
}

#[test]
fn the_choice_holds_the_budget_and_nothing_cheaper_does() {
    for budget in [
        Budget::Beyond {
            levels: 2,
            percent: 1.0,
        },
        Budget::Psnr(45.0),
    ] {
        for core in [Core::CortexM0, Core::Rp2040] {
            let advice = advise(DEFAULT, core, budget).unwrap();
            let choice = advice.choice().expect("some format holds");
            assert!(choice.holds);
            match budget {
                Budget::Beyond { percent, .. } => assert!(choice.beyond <= percent),
                Budget::Psnr(db) => assert!(choice.psnr >= db),
            }
            for c in &advice.candidates {
                if c.cost < choice.cost {
                    assert!(!c.holds, "{} {} is cheaper and holds", c.format, c.sampling);
                }
            }
            assert!(advice.candidates.windows(2).all(|w| w[0].cost <= w[1].cost));
        }
    }
}

#[test]
fn a_budget_nothing_holds_has_no_choice() {
    // No format draws every pixel of the spheres within 0 levels of f64 but f64 itself,
    // which is not a candidate (it is the reference).
    let advice = advise(SPHERES, Core::CortexM4F, Budget::Psnr(f64::INFINITY)).unwrap();
    assert!(
        advice
            .candidates
            .iter()
            .all(|c| c.psnr.is_finite() || c.holds)
    );
    if advice.candidates.iter().all(|c| c.psnr.is_finite()) {
        assert_eq!(advice.choice(), None);
    }
}

#[test]
fn sampled_modes_are_priced_by_their_work() {
    // A frame drawn in blocks fills pixels and traces corners; where it traces fewer
    // pixels its counted rays fall.
    let scene = Scene::<I16F16>::parse(include_str!("../scenes/boing-240x240.scene")).unwrap();
    let (exact_pixels, exact) = work(&scene, Sampling::Exact);
    let blocks = Sampling::blocks(fixray::BlockSize::Eight, 8);
    let (_, sampled) = work(&scene, blocks);
    assert_eq!(exact.pixels(), exact_pixels.len() as f64);
    assert_eq!(exact.counts[13], 0.0);
    assert_eq!(exact.counts[14], 0.0);
    assert!(sampled.counts[13] > 0.0 && sampled.counts[14] > 0.0);
    assert!(sampled.sampled && !exact.sampled);
    let rays = |w: &fixray::advise::Work| w.counts[1..5].iter().sum::<f64>();
    assert!(rays(&sampled) < rays(&exact));
    // Zero bound: the exact frame's pixels.
    let (zero, _) = work(&scene, Sampling::blocks(fixray::BlockSize::Eight, 0));
    assert_eq!(zero, exact_pixels);
}

#[test]
fn i32f32_costs_more_than_i16f16_on_the_m0() {
    let advice = advise(DEFAULT, Core::CortexM0, Budget::Psnr(0.0)).unwrap();
    let exact = |f: &str| {
        advice
            .candidates
            .iter()
            .find(|c| c.format == f && c.sampling == Sampling::Exact)
            .map(|c| c.cost)
            .unwrap()
    };
    assert!(exact("i32f32") > 3.0 * exact("i16f16"));
    // No sampled I32F32 on the M0: none was counted (that firmware does not fit the flash).
    assert!(
        advice
            .candidates
            .iter()
            .filter(|c| c.format == "i32f32")
            .all(|c| !c.sampled)
    );
}
