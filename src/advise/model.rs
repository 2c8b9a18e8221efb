//! The cost models, written by `cargo xtask calibrate` from the firmware's counts under
//! QEMU (`docs/calibration.md` holds every frame): do not edit.

use super::Model;

/// Every core × format calibrated: instructions per frame = Σ coefficient × count.
pub const MODELS: &[Model] = &[
    Model {
        core: "cortex-m0",
        format: "i16f16",
        coefficients: [
            1.042778e2, 0.000000e0, 2.624948e2, 4.307273e2, 2.930736e3, 0.000000e0, 0.000000e0,
            1.974248e4, 2.080244e2, 2.425650e3, 1.912552e3, 1.187393e4, 0.000000e0, 2.489391e3,
            1.291090e2,
        ],
        sampled: true,
        frames: 73,
        error: (0.3564, 2.4496),
    },
    Model {
        core: "cortex-m0",
        format: "i20f12",
        coefficients: [
            1.060814e2, 0.000000e0, 3.752670e2, 4.960132e2, 2.862975e3, 0.000000e0, 0.000000e0,
            2.142009e4, 0.000000e0, 2.685787e3, 1.895883e3, 1.218499e4, 0.000000e0, 2.271057e3,
            1.367278e2,
        ],
        sampled: true,
        frames: 73,
        error: (0.2980, 1.3101),
    },
    Model {
        core: "cortex-m0",
        format: "i32f32",
        coefficients: [
            3.345105e2, 0.000000e0, 1.088558e3, 3.153532e3, 2.443956e4, 0.000000e0, 0.000000e0,
            5.406443e4, 3.556898e3, 1.450356e4, 1.214653e4, 1.029534e5, 0.000000e0, 0.000000e0,
            0.000000e0,
        ],
        sampled: false,
        frames: 13,
        error: (0.5467, 1.4496),
    },
    Model {
        core: "cortex-m0",
        format: "f32",
        coefficients: [
            2.665599e2, 4.860518e1, 9.675847e2, 1.898841e3, 5.456948e3, 0.000000e0, 3.493963e3,
            1.123557e4, 2.954977e3, 4.002571e3, 4.129718e3, 1.987121e4, 0.000000e0, 6.079353e3,
            0.000000e0,
        ],
        sampled: true,
        frames: 73,
        error: (0.3285, 1.5923),
    },
    Model {
        core: "cortex-m4f",
        format: "i16f16",
        coefficients: [
            5.507093e1, 0.000000e0, 9.180313e1, 2.497103e2, 9.615273e2, 0.000000e0, 2.866381e2,
            4.372003e3, 9.735797e1, 7.716729e2, 6.802863e2, 4.567978e3, 0.000000e0, 8.847483e2,
            4.481505e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.2546, 1.2922),
    },
    Model {
        core: "cortex-m4f",
        format: "i20f12",
        coefficients: [
            5.545890e1, 0.000000e0, 2.118535e2, 3.049211e2, 1.085264e3, 0.000000e0, 0.000000e0,
            5.545622e3, 0.000000e0, 9.043611e2, 8.770761e2, 5.959066e3, 0.000000e0, 8.410856e2,
            4.602076e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.2002, 1.1450),
    },
    Model {
        core: "cortex-m4f",
        format: "i32f32",
        coefficients: [
            1.065805e2, 0.000000e0, 4.843603e2, 1.475838e3, 1.185798e4, 0.000000e0, 0.000000e0,
            1.816068e4, 1.970363e3, 6.131094e3, 5.024283e3, 5.134058e4, 0.000000e0, 0.000000e0,
            0.000000e0,
        ],
        sampled: false,
        frames: 13,
        error: (0.5004, 1.2960),
    },
    Model {
        core: "cortex-m4f",
        format: "f32",
        coefficients: [
            5.705060e1, 0.000000e0, 1.114649e2, 2.352427e2, 3.736067e2, 0.000000e0, 5.883430e2,
            0.000000e0, 3.757251e2, 2.264647e2, 3.640378e2, 1.180378e3, 0.000000e0, 6.515041e2,
            3.745634e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.2255, 1.3777),
    },
    Model {
        core: "riscv32imc",
        format: "i16f16",
        coefficients: [
            7.593497e1, 0.000000e0, 1.233150e2, 2.588555e2, 1.393277e3, 0.000000e0, 2.392989e2,
            8.486134e3, 1.643626e2, 1.147918e3, 9.474914e2, 5.771093e3, 0.000000e0, 1.228278e3,
            4.392909e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.3056, 1.1557),
    },
    Model {
        core: "riscv32imc",
        format: "i20f12",
        coefficients: [
            7.682688e1, 0.000000e0, 2.328666e2, 3.142633e2, 1.479758e3, 0.000000e0, 0.000000e0,
            8.638511e3, 1.353270e1, 1.287067e3, 1.095163e3, 6.952085e3, 0.000000e0, 1.150152e3,
            4.690352e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.2302, 1.1118),
    },
    Model {
        core: "riscv32imc",
        format: "i32f32",
        coefficients: [
            1.546860e2, 0.000000e0, 5.733942e2, 1.304869e3, 1.350992e4, 0.000000e0, 1.289334e3,
            4.473113e4, 2.384628e3, 8.483602e3, 5.877183e3, 5.771010e4, 0.000000e0, 6.517272e3,
            1.562707e2,
        ],
        sampled: true,
        frames: 73,
        error: (0.3503, 1.3646),
    },
    Model {
        core: "riscv32imc",
        format: "f32",
        coefficients: [
            1.539952e2, 6.351897e1, 6.196410e2, 1.190519e3, 3.357602e3, 0.000000e0, 2.110364e3,
            5.312518e3, 2.008467e3, 2.269592e3, 2.695817e3, 1.184453e4, 0.000000e0, 3.912040e3,
            0.000000e0,
        ],
        sampled: true,
        frames: 73,
        error: (0.3235, 1.6000),
    },
];

/// Cycles per instruction of the RP2040's Cortex-M0+ on this code: the emulated board's
/// whole exact frame of the boing ball at 240×240 (948.7 cycles per pixel at 200 MHz)
/// over the Cortex-M0's count of `scenes/boing-240x240.scene` in I16F16 (802.3
/// instructions per pixel).
pub const RP2040_CYCLES_PER_INSTRUCTION: f64 = 1.1825;
