//! The cost models, written by `cargo xtask calibrate` from the firmware's counts under
//! QEMU (`docs/calibration.md` holds every frame): do not edit.

use super::Model;

/// Every core × format calibrated: instructions per frame = Σ coefficient × count.
pub const MODELS: &[Model] = &[
    Model {
        core: "cortex-m0",
        format: "i16f16",
        coefficients: [
            1.040163e2, 0.000000e0, 2.561020e2, 4.329297e2, 2.877751e3, 0.000000e0, 9.857292e1,
            1.835574e4, 1.505304e2, 2.390978e3, 1.806699e3, 1.139999e4, 0.000000e0, 2.692905e3,
            1.268175e2,
        ],
        sampled: true,
        frames: 73,
        error: (0.3314, 2.7880),
    },
    Model {
        core: "cortex-m0",
        format: "i20f12",
        coefficients: [
            1.057908e2, 0.000000e0, 3.910816e2, 5.174213e2, 2.862856e3, 0.000000e0, 0.000000e0,
            1.978230e4, 0.000000e0, 2.611776e3, 1.853361e3, 1.218724e4, 0.000000e0, 2.430456e3,
            1.359712e2,
        ],
        sampled: true,
        frames: 73,
        error: (0.3179, 1.2658),
    },
    Model {
        core: "cortex-m0",
        format: "i32f32",
        coefficients: [
            3.345137e2, 0.000000e0, 1.095899e3, 3.154180e3, 2.443839e4, 0.000000e0, 0.000000e0,
            5.400400e4, 3.558195e3, 1.450012e4, 1.214524e4, 1.029633e5, 0.000000e0, 0.000000e0,
            0.000000e0,
        ],
        sampled: false,
        frames: 13,
        error: (0.5467, 1.4495),
    },
    Model {
        core: "cortex-m0",
        format: "f32",
        coefficients: [
            2.631662e2, 5.200277e1, 9.389566e2, 1.879865e3, 5.080783e3, 0.000000e0, 4.189444e3,
            3.970894e3, 2.546422e3, 3.873540e3, 3.453468e3, 1.655369e4, 0.000000e0, 6.331810e3,
            0.000000e0,
        ],
        sampled: true,
        frames: 73,
        error: (0.2927, 1.6441),
    },
    Model {
        core: "cortex-m4f",
        format: "i16f16",
        coefficients: [
            5.497993e1, 0.000000e0, 8.890010e1, 2.476156e2, 9.396527e2, 0.000000e0, 3.288164e2,
            4.002827e3, 7.018048e1, 7.683604e2, 6.410460e2, 4.358313e3, 0.000000e0, 9.258751e2,
            4.465110e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.2358, 1.4786),
    },
    Model {
        core: "cortex-m4f",
        format: "i20f12",
        coefficients: [
            5.536216e1, 0.000000e0, 2.141195e2, 3.136426e2, 1.086485e3, 0.000000e0, 0.000000e0,
            4.877696e3, 0.000000e0, 8.740053e2, 8.597276e2, 5.949135e3, 0.000000e0, 8.567084e2,
            4.774349e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.1811, 1.2533),
    },
    Model {
        core: "cortex-m4f",
        format: "i32f32",
        coefficients: [
            1.065781e2, 0.000000e0, 4.852212e2, 1.475345e3, 1.185630e4, 0.000000e0, 0.000000e0,
            1.819087e4, 1.971080e3, 6.132057e3, 5.025272e3, 5.135488e4, 0.000000e0, 0.000000e0,
            0.000000e0,
        ],
        sampled: false,
        frames: 13,
        error: (0.5005, 1.2961),
    },
    Model {
        core: "cortex-m4f",
        format: "f32",
        coefficients: [
            5.705761e1, 0.000000e0, 1.119171e2, 2.338318e2, 3.600730e2, 0.000000e0, 6.123223e2,
            0.000000e0, 3.627692e2, 2.241288e2, 3.421124e2, 1.070250e3, 0.000000e0, 6.345569e2,
            3.705444e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.2294, 1.3828),
    },
    Model {
        core: "riscv32imc",
        format: "i16f16",
        coefficients: [
            7.566937e1, 0.000000e0, 1.179058e2, 2.606119e2, 1.355084e3, 0.000000e0, 3.114439e2,
            7.453324e3, 1.134940e2, 1.126606e3, 8.698031e2, 5.419542e3, 0.000000e0, 1.285975e3,
            5.635326e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.2279, 1.3694),
    },
    Model {
        core: "riscv32imc",
        format: "i20f12",
        coefficients: [
            7.648995e1, 0.000000e0, 2.408054e2, 3.274101e2, 1.479987e3, 0.000000e0, 0.000000e0,
            7.636845e3, 0.000000e0, 1.249077e3, 1.069207e3, 6.951563e3, 0.000000e0, 1.178195e3,
            6.123860e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.1929, 0.9592),
    },
    Model {
        core: "riscv32imc",
        format: "i32f32",
        coefficients: [
            0.000000e0, 1.544521e2, 5.488343e2, 1.334664e3, 1.320650e4, 0.000000e0, 2.005909e3,
            3.749462e4, 2.192974e3, 8.234398e3, 5.232898e3, 5.421923e4, 0.000000e0, 8.646068e3,
            2.154614e2,
        ],
        sampled: true,
        frames: 73,
        error: (0.4030, 1.9270),
    },
    Model {
        core: "riscv32imc",
        format: "f32",
        coefficients: [
            1.646444e2, 5.286890e1, 6.034070e2, 1.176798e3, 3.129910e3, 0.000000e0, 2.514557e3,
            1.000882e3, 1.736088e3, 2.209795e3, 2.295568e3, 9.939976e3, 0.000000e0, 4.036823e3,
            0.000000e0,
        ],
        sampled: true,
        frames: 73,
        error: (0.2886, 1.6383),
    },
];

/// Cycles per instruction of the RP2040's Cortex-M0+ on this code: the emulated board's
/// whole exact frame of the boing ball at 240×240 (1025.4 cycles per pixel at 200 MHz)
/// over the Cortex-M0's count of `scenes/boing-240x240.scene` in I16F16 (806.4
/// instructions per pixel).
pub const RP2040_CYCLES_PER_INSTRUCTION: f64 = 1.2716;
