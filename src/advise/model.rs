//! The cost models, written by `cargo xtask calibrate` from the firmware's counts under
//! QEMU (`docs/calibration.md` holds every frame): do not edit.

use super::Model;

/// Every core × format calibrated: instructions per frame = Σ coefficient × count.
pub const MODELS: &[Model] = &[
    Model {
        core: "cortex-m0",
        format: "i16f16",
        coefficients: [
            1.042053e2, 0.000000e0, 2.575439e2, 4.308610e2, 2.930780e3, 0.000000e0, 0.000000e0,
            1.973318e4, 2.231142e2, 2.416882e3, 1.912357e3, 1.187388e4, 0.000000e0, 2.476964e3,
            1.466357e2,
        ],
        sampled: true,
        frames: 73,
        error: (0.3562, 2.3962),
    },
    Model {
        core: "cortex-m0",
        format: "i20f12",
        coefficients: [
            1.060359e2, 0.000000e0, 3.737797e2, 4.964761e2, 2.863003e3, 0.000000e0, 0.000000e0,
            2.138470e4, 0.000000e0, 2.684191e3, 1.895003e3, 1.218496e4, 0.000000e0, 2.256149e3,
            1.545152e2,
        ],
        sampled: true,
        frames: 73,
        error: (0.2987, 1.2904),
    },
    Model {
        core: "cortex-m0",
        format: "i32f32",
        coefficients: [
            3.345105e2, 0.000000e0, 1.088131e3, 3.153499e3, 2.443956e4, 0.000000e0, 0.000000e0,
            5.405617e4, 3.557180e3, 1.450304e4, 1.214660e4, 1.029534e5, 0.000000e0, 0.000000e0,
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
            2.802123e2, 3.495663e1, 9.594871e2, 1.894946e3, 5.445206e3, 0.000000e0, 3.500828e3,
            1.092961e4, 2.957906e3, 3.986870e3, 4.116789e3, 1.984853e4, 0.000000e0, 6.071401e3,
            0.000000e0,
        ],
        sampled: true,
        frames: 73,
        error: (0.3253, 1.5955),
    },
    Model {
        core: "cortex-m4f",
        format: "i16f16",
        coefficients: [
            5.500271e1, 0.000000e0, 9.171592e1, 2.501928e2, 9.633336e2, 0.000000e0, 2.834061e2,
            4.368673e3, 9.665412e1, 7.720483e2, 6.827244e2, 4.583257e3, 0.000000e0, 8.770342e2,
            5.613384e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.2501, 1.2834),
    },
    Model {
        core: "cortex-m4f",
        format: "i20f12",
        coefficients: [
            5.537877e1, 0.000000e0, 2.121783e2, 3.048380e2, 1.085310e3, 0.000000e0, 0.000000e0,
            5.553463e3, 0.000000e0, 9.045467e2, 8.773202e2, 5.959025e3, 0.000000e0, 8.333060e2,
            5.733693e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.1954, 1.1497),
    },
    Model {
        core: "cortex-m4f",
        format: "i32f32",
        coefficients: [
            1.065780e2, 0.000000e0, 4.842760e2, 1.475844e3, 1.185799e4, 0.000000e0, 0.000000e0,
            1.815265e4, 1.970557e3, 6.130626e3, 5.024275e3, 5.134057e4, 0.000000e0, 0.000000e0,
            0.000000e0,
        ],
        sampled: false,
        frames: 13,
        error: (0.5004, 1.2961),
    },
    Model {
        core: "cortex-m4f",
        format: "f32",
        coefficients: [
            5.691094e1, 0.000000e0, 1.098199e2, 2.337064e2, 3.693631e2, 0.000000e0, 5.960033e2,
            0.000000e0, 3.910270e2, 2.189062e2, 3.593482e2, 1.145125e3, 0.000000e0, 6.495375e2,
            4.882316e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.2241, 1.4205),
    },
    Model {
        core: "riscv32imc",
        format: "i16f16",
        coefficients: [
            7.589685e1, 0.000000e0, 1.228634e2, 2.589684e2, 1.393337e3, 0.000000e0, 2.392294e2,
            8.470035e3, 1.649097e2, 1.146893e3, 9.473752e2, 5.771389e3, 0.000000e0, 1.224709e3,
            4.849104e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.3032, 1.1519),
    },
    Model {
        core: "riscv32imc",
        format: "i20f12",
        coefficients: [
            7.678286e1, 0.000000e0, 2.313999e2, 3.143442e2, 1.479783e3, 0.000000e0, 0.000000e0,
            8.632811e3, 1.724678e1, 1.284550e3, 1.095046e3, 6.952050e3, 0.000000e0, 1.145372e3,
            5.161458e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.2239, 1.0939),
    },
    Model {
        core: "riscv32imc",
        format: "i32f32",
        coefficients: [
            1.546785e2, 0.000000e0, 5.727548e2, 1.304965e3, 1.350991e4, 0.000000e0, 1.289345e3,
            4.471632e4, 2.386017e3, 8.482162e3, 5.876986e3, 5.771004e4, 0.000000e0, 6.514288e3,
            1.601891e2,
        ],
        sampled: true,
        frames: 73,
        error: (0.3502, 1.3636),
    },
    Model {
        core: "riscv32imc",
        format: "f32",
        coefficients: [
            1.621749e2, 5.533841e1, 6.162053e2, 1.188937e3, 3.352950e3, 0.000000e0, 2.110030e3,
            5.156273e3, 2.001907e3, 2.266122e3, 2.691159e3, 1.185244e4, 0.000000e0, 3.912042e3,
            0.000000e0,
        ],
        sampled: true,
        frames: 73,
        error: (0.3205, 1.5976),
    },
];

/// Cycles per instruction of the RP2040's Cortex-M0+ on this code: the emulated board's
/// whole exact frame of the boing ball at 240×240 (1023.7 cycles per pixel at 200 MHz)
/// over the Cortex-M0's count of `scenes/boing-240x240.scene` in I16F16 (804.5
/// instructions per pixel).
pub const RP2040_CYCLES_PER_INSTRUCTION: f64 = 1.2725;
