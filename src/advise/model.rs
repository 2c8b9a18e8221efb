//! The cost models, written by `cargo xtask calibrate` from the firmware's counts under
//! QEMU (`docs/calibration.md` holds every frame): do not edit.

use super::Model;

/// Every core × format calibrated: instructions per frame = Σ coefficient × count.
pub const MODELS: &[Model] = &[
    Model {
        core: "cortex-m0",
        format: "i16f16",
        coefficients: [
            1.061308e2, 0.000000e0, 1.102600e3, 4.706666e2, 2.923745e3, 0.000000e0, 2.911640e1,
            1.638261e4, 6.244862e0, 2.390133e3, 1.826559e3, 1.174447e4, 0.000000e0, 1.544401e4,
            4.660391e1,
        ],
        sampled: true,
        frames: 72,
        error: (0.4042, 2.5530),
    },
    Model {
        core: "cortex-m0",
        format: "i20f12",
        coefficients: [
            1.083683e2, 0.000000e0, 1.298519e3, 5.373915e2, 2.870925e3, 0.000000e0, 0.000000e0,
            1.763168e4, 0.000000e0, 2.535269e3, 1.836318e3, 1.219999e4, 0.000000e0, 1.458210e4,
            5.111011e1,
        ],
        sampled: true,
        frames: 59,
        error: (0.4513, 1.9127),
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
            1.171782e2, 1.979006e2, 4.026819e3, 2.044987e3, 5.158328e3, 0.000000e0, 4.209352e3,
            0.000000e0, 1.884528e3, 3.838575e3, 3.267576e3, 1.630555e4, 0.000000e0, 3.059510e4,
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
            5.593817e1, 0.000000e0, 3.702711e2, 2.659312e2, 9.481183e2, 0.000000e0, 3.102441e2,
            2.683456e3, 3.177932e1, 7.305231e2, 6.188887e2, 4.329118e3, 0.000000e0, 5.418572e3,
            2.887557e1,
        ],
        sampled: true,
        frames: 72,
        error: (0.3113, 1.2996),
    },
    Model {
        core: "cortex-m4f",
        format: "i20f12",
        coefficients: [
            5.650915e1, 0.000000e0, 7.393461e2, 3.209484e2, 1.084722e3, 0.000000e0, 0.000000e0,
            3.668799e3, 0.000000e0, 8.299301e2, 8.402421e2, 5.832014e3, 0.000000e0, 5.206078e3,
            2.976095e1,
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
            5.799976e1, 0.000000e0, 4.678150e2, 2.507670e2, 3.974393e2, 0.000000e0, 5.481445e2,
            0.000000e0, 2.885527e2, 2.499913e2, 3.824553e2, 1.359419e3, 0.000000e0, 3.676629e3,
            3.501317e1,
        ],
        sampled: true,
        frames: 72,
        error: (0.2354, 0.8903),
    },
    Model {
        core: "riscv32imc",
        format: "i16f16",
        coefficients: [
            7.723941e1, 0.000000e0, 5.191964e2, 2.778765e2, 1.381770e3, 0.000000e0, 2.637417e2,
            6.690754e3, 6.557154e1, 1.120499e3, 8.858865e2, 5.620118e3, 0.000000e0, 7.648709e3,
            1.862138e1,
        ],
        sampled: true,
        frames: 72,
        error: (0.3417, 1.2329),
    },
    Model {
        core: "riscv32imc",
        format: "i20f12",
        coefficients: [
            7.826462e1, 0.000000e0, 8.740537e2, 3.303456e2, 1.480347e3, 0.000000e0, 0.000000e0,
            6.906272e3, 0.000000e0, 1.227866e3, 1.067540e3, 6.927231e3, 0.000000e0, 7.363023e3,
            1.908615e1,
        ],
        sampled: true,
        frames: 59,
        error: (0.3819, 1.0556),
    },
    Model {
        core: "riscv32imc",
        format: "i32f32",
        coefficients: [
            1.054300e1, 1.438502e2, 2.359157e3, 1.483372e3, 1.317525e4, 0.000000e0, 1.910253e3,
            2.740614e4, 1.943066e3, 7.923204e3, 5.039592e3, 5.578015e4, 0.000000e0, 4.746899e4,
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
            6.871598e1, 1.487601e2, 2.601413e3, 1.279550e3, 3.209407e3, 0.000000e0, 2.473102e3,
            0.000000e0, 1.309351e3, 2.236906e3, 2.231402e3, 1.008372e4, 0.000000e0, 1.977791e4,
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
