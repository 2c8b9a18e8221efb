//! The cost models, written by `cargo xtask calibrate` from the firmware's counts under
//! QEMU (`docs/calibration.md` holds every frame): do not edit.

use super::Model;

/// Every core × format calibrated: instructions per frame = Σ coefficient × count.
pub const MODELS: &[Model] = &[
    Model {
        core: "cortex-m0",
        format: "i16f16",
        coefficients: [
            1.042492e2, 0.000000e0, 2.550780e2, 4.328584e2, 2.912458e3, 0.000000e0, 3.429958e1,
            1.915328e4, 2.713014e2, 2.362677e3, 1.872927e3, 1.170740e4, 0.000000e0, 2.533554e3,
            1.199246e2,
        ],
        sampled: true,
        frames: 73,
        error: (0.3407, 2.4169),
    },
    Model {
        core: "cortex-m0",
        format: "i20f12",
        coefficients: [
            1.060519e2, 0.000000e0, 3.955719e2, 5.044083e2, 2.862704e3, 0.000000e0, 0.000000e0,
            2.077501e4, 0.000000e0, 2.656638e3, 1.879126e3, 1.218742e4, 0.000000e0, 2.337883e3,
            1.255929e2,
        ],
        sampled: true,
        frames: 73,
        error: (0.3334, 1.3390),
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
            2.465120e2, 6.865689e1, 9.129539e2, 1.857355e3, 5.270553e3, 0.000000e0, 3.858597e3,
            1.022777e4, 3.173350e3, 3.822143e3, 3.856517e3, 1.811750e4, 0.000000e0, 5.643437e3,
            0.000000e0,
        ],
        sampled: true,
        frames: 73,
        error: (0.3268, 1.6550),
    },
    Model {
        core: "cortex-m4f",
        format: "i16f16",
        coefficients: [
            5.521493e1, 0.000000e0, 8.828612e1, 2.461052e2, 9.593764e2, 0.000000e0, 2.924779e2,
            4.563705e3, 1.325593e2, 7.605803e2, 6.813267e2, 4.530818e3, 0.000000e0, 8.466571e2,
            3.846865e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.2893, 1.2456),
    },
    Model {
        core: "cortex-m4f",
        format: "i20f12",
        coefficients: [
            5.559889e1, 0.000000e0, 2.167184e2, 3.063745e2, 1.086344e3, 0.000000e0, 0.000000e0,
            5.429825e3, 0.000000e0, 8.989593e2, 8.740271e2, 5.949324e3, 0.000000e0, 8.016294e2,
            4.030271e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.1932, 1.1960),
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
            5.745931e1, 0.000000e0, 1.072272e2, 2.294070e2, 3.740631e2, 0.000000e0, 5.871151e2,
            3.549859e2, 4.201585e2, 2.223033e2, 3.765694e2, 1.186289e3, 0.000000e0, 5.387887e2,
            3.055985e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.2269, 1.3610),
    },
    Model {
        core: "riscv32imc",
        format: "i16f16",
        coefficients: [
            7.597253e1, 0.000000e0, 1.155212e2, 2.582585e2, 1.370793e3, 0.000000e0, 2.825394e2,
            7.984729e3, 1.799467e2, 1.114935e3, 9.040311e2, 5.556090e3, 0.000000e0, 1.170693e3,
            4.863432e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.2846, 1.1470),
    },
    Model {
        core: "riscv32imc",
        format: "i20f12",
        coefficients: [
            7.681950e1,
            0.000000e0,
            2.441829e2,
            3.203274e2,
            1.479792e3,
            0.000000e0,
            0.000000e0,
            8.172364e3,
            3.903473e-1,
            1.273062e3,
            1.083043e3,
            6.951823e3,
            0.000000e0,
            1.098012e3,
            5.183406e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.2352, 0.9405),
    },
    Model {
        core: "riscv32imc",
        format: "i32f32",
        coefficients: [
            0.000000e0, 1.544521e2, 5.544684e2, 1.358395e3, 1.338263e4, 0.000000e0, 1.687417e3,
            3.963101e4, 2.704065e3, 8.060765e3, 5.514065e3, 5.571220e4, 0.000000e0, 8.165069e3,
            2.113300e2,
        ],
        sampled: true,
        frames: 73,
        error: (0.3368, 1.6705),
    },
    Model {
        core: "riscv32imc",
        format: "f32",
        coefficients: [
            1.506669e2, 6.684640e1, 5.874728e2, 1.163139e3, 3.242785e3, 0.000000e0, 2.323585e3,
            4.774891e3, 2.112448e3, 2.179433e3, 2.533913e3, 1.083285e4, 0.000000e0, 3.577084e3,
            0.000000e0,
        ],
        sampled: true,
        frames: 73,
        error: (0.3097, 1.6464),
    },
];

/// Cycles per instruction of the RP2040's Cortex-M0+ on this code: the emulated board's
/// whole exact frame of the boing ball at 240×240 (1025.4 cycles per pixel at 200 MHz)
/// over the Cortex-M0's count of `scenes/boing-240x240.scene` in I16F16 (806.4
/// instructions per pixel).
pub const RP2040_CYCLES_PER_INSTRUCTION: f64 = 1.2715;
