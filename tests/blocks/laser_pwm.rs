//! `laser_pwm` against its model, clock for clock, and an independent
//! monitor of the PWM at the pin.

use motion_hdl::blocks::laser_pwm::model::{LaserInputs, LaserPwmModel, ENGINE_CLOCKS};
use motion_hdl::blocks::laser_pwm::{LaserPwm, C, F, R};
use motion_hdl::sim::{Backend, Lockstep};
use motion_hdl::tools::cosim::{check_instance, Instance};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

fn model() -> LaserPwmModel {
    LaserPwmModel::new(R as u32, C as u32, F as u32)
}

/// Random stimulus: PWM periods short and long (and below 2), powers
/// below, at and above the period, both modes, loads at random and at
/// interpolation-period spacing, counts of every size and sign, feeds
/// (0 too), hold factors (0, partial, full, above), enable, kill, reset.
fn stimulus(rng: &mut StdRng, i: &mut LaserInputs, cycle: u64) {
    if rng.gen_ratio(1, 2000) {
        i.pwm_period = match rng.gen_range(0..6) {
            0 => rng.gen_range(0..3),
            1 => rng.gen_range(3..20),
            2 => 65535,
            _ => rng.gen_range(20..400),
        };
    }
    if rng.gen_ratio(1, 300) {
        i.power = match rng.gen_range(0..5) {
            0 => 0,
            1 => i.pwm_period,
            2 => 65535,
            _ => rng.gen_range(0..=i.pwm_period.max(1)),
        };
    }
    if rng.gen_ratio(1, 3000) {
        i.dynamic = !i.dynamic;
    }
    i.load = cycle.is_multiple_of(150) || rng.gen_ratio(1, 400);
    i.commit = cycle % 150 == 149 || rng.gen_ratio(1, 300);
    if i.load {
        let big = rng.gen_ratio(1, 10);
        let count = |rng: &mut StdRng| -> u64 {
            let v: i64 = match big {
                true => rng.gen_range(-32768..32768),
                false => rng.gen_range(-300..300),
            };
            (v as u64) & 0xffff
        };
        i.count_a = count(rng);
        i.count_b = count(rng);
        if rng.gen_ratio(1, 20) {
            i.count_a = 0x8000;
        }
        if rng.gen_ratio(1, 20) {
            (i.count_a, i.count_b) = (0, 0);
        }
    }
    if rng.gen_ratio(1, 500) {
        i.feed = match rng.gen_range(0..5) {
            0 => 0,
            1 => rng.gen_range(1..(1 << 24)),
            _ => rng.gen_range(1..500),
        };
    }
    if rng.gen_ratio(1, 700) {
        i.factor = match rng.gen_range(0..5) {
            0 => 0,
            1 => 65536,
            2 => rng.gen_range(65537..131072),
            _ => rng.gen_range(0..65536),
        };
    }
    if rng.gen_ratio(1, 1500) {
        i.enable = !i.enable;
    }
    i.kill = rng.gen_ratio(1, 5000) || (i.kill && !rng.gen_ratio(1, 50));
    i.reset = rng.gen_ratio(1, 50_000);
}

fn lockstep(backend: Backend, cycles: u64, seed: u64) {
    let mut rng = StdRng::seed_from_u64(seed);
    let mut l = Lockstep::on(backend, "laser_pwm", LaserPwm::default(), model()).unwrap();
    let mut i = LaserInputs {
        pwm_period: 100,
        power: 40,
        feed: 200,
        factor: 65536,
        enable: true,
        ..Default::default()
    };
    let (mut high, mut computed, mut dynamic_full) = (0u64, 0u64, 0u64);
    let mut was_busy = false;
    l.run(
        |cycle, _| {
            (cycle < cycles).then(|| {
                stimulus(&mut rng, &mut i, cycle);
                i
            })
        },
        |_, inputs, out| {
            high += out.pwm as u64;
            computed += (out.busy && !was_busy) as u64;
            was_busy = out.busy;
            dynamic_full += (inputs.dynamic && out.duty > 0 && out.duty == inputs.power) as u64;
        },
    )
    .unwrap_or_else(|e| panic!("{e}"));
    assert!(
        high > cycles / 20 && computed > cycles / 200 && dynamic_full > 0,
        "{high} {computed} {dynamic_full}"
    );
}

