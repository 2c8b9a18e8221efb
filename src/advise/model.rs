//! The cost models, written by `cargo xtask calibrate` from the firmware's counts under
//! QEMU (`docs/calibration.md` holds every frame): do not edit.

use super::Model;

/// Every core × format calibrated: instructions per frame = Σ coefficient × count.
pub const MODELS: &[Model] = &[
    Model {
        core: "cortex-m0",
        format: "i16f16",
        coefficients: [
            1.042118e2, 0.000000e0, 2.634093e2, 4.274962e2, 2.903882e3, 0.000000e0, 5.292875e1,
            1.921231e4, 2.924930e2, 2.353411e3, 1.870356e3, 1.158520e4, 0.000000e0, 2.535150e3,
            1.195571e2,
        ],
        sampled: true,
        frames: 73,
        error: (0.3445, 2.3361),
    },
    Model {
        core: "cortex-m0",
        format: "i20f12",
        coefficients: [
            1.061315e2, 0.000000e0, 4.033837e2, 5.033388e2, 2.864152e3, 0.000000e0, 0.000000e0,
            1.994211e4, 0.000000e0, 2.637203e3, 1.886924e3, 1.215446e4, 0.000000e0, 2.331414e3,
            1.262883e2,
        ],
        sampled: true,
        frames: 73,
        error: (0.3297, 1.2203),
    },
    Model {
        core: "cortex-m0",
        format: "i32f32",
        coefficients: [
            3.344298e2, 0.000000e0, 1.164182e3, 3.146228e3, 2.437148e4, 0.000000e0, 0.000000e0,
            5.504209e4, 3.634424e3, 1.450415e4, 1.215897e4, 1.037252e5, 0.000000e0, 0.000000e0,
            0.000000e0,
        ],
        sampled: false,
        frames: 13,
        error: (0.5472, 1.4496),
    },
    Model {
        core: "cortex-m0",
        format: "f32",
        coefficients: [
            2.465101e2, 6.863931e1, 9.095650e2, 1.859225e3, 5.270052e3, 0.000000e0, 3.864750e3,
            1.002636e4, 3.166328e3, 3.827263e3, 3.852064e3, 1.804167e4, 0.000000e0, 5.643446e3,
            0.000000e0,
        ],
        sampled: true,
        frames: 73,
        error: (0.3263, 1.6561),
    },
    Model {
        core: "cortex-m4f",
        format: "i16f16",
        coefficients: [
            5.519057e1, 0.000000e0, 8.671305e1, 2.474607e2, 9.446671e2, 0.000000e0, 3.173978e2,
            4.029230e3, 1.386450e2, 7.316573e2, 6.492293e2, 4.294602e3, 0.000000e0, 8.470084e2,
            3.854650e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.2708, 1.2002),
    },
    Model {
        core: "cortex-m4f",
        format: "i20f12",
        coefficients: [
            5.563583e1, 0.000000e0, 2.164535e2, 3.081510e2, 1.085256e3, 0.000000e0, 0.000000e0,
            4.674741e3, 0.000000e0, 8.753902e2, 8.667393e2, 5.831317e3, 0.000000e0, 7.985852e2,
            4.083891e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.1571, 1.1354),
    },
    Model {
        core: "cortex-m4f",
        format: "i32f32",
        coefficients: [
            1.065613e2, 0.000000e0, 4.996937e2, 1.484280e3, 1.177418e4, 0.000000e0, 0.000000e0,
            1.787334e4, 1.973643e3, 6.115404e3, 5.026163e3, 5.209237e4, 0.000000e0, 0.000000e0,
            0.000000e0,
        ],
        sampled: false,
        frames: 13,
        error: (0.5029, 1.2961),
    },
    Model {
        core: "cortex-m4f",
        format: "f32",
        coefficients: [
            5.742083e1, 0.000000e0, 1.065846e2, 2.301419e2, 3.749180e2, 0.000000e0, 5.886643e2,
            3.797563e2, 4.185512e2, 2.257042e2, 3.825064e2, 1.173038e3, 0.000000e0, 5.386898e2,
            3.069983e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.2260, 1.3563),
    },
    Model {
        core: "riscv32imc",
        format: "i16f16",
        coefficients: [
            7.595123e1, 0.000000e0, 1.204659e2, 2.528161e2, 1.362072e3, 0.000000e0, 3.009805e2,
            8.181280e3, 2.052620e2, 1.108735e3, 8.988905e2, 5.443499e3, 0.000000e0, 1.171381e3,
            4.827092e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.3062, 1.1357),
    },
    Model {
        core: "riscv32imc",
        format: "i20f12",
        coefficients: [
            7.675432e1, 0.000000e0, 2.407881e2, 3.161531e2, 1.481254e3, 0.000000e0, 0.000000e0,
            8.035402e3, 5.723699e1, 1.247243e3, 1.097454e3, 6.926026e3, 0.000000e0, 1.096566e3,
            5.181841e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.2148, 0.9411),
    },
    Model {
        core: "riscv32imc",
        format: "i32f32",
        coefficients: [
            0.000000e0, 1.544153e2, 5.758590e2, 1.343944e3, 1.326667e4, 0.000000e0, 1.756234e3,
            4.026753e4, 2.759216e3, 8.056752e3, 5.487930e3, 5.649387e4, 0.000000e0, 8.173840e3,
            2.106040e2,
        ],
        sampled: true,
        frames: 73,
        error: (0.3504, 1.6719),
    },
    Model {
        core: "riscv32imc",
        format: "f32",
        coefficients: [
            1.506655e2, 6.683290e1, 5.867551e2, 1.163593e3, 3.243490e3, 0.000000e0, 2.322561e3,
            4.747199e3, 2.111458e3, 2.189394e3, 2.536717e3, 1.085909e4, 0.000000e0, 3.577019e3,
            0.000000e0,
        ],
        sampled: true,
        frames: 73,
        error: (0.3099, 1.6464),
    },
];

/// Cycles per instruction of the RP2040's Cortex-M0+ on this code: the emulated board's
/// whole exact frame of the boing ball at 240×240 (1186.4 cycles per pixel at 200 MHz)
/// over the Cortex-M0's count of `scenes/boing-240x240.scene` in I16F16 (842.8
/// instructions per pixel).
pub const RP2040_CYCLES_PER_INSTRUCTION: f64 = 1.4077;
