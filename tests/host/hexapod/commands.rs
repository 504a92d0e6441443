//! Tests of `motion_hdl::host::hexapod::commands` (`src/host/hexapod/commands.rs`).

use motion_hdl::host::hexapod::*;
use rand::{Rng, SeedableRng};

fn point(rng: &mut rand::rngs::StdRng) -> PeriodPoint {
    let mut r = |scale: f64| rng.gen_range(-scale..scale);
    PeriodPoint {
        sequence: 0,
        pose: Pose {
            position: [r(200.0), r(200.0), 500.0 + r(200.0)],
            angles: [r(20.0), r(20.0), r(20.0)],
        },
        velocity: [r(500.0), r(500.0), r(500.0), r(90.0), r(90.0), r(90.0)],
        acceleration: [r(5e3), r(5e3), r(5e3), r(900.0), r(900.0), r(900.0)],
    }
}

#[test]
fn points_survive_the_words_within_half_a_count() {
    let mut rng = rand::rngs::StdRng::seed_from_u64(36);
    for n in 0..10_000u32 {
        let mut p = point(&mut rng);
        p.sequence = (n * 7) as u16;
        let words = p.encode().unwrap();
        assert_eq!(words[0] >> 24, HEADER_MARK);
        let back = PeriodPoint::decode(&words).unwrap();
        assert_eq!(back.sequence, p.sequence);
        let (a, b) = (p.values(), back.values());
        for i in 0..WORDS - 1 {
            assert!(
                (a[i] - b[i]).abs() <= PeriodPoint::resolution()[i] * (1.0 + 1e-9),
                "{}: {} -> {}",
                FIELDS[i],
                a[i],
                b[i]
            );
        }
    }
}

#[test]
fn a_value_that_does_not_fit_is_named_not_wrapped() {
    let mut rng = rand::rngs::StdRng::seed_from_u64(37);
    let mut p = point(&mut rng);
    p.pose.position[2] = 2200.0;
    assert!(matches!(
        p.encode(),
        Err(CommandError::OutOfRange { field: "Z", .. })
    ));
    let mut p = point(&mut rng);
    p.acceleration[4] = f64::NAN;
    let e = p.encode().unwrap_err();
    assert!(e.to_string().contains("B acceleration"), "{e}");
    let mut p = point(&mut rng);
    p.velocity[0] = -2.2e6;
    assert!(matches!(
        p.encode(),
        Err(CommandError::OutOfRange {
            field: "X velocity",
            ..
        })
    ));
}

#[test]
fn a_slave_tells_a_point_from_an_empty_fifo_or_a_misaligned_read() {
    let mut rng = rand::rngs::StdRng::seed_from_u64(38);
    let words = point(&mut rng).encode().unwrap();
    assert_eq!(
        PeriodPoint::decode(&[0; WORDS]),
        Err(CommandError::Underflow)
    );
    let mut shifted = [0u32; WORDS];
    shifted[..WORDS - 1].copy_from_slice(&words[1..]);
    assert!(matches!(
        PeriodPoint::decode(&shifted),
        Err(CommandError::Header(_) | CommandError::Underflow)
    ));
    assert_eq!(
        PeriodPoint::decode(&words[..5]),
        Err(CommandError::Length(5))
    );
    assert_eq!(POINTS_PER_FIFO, 3);
}
