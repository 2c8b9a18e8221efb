//! The cost models, written by `cargo xtask calibrate` from the firmware's counts under
//! QEMU (`docs/calibration.md` holds every frame): do not edit.

use super::Model;

/// Every core × format calibrated: instructions per frame = Σ coefficient × count.
pub const MODELS: &[Model] = &[
    Model {
        core: "cortex-m0",
        format: "i16f16",
        coefficients: [
            1.061270e2, 0.000000e0, 1.102608e3, 4.706667e2, 2.923751e3, 0.000000e0, 2.910794e1,
            1.638280e4, 6.250207e0, 2.390139e3, 1.826571e3, 1.174452e4, 0.000000e0, 1.544397e4,
            4.660192e1,
        ],
        sampled: true,
        frames: 72,
        error: (0.4042, 2.5530),
    },
    Model {
        core: "cortex-m0",
        format: "i20f12",
        coefficients: [
            1.083683e2, 0.000000e0, 1.298519e3, 5.373907e2, 2.870925e3, 0.000000e0, 0.000000e0,
            1.763175e4, 0.000000e0, 2.535272e3, 1.836320e3, 1.219999e4, 0.000000e0, 1.458208e4,
            5.110825e1,
        ],
        sampled: true,
        frames: 59,
        error: (0.4513, 1.9128),
    },
    Model {
        core: "cortex-m0",
        format: "i32f32",
        coefficients: [
            3.345567e2, 0.000000e0, 4.728059e3, 3.208685e3, 2.437137e4, 0.000000e0, 0.000000e0,
            5.038939e4, 2.628303e3, 1.485175e4, 1.203837e4, 1.037253e5, 0.000000e0, 0.000000e0,
            0.000000e0,
        ],
        sampled: false,
        frames: 13,
        error: (0.5435, 1.4543),
    },
    Model {
        core: "cortex-m0",
        format: "f32",
        coefficients: [
            1.171757e2, 1.979031e2, 4.026825e3, 2.044988e3, 5.158333e3, 0.000000e0, 4.209345e3,
            0.000000e0, 1.884532e3, 3.838572e3, 3.267583e3, 1.630558e4, 0.000000e0, 3.059510e4,
            0.000000e0,
        ],
        sampled: true,
        frames: 72,
        error: (0.3917, 1.4089),
    },
    Model {
        core: "cortex-m4f",
        format: "i16f16",
        coefficients: [
            5.593816e1, 0.000000e0, 3.702706e2, 2.659310e2, 9.481168e2, 0.000000e0, 3.102467e2,
            2.683392e3, 3.177809e1, 7.305256e2, 6.188865e2, 4.329106e3, 0.000000e0, 5.418570e3,
            2.887523e1,
        ],
        sampled: true,
        frames: 72,
        error: (0.3113, 1.2996),
    },
    Model {
        core: "cortex-m4f",
        format: "i20f12",
        coefficients: [
            5.650912e1, 0.000000e0, 7.393462e2, 3.209482e2, 1.084722e3, 0.000000e0, 0.000000e0,
            3.668812e3, 0.000000e0, 8.299307e2, 8.402403e2, 5.832014e3, 0.000000e0, 5.206068e3,
            2.976236e1,
        ],
        sampled: true,
        frames: 59,
        error: (0.3893, 1.9388),
    },
    Model {
        core: "cortex-m4f",
        format: "i32f32",
        coefficients: [
            1.065669e2, 0.000000e0, 2.060766e3, 1.509523e3, 1.177416e4, 0.000000e0, 0.000000e0,
            1.593900e4, 1.521857e3, 6.278419e3, 4.975642e3, 5.209240e4, 0.000000e0, 0.000000e0,
            0.000000e0,
        ],
        sampled: false,
        frames: 13,
        error: (0.5043, 1.2994),
    },
    Model {
        core: "cortex-m4f",
        format: "f32",
        coefficients: [
            5.799975e1, 0.000000e0, 4.678141e2, 2.507670e2, 3.974386e2, 0.000000e0, 5.481462e2,
            0.000000e0, 2.885517e2, 2.499907e2, 3.824535e2, 1.359409e3, 0.000000e0, 3.676627e3,
            3.501411e1,
        ],
        sampled: true,
        frames: 72,
        error: (0.2354, 0.8903),
    },
    Model {
        core: "riscv32imc",
        format: "i16f16",
        coefficients: [
            7.723944e1, 0.000000e0, 5.191963e2, 2.778760e2, 1.381769e3, 0.000000e0, 2.637437e2,
            6.690769e3, 6.557341e1, 1.120498e3, 8.858855e2, 5.620109e3, 0.000000e0, 7.648700e3,
            1.861431e1,
        ],
        sampled: true,
        frames: 72,
        error: (0.3417, 1.2329),
    },
    Model {
        core: "riscv32imc",
        format: "i20f12",
        coefficients: [
            7.826471e1, 0.000000e0, 8.740547e2, 3.303431e2, 1.480347e3, 0.000000e0, 0.000000e0,
            6.906462e3, 0.000000e0, 1.227875e3, 1.067545e3, 6.927231e3, 0.000000e0, 7.363008e3,
            1.907642e1,
        ],
        sampled: true,
        frames: 59,
        error: (0.3819, 1.0555),
    },
    Model {
        core: "riscv32imc",
        format: "i32f32",
        coefficients: [
            1.053853e1, 1.438547e2, 2.359156e3, 1.483374e3, 1.317524e4, 0.000000e0, 1.910265e3,
            2.740598e4, 1.943064e3, 7.923198e3, 5.039581e3, 5.578009e4, 0.000000e0, 4.746898e4,
            0.000000e0,
        ],
        sampled: true,
        frames: 72,
        error: (0.4259, 1.3963),
    },
    Model {
        core: "riscv32imc",
        format: "f32",
        coefficients: [
            6.870730e1, 1.487688e2, 2.601427e3, 1.279552e3, 3.209419e3, 0.000000e0, 2.473089e3,
            0.000000e0, 1.309363e3, 2.236908e3, 2.231419e3, 1.008377e4, 0.000000e0, 1.977788e4,
            0.000000e0,
        ],
        sampled: true,
        frames: 72,
        error: (0.3567, 1.3071),
    },
];

/// Cycles per instruction of the RP2040's Cortex-M0+ on this code: the emulated board's
/// whole exact frame of the boing ball at 240×240 (1258.9 cycles per pixel at 200 MHz)
/// over the Cortex-M0's count of `scenes/boing-240x240.scene` in I16F16 (869.0
/// instructions per pixel).
pub const RP2040_CYCLES_PER_INSTRUCTION: f64 = 1.4487;