#[test]
fn rtl_matches_the_model_on_rust_hdl() {
    lockstep(Backend::RustHdl, 100_000, 1);
}

#[test]
fn exported_verilog_matches_the_model_in_verilator() {
    lockstep(Backend::Verilator, 2_000_000, 2);
}

/// The engine's arithmetic over a sweep of counts, in Verilator against
/// the model: every pair of magnitudes 0..=80 (signs at random) and 2000
/// pairs up to the extremes (-2^15 and 2^15 - 1), each with a random
/// power, feed and hold factor, back to back (`load` always high, the
/// duty committed every clock so `target` shows each result).
#[test]
fn the_engine_matches_the_model_over_a_sweep_of_counts() {
    let mut rng = StdRng::seed_from_u64(4);
    let sign = |rng: &mut StdRng, m: i64| if rng.gen() { -m } else { m };
    let mut pairs: Vec<(i64, i64)> = Vec::new();
    for a in 0..=80 {
        for b in 0..=80 {
            pairs.push((sign(&mut rng, a), sign(&mut rng, b)));
        }
    }
    for _ in 0..2000 {
        let mut extreme = || match rng.gen_range(0..4) {
            0 => -32768,
            1 => 32767,
            _ => rng.gen_range(-32768..32768),
        };
        pairs.push((extreme(), extreme()));
    }
    let computations = pairs.len();
    let mut l = Lockstep::on(
        Backend::Verilator,
        "laser_pwm",
        LaserPwm::default(),
        model(),
    )
    .unwrap();
    let taken = std::cell::Cell::new(0usize);
    let was_busy = std::cell::Cell::new(false);
    let mut tail = 0;
    let mut i = LaserInputs {
        pwm_period: 1000,
        dynamic: true,
        load: true,
        commit: true,
        enable: true,
        ..Default::default()
    };
    l.run(
        |_, _| {
            // The last pair's result shows ENGINE_CLOCKS after its load.
            if taken.get() == computations {
                tail += 1;
                i.load = false;
                return (tail <= ENGINE_CLOCKS + 2).then_some(i);
            }
            let (a, b) = pairs[taken.get()];
            if !was_busy.get() {
                i.count_a = a as u64 & 0xffff;
                i.count_b = b as u64 & 0xffff;
                i.power = [rng.gen_range(0..1000), 65535, 1][rng.gen_range(0..3)];
                i.feed =
                    [rng.gen_range(1..4000), rng.gen_range(1..1 << 24), 16][rng.gen_range(0..3)];
                i.factor = [65536, rng.gen_range(0..65536), 131071][rng.gen_range(0..3)];
            }
            Some(i)
        },
        |_, _, out| {
            if out.busy && !was_busy.get() {
                taken.set(taken.get() + 1);
            }
            was_busy.set(out.busy);
        },
    )
    .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(taken.get(), computations);
}

#[test]
fn the_engine_takes_its_stated_clocks() {
    assert_eq!(ENGINE_CLOCKS, 130);
}

#[test]
fn exported_verilog_matches_rust_in_icarus_and_verilator() {
    let mut rng = StdRng::seed_from_u64(3);
    let mut i = LaserInputs {
        pwm_period: 60,
        power: 30,
        feed: 100,
        factor: 65536,
        enable: true,
        dynamic: true,
        ..Default::default()
    };
    let vectors: Vec<Vec<u64>> = (0..30_000)
        .map(|cycle| {
            stimulus(&mut rng, &mut i, cycle);
            i.to_vector()
        })
        .collect();
    check_instance::<LaserPwm>(Instance::Exported("laser_pwm"), vectors);
}

/// One interpolation period of a path: its step counts and its length in
/// clocks (a held period lasts longer: the hold stretches its ticks).
#[derive(Clone, Copy, Debug)]
struct Period {
    a: i64,
    b: i64,
    factor: u64,
    clocks: u64,
}

