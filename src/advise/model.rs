//! The cost models, written by `cargo xtask calibrate` from the firmware's counts under
//! QEMU (`docs/calibration.md` holds every frame): do not edit.

use super::Model;

/// Every core × format calibrated: instructions per frame = Σ coefficient × count.
pub const MODELS: &[Model] = &[
    Model {
        core: "cortex-m0",
        format: "i16f16",
        coefficients: [
            1.040438e2, 0.000000e0, 2.603673e2, 4.316435e2, 2.903610e3, 0.000000e0, 5.084120e1,
            1.904620e4, 1.828322e2, 2.406149e3, 1.858495e3, 1.162818e4, 0.000000e0, 2.636234e3,
            1.281694e2,
        ],
        sampled: true,
        frames: 73,
        error: (0.3438, 2.6777),
    },
    Model {
        core: "cortex-m0",
        format: "i20f12",
        coefficients: [
            1.058097e2, 0.000000e0, 3.906622e2, 5.064953e2, 2.862845e3, 0.000000e0, 0.000000e0,
            2.062093e4, 0.000000e0, 2.649675e3, 1.875194e3, 1.218726e4, 0.000000e0, 2.400708e3,
            1.352709e2,
        ],
        sampled: true,
        frames: 73,
        error: (0.3349, 1.3215),
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
            2.589854e2, 5.617965e1, 9.682603e2, 1.862096e3, 5.254390e3, 0.000000e0, 3.874868e3,
            9.344152e3, 2.756455e3, 4.011571e3, 3.817776e3, 1.804912e4, 0.000000e0, 6.021507e3,
            0.000000e0,
        ],
        sampled: true,
        frames: 73,
        error: (0.3112, 1.6423),
    },
    Model {
        core: "cortex-m4f",
        format: "i16f16",
        coefficients: [
            5.499674e1, 0.000000e0, 9.159369e1, 2.465972e2, 9.560109e2, 0.000000e0, 2.988704e2,
            4.452222e3, 9.062832e1, 7.785075e2, 6.739650e2, 4.500338e3, 0.000000e0, 8.966063e2,
            4.478006e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.2519, 1.3948),
    },
    Model {
        core: "cortex-m4f",
        format: "i20f12",
        coefficients: [
            5.537837e1, 0.000000e0, 2.145088e2, 3.076640e2, 1.086474e3, 0.000000e0, 0.000000e0,
            5.336435e3, 0.000000e0, 8.947389e2, 8.716706e2, 5.949158e3, 0.000000e0, 8.377476e2,
            4.700715e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.1930, 1.2047),
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
            5.710985e1, 0.000000e0, 1.138835e2, 2.317977e2, 3.785380e2, 0.000000e0, 5.795688e2,
            2.744782e2, 3.896256e2, 2.358233e2, 3.799240e2, 1.220585e3, 0.000000e0, 5.985455e2,
            3.664018e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.2340, 1.4373),
    },
    Model {
        core: "riscv32imc",
        format: "i16f16",
        coefficients: [
            7.568573e1, 0.000000e0, 1.202305e2, 2.595967e2, 1.370048e3, 0.000000e0, 2.842047e2,
            7.868877e3, 1.316512e2, 1.136386e3, 8.999232e2, 5.548010e3, 0.000000e0, 1.255537e3,
            5.677035e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.2391, 1.2997),
    },
    Model {
        core: "riscv32imc",
        format: "i20f12",
        coefficients: [
            7.651517e1, 0.000000e0, 2.411465e2, 3.217196e2, 1.479972e3, 0.000000e0, 0.000000e0,
            8.073229e3, 0.000000e0, 1.268798e3, 1.080562e3, 6.951583e3, 0.000000e0, 1.159521e3,
            6.060616e1,
        ],
        sampled: true,
        frames: 73,
        error: (0.2209, 0.9610),
    },
    Model {
        core: "riscv32imc",
        format: "i32f32",
        coefficients: [
            0.000000e0, 1.544521e2, 5.673203e2, 1.335580e3, 1.330506e4, 0.000000e0, 1.827678e3,
            3.963725e4, 2.257042e3, 8.302732e3, 5.414971e3, 5.505471e4, 0.000000e0, 8.472231e3,
            2.208894e2,
        ],
        sampled: true,
        frames: 73,
        error: (0.3936, 1.8168),
    },
    Model {
        core: "riscv32imc",
        format: "f32",
        coefficients: [
            1.619487e2, 5.556461e1, 6.201940e2, 1.166545e3, 3.233679e3, 0.000000e0, 2.328045e3,
            4.170596e3, 1.864743e3, 2.288641e3, 2.511218e3, 1.082043e4, 0.000000e0, 3.841972e3,
            0.000000e0,
        ],
        sampled: true,
        frames: 73,
        error: (0.3203, 1.6380),
    },
];

/// Cycles per instruction of the RP2040's Cortex-M0+ on this code: the emulated board's
/// whole exact frame of the boing ball at 240×240 (1025.4 cycles per pixel at 200 MHz)
/// over the Cortex-M0's count of `scenes/boing-240x240.scene` in I16F16 (806.4
/// instructions per pixel).
pub const RP2040_CYCLES_PER_INSTRUCTION: f64 = 1.2716;
