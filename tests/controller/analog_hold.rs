//! The feed hold on analog axes (`motion_controller_servo`), at the DAC
//! pins through a bank of AD669s: while the factor is below 1 every update
//! carries each analog axis's code scaled by one factor of the ramp, the
//! same for all axes; the codes ramp down to 0 and back, one ramp step at
//! a time, never stepped. The RTL runs in lockstep with the model (the
//! bench compares every clock).

use crate::bench::Bench;
use crate::motion_controller::configure;
use motion_hdl::blocks::motion_controller::analog_model::scaled_code;
use motion_hdl::blocks::motion_controller::hold_ramp::UNITY;
use motion_hdl::blocks::motion_controller::latency;
use motion_hdl::sim::Ad669Bank;

type Analog3 = Bench<3, 4, 5, false, true, true, false>;

/// The analog axes' codes (axis 1 steps).
const CODES: [i16; 2] = [20_000, -12_345];
const TICK_DIVISOR: u32 = 50;
const RATE: u32 = 2048;
const STEPS: u32 = UNITY / RATE;

/// One update at the outputs: its LDAC clock and axes 0 and 2's codes.
type Update = (u64, [i16; 2]);

/// The ramp steps n (factor UNITY - n x RATE) that give both codes of an
/// update.
fn ramp_steps(codes: [i16; 2]) -> Vec<u32> {
    (0..=STEPS)
        .filter(|n| {
            let f = UNITY - n * RATE;
            scaled_code(CODES[0], f) == codes[0] && scaled_code(CODES[1], f) == codes[1]
        })
        .collect()
}

/// The contract: every update is the codes at one factor of the ramp
/// (all axes alike); the factor never moves by more than the ticks since
/// the last update allow (one RATE per tick, plus one for the phase);
/// it reaches 0 and returns to 1.
fn check_ramp(updates: &[Update]) -> Result<(), String> {
    let mut last: Option<(u64, Vec<u32>)> = None;
    let (mut reached_zero, mut returned) = (false, false);
    for &(clock, codes) in updates {
        let steps = ramp_steps(codes);
        if steps.is_empty() {
            return Err(format!(
                "clock {clock}: {codes:?} is no factor of the ramp for both axes"
            ));
        }
        if let Some((then, before)) = &last {
            let allowed = (clock - then).div_ceil(TICK_DIVISOR as u64) as u32 + 1;
            let near = steps
                .iter()
                .any(|n| before.iter().any(|m| n.abs_diff(*m) <= allowed));
            if !near {
                return Err(format!(
                    "clock {clock}: the factor jumped from step {before:?} to {steps:?} in {} clocks",
                    clock - then
                ));
            }
        }
        reached_zero |= steps.contains(&STEPS);
        returned |= reached_zero && steps.contains(&0);
        last = Some((clock, steps));
    }
    if !reached_zero {
        return Err("the codes never reached 0".into());
    }
    if !returned {
        return Err("the codes never returned to the full codes".into());
    }
    Ok(())
}