/// A corner of an engraving: along A up to the feed, slowing to 30 % as
/// the direction turns through 90 degrees, along B back up to the feed,
/// a feed hold that slows to 20 % and resumes, then a stop. Counts per
/// period are the rounded vector (the host carries the fractions).
fn corner_path(feed: f64, clocks: u64) -> Vec<Period> {
    let mut speed: Vec<(f64, f64, u64)> = Vec::new(); // (v, angle, factor)
    let accel = feed / 20.0;
    let mut v = 0.0;
    while v < feed {
        v = (v + accel).min(feed);
        speed.push((v, 0.0, 65536));
    }
    speed.extend(std::iter::repeat_n((feed, 0.0, 65536), 30));
    for k in 0..14 {
        speed.push((feed * (1.0 - 0.05 * k as f64), 0.0, 65536));
    }
    for k in 0..=10 {
        speed.push((
            feed * 0.3,
            std::f64::consts::FRAC_PI_2 * k as f64 / 10.0,
            65536,
        ));
    }
    for k in 1..=14 {
        speed.push((
            feed * (0.3 + 0.05 * k as f64),
            std::f64::consts::FRAC_PI_2,
            65536,
        ));
    }
    for k in 0..40 {
        // The hold: the factor falls to 0.2 and comes back.
        let f = 1.0 - 0.8 * (std::f64::consts::PI * k as f64 / 39.0).sin();
        speed.push((feed, std::f64::consts::FRAC_PI_2, (f * 65536.0) as u64));
    }
    while v > 0.0 {
        v = (v - accel).max(0.0);
        speed.push((v, std::f64::consts::FRAC_PI_2, 65536));
    }
    speed
        .into_iter()
        .map(|(v, angle, factor)| Period {
            a: (v * angle.cos()).round() as i64,
            b: (v * angle.sin()).round() as i64,
            factor,
            clocks: clocks * 65536 / factor.max(1),
        })
        .collect()
}

/// Energy per step along the path, the duty x time / distance,
/// independent of the RTL and the model: the path's distance grows
/// through each period at its steps / clocks; each clock adds its duty in
/// force (`trace`, a fraction of the PWM period: a clock at full duty
/// adds one) to the window of `window` steps of distance it falls in; the
/// windows are compared with `expected` per step. Returns the worst
/// relative error over the windows that lie `margin` steps or more from
/// either end of the path.
fn energy_spread(trace: &[f64], path: &[Period], window: f64, margin: f64, expected: f64) -> f64 {
    let total: f64 = path
        .iter()
        .map(|p| ((p.a * p.a + p.b * p.b) as f64).sqrt())
        .sum();
    let mut windows = vec![0.0f64; (total / window).ceil() as usize + 1];
    let (mut clock, mut distance) = (0usize, 0.0f64);
    for p in path {
        let per_clock = ((p.a * p.a + p.b * p.b) as f64).sqrt() / p.clocks as f64;
        for _ in 0..p.clocks {
            windows[(distance / window) as usize] += trace.get(clock).copied().unwrap_or(0.0);
            distance += per_clock;
            clock += 1;
        }
    }
    let mut worst: f64 = 0.0;
    for (k, &high) in windows.iter().enumerate() {
        let (from, to) = (k as f64 * window, (k + 1) as f64 * window);
        if from >= margin && to <= total - margin {
            worst = worst.max((high / window - expected).abs() / expected);
        }
    }
    worst
}

