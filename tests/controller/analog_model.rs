//! Tests of `motion_hdl::blocks::motion_controller::analog_model` (`src/blocks/motion_controller/analog_model.rs`).

use motion_hdl::blocks::motion_controller::analog_model::*;
use motion_hdl::blocks::motion_controller::analog_outputs::SCALE_STEPS;
use motion_hdl::blocks::motion_controller::hold_ramp::UNITY;

/// The RTL's multiply, step by step: 16 halvings of the product plus
/// the magnitude where the factor's bit is set, from its LSB.
fn shift_add(magnitude: u32, factor: u32) -> u32 {
    (0..SCALE_STEPS).fold(0, |p, i| (p + (factor >> i & 1) * magnitude) >> 1)
}

#[test]
fn the_shift_add_is_the_floor_of_the_product_at_every_magnitude_and_factor_edge() {
    let factors = (0..16)
        .flat_map(|b| [1u32 << b, (1 << b) - 1, (1 << b) + 1])
        .chain([0, 0xffff, 0xaaaa, 0x5555, 0x8001, 0x7fff, 12_345, 54_321])
        .filter(|&f| f < UNITY);
    for f in factors {
        for m in 0..=32_768u32 {
            assert_eq!(shift_add(m, f), (m * f) >> 16, "|code| {m}, factor {f}");
        }
    }
    for f in 0..UNITY {
        for m in [0, 1, 2, 255, 256, 32_767, 32_768] {
            assert_eq!(shift_add(m, f), (m * f) >> 16, "|code| {m}, factor {f}");
        }
    }
}

#[test]
fn a_scaled_code_keeps_its_sign_and_never_grows() {
    for code in [i16::MIN, -32_767, -1, 0, 1, 20_000, i16::MAX] {
        for f in [0, 1, 32_768, UNITY - 1] {
            let s = scaled_code(code, f);
            assert!(s.unsigned_abs() <= code.unsigned_abs());
            assert!(s == 0 || (s < 0) == (code < 0));
        }
        assert_eq!(scaled_code(code, 0), 0);
    }
}