/// Runs 12 periods of `CODES`, holds at `hold`, releases at `release`
/// (clocks from the RUN write); returns the updates seen.
fn run_held(hold: u64, release: u64) -> Vec<Update> {
    let mut b = Analog3::new().with_loopback();
    b.reset();
    configure(&mut b, 100, [false; 3]);
    b.write("TICK_DIVISOR", 0, TICK_DIVISOR);
    for axis in [0, 2] {
        let config = b.pack("AXIS_CONFIG", &[("ANALOG", 1)]);
        b.write("AXIS_CONFIG", axis, config);
    }
    for _ in 0..12 {
        b.write("FIFO_WRITE", 0, CODES[0] as i32 as u32);
        b.write("FIFO_WRITE", 1, 5);
        b.write("FIFO_WRITE", 2, CODES[1] as i32 as u32);
    }
    let hold_word = |b: &Analog3, hold: bool, release: bool| {
        b.pack(
            "HOLD_CONTROL",
            &[
                ("HOLD", hold as u64),
                ("RELEASE", release as u64),
                ("RATE", RATE as u64),
            ],
        )
    };
    let mut bank = Ad669Bank::new(3);
    let mut updates = Vec::new();
    b.write("CONTROL", 0, 1);
    let mut ldac_prev = b.last.dac.ldac;
    let mut stopped_at = None;
    for clock in 1..12 * 100 * TICK_DIVISOR as u64 + release + 10_000 {
        if clock == hold {
            let w = hold_word(&b, true, false);
            b.write("HOLD_CONTROL", 0, w);
        } else if clock == release {
            let w = hold_word(&b, false, true);
            b.write("HOLD_CONTROL", 0, w);
        } else {
            b.idle(1);
        }
        let pins = b.last.dac;
        bank.clock(pins.data, pins.cs_n, pins.l1_n, pins.ldac);
        if ldac_prev && !pins.ldac {
            updates.push((clock, [bank.code(0) as i16, bank.code(2) as i16]));
        }
        ldac_prev = pins.ldac;
        // The stop's 0 V update comes after RUN falls.
        if !b.last.running && clock > release {
            let at = *stopped_at.get_or_insert(clock);
            if clock > at + 200 {
                break;
            }
        }
    }
    updates
}

#[test]
fn a_hold_ramps_every_analog_code_down_and_back_by_one_factor() {
    // Hold inside period 3, release well after the stop (the ramp takes
    // 32 ticks, 1 600 clocks).
    let updates = run_held(3 * 5000 + 1234, 3 * 5000 + 1234 + 8000);
    check_ramp(&updates).unwrap_or_else(|e| panic!("{e}"));
    // The run ends with 0 V (the underrun after the last period).
    assert_eq!(updates.last().map(|u| u.1), Some([0, 0]));
    // With no pop between, re-walks follow each other at the stated pace.
    let spacings: Vec<u64> = updates.windows(2).map(|w| w[1].0 - w[0].0).collect();
    let rewalk = latency::analog_rewalk(3, 1, 5, 2, 5);
    let at_pace = spacings.iter().filter(|&&d| d == rewalk).count();
    assert!(
        at_pace * 2 > spacings.len(),
        "{at_pace} of {} updates {rewalk} clocks apart: {spacings:?}",
        spacings.len()
    );
    let scaled = updates
        .iter()
        .filter(|(_, c)| *c != CODES && *c != [0, 0])
        .count();
    assert!(
        scaled >= 2 * STEPS as usize / 2,
        "{scaled} updates with scaled codes: the ramp was not followed"
    );
}

#[test]
fn the_ramp_check_catches_a_stepped_uncoordinated_or_unreturned_update() {
    let full = (0, CODES);
    let half = |c| {
        (
            c,
            [
                scaled_code(CODES[0], UNITY / 2),
                scaled_code(CODES[1], UNITY / 2),
            ],
        )
    };
    let zero = |c| (c, [0, 0]);
    // A good ramp: full, half, zero, half, full, each far enough apart.
    let good = [full, half(1000), zero(2000), half(3000), (4000, CODES)];
    check_ramp(&good).unwrap();
    // Stepped straight to 0 in one update.
    let stepped = [full, zero(60), half(3000), (4000, CODES)];
    assert!(check_ramp(&stepped).unwrap_err().contains("jumped"));
    // Axis 2 scaled by another factor than axis 0.
    let torn = [
        full,
        (1000, [scaled_code(CODES[0], UNITY / 2), CODES[1]]),
        zero(2000),
        (4000, CODES),
    ];
    assert!(check_ramp(&torn).unwrap_err().contains("no factor"));
    // Held at 0 and never returned.
    let unreturned = [full, half(1000), zero(2000)];
    assert!(check_ramp(&unreturned)
        .unwrap_err()
        .contains("never returned"));
}