/// The figure of merit: the energy per millimetre through the
/// acceleration, the corner (vector speed), the hold and the stop stays
/// within ±5 % of the programmed value, outside the slowest periods (below
/// 5 % of the feed: the first and last steps of the burn).
#[test]
fn dynamic_power_keeps_the_energy_per_step_through_a_corner_and_a_hold() {
    const PWM: u64 = 500;
    const PERIOD: u64 = 5 * PWM;
    let feed = 80u64;
    let power = 400u64;
    let path = corner_path(feed as f64, PERIOD);
    let mut l = Lockstep::on(
        Backend::Verilator,
        "laser_pwm",
        LaserPwm::default(),
        model(),
    )
    .unwrap();
    let mut i = LaserInputs {
        pwm_period: PWM,
        power,
        dynamic: true,
        // The feed port is in 1/16 step per period.
        feed: feed * 16,
        factor: 65536,
        enable: true,
        ..Default::default()
    };
    // A prelude of 200 clocks standing, in which the first period's
    // counts are loaded; then each period commits its duty in its first
    // clock and loads the next period's counts.
    let path: Vec<Period> = std::iter::once(Period {
        a: 0,
        b: 0,
        factor: 65536,
        clocks: 200,
    })
    .chain(path)
    .collect();
    let (mut trace, mut pin) = (Vec::new(), Vec::new());
    for (k, p) in path.iter().enumerate() {
        let next = path.get(k + 1).copied().unwrap_or(Period {
            a: 0,
            b: 0,
            factor: 65536,
            clocks: 0,
        });
        for clock in 0..p.clocks {
            i.commit = clock == 0 && k > 0;
            i.load = clock == 0;
            i.count_a = (next.a as u64) & 0xffff;
            i.count_b = (next.b as u64) & 0xffff;
            i.factor = next.factor;
            let out = l.step(&i).unwrap();
            trace.push(out.duty.min(PWM) as f64 / PWM as f64);
            pin.push(out.pwm);
        }
    }
    // At the pin, over the whole burn: the high clocks are the duty's.
    let highs = pin.iter().filter(|&&h| h).count() as f64;
    let duty_sum: f64 = trace.iter().sum();
    assert!(
        (highs - duty_sum).abs() <= PWM as f64,
        "{highs} high clocks, {duty_sum} by the duty"
    );
    // Windows of 8 steps (0.1 mm at 80 steps/mm), away from the burn's
    // first and last 8 steps (0.1 mm).
    let shift = (8.0, 8.0);
    let expected = power as f64 * PERIOD as f64 / (PWM as f64 * feed as f64);
    let worst = energy_spread(&trace, &path, shift.0, shift.1, expected);
    assert!(
        worst <= 0.05,
        "energy per step off by {:.1} %",
        worst * 100.0
    );
    // Mutations the monitor must catch: the Manhattan length instead of
    // the vector sum in the corner, a duty 10 % short, and a duty that
    // ignores the hold.
    let manhattan: Vec<Period> = path
        .iter()
        .map(|p| Period {
            // The energy a Manhattan-length duty gives, seen against the
            // vector length: the path's steps shrink by the same ratio.
            a: (p.a as f64 * ((p.a * p.a + p.b * p.b) as f64).sqrt().max(1.0)
                / (p.a.abs() + p.b.abs()).max(1) as f64)
                .round() as i64,
            b: (p.b as f64 * ((p.a * p.a + p.b * p.b) as f64).sqrt().max(1.0)
                / (p.a.abs() + p.b.abs()).max(1) as f64)
                .round() as i64,
            ..*p
        })
        .collect();
    assert!(energy_spread(&trace, &manhattan, shift.0, shift.1, expected) > 0.05);
    let dropped: Vec<f64> = trace.iter().map(|&d| d * 0.9).collect();
    assert!(energy_spread(&dropped, &path, shift.0, shift.1, expected) > 0.05);
    let unheld: Vec<Period> = path
        .iter()
        .map(|p| Period {
            clocks: PERIOD,
            ..*p
        })
        .collect();
    assert!(energy_spread(&trace, &unheld, shift.0, shift.1, expected) > 0.05);
}

/// A duty of 0 never fires and a full duty never drops for a clock, across
/// changes of power and period; `kill` and `enable` turn the pin off in
/// the next clock.
#[test]
fn no_glitch_at_zero_and_full_duty_and_off_in_one_clock() {
    let mut l = Lockstep::on(
        Backend::Verilator,
        "laser_pwm",
        LaserPwm::default(),
        model(),
    )
    .unwrap();
    let mut i = LaserInputs {
        pwm_period: 37,
        power: 0,
        enable: true,
        ..Default::default()
    };
    let mut rng = StdRng::seed_from_u64(9);
    for _ in 0..20_000 {
        if rng.gen_ratio(1, 500) {
            i.pwm_period = rng.gen_range(2..80);
        }
        assert!(!l.step(&i).unwrap().pwm, "a pulse at duty 0");
    }
    i.power = 65535;
    for _ in 0..200 {
        l.step(&i).unwrap();
    }
    for _ in 0..20_000 {
        if rng.gen_ratio(1, 500) {
            i.pwm_period = rng.gen_range(2..80);
            i.power = rng.gen_range(i.pwm_period..65536);
        }
        assert!(l.step(&i).unwrap().pwm, "a low clock at full duty");
    }
    i.kill = true;
    assert!(!l.step(&i).unwrap().pwm, "on after kill");
    i.kill = false;
    for _ in 0..100 {
        l.step(&i).unwrap();
    }
    i.enable = false;
    assert!(!l.step(&i).unwrap().pwm, "on after enable fell");
}
