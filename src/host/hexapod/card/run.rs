//! The parallel-machine card run end to end: the control DSP, three motor
//! DSPs and six leg plants around `parallel_card`, clock by clock.

use crate::blocks::parallel_card::model::{CardInputs, CardOutputs};
use crate::blocks::parallel_card::registers::{JOINTS, JOINTS_PER_SLAVE, SLAVES};
use crate::blocks::parallel_card::ParallelCard;
use crate::blocks::sync_fifo_bridge::model::SlaveBus;
use crate::host::servo::{FollowingError, ServoError};
use crate::sim::{quadrature_state, stepper, Ad669Bank, Backend, ServoMotor, SimError};

use super::super::{
    check_pose, forward, inverse, leg_inertia, CommandError, ForwardLimits, Pose, PoseError,
};
use super::control_dsp::{ControlDsp, Underrun};
use super::motor_dsp::{MotorDsp, MotorDspError, MotorDspSettings};
use super::trajectory::CartesianMotion;
use super::LEAD_PERIODS;

/// The legs' drives and motors (the plant).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LegPlant {
    /// The drive's gain, counts/s per V.
    pub counts_per_s_per_volt: f64,
    /// The velocity loop's time constant with the load at home, s; it
    /// grows with the leg's load Λ_ii at the platform's pose.
    pub time_constant_s: f64,
    /// Top speed, counts/s.
    pub max_velocity: f64,
    /// Peak acceleration, counts/s².
    pub max_acceleration: f64,
}

impl Default for LegPlant {
    /// 10 000 counts/s per V, 2 ms at home, ±100 000 counts/s,
    /// 2·10^6 counts/s² (the seed card's analog servo, [`ServoMotor`]).
    fn default() -> Self {
        Self {
            counts_per_s_per_volt: 10_000.0,
            time_constant_s: 0.002,
            max_velocity: 100_000.0,
            max_acceleration: 2.0e6,
        }
    }
}

/// A run's settings.
#[derive(Clone, Debug)]
pub struct CardSettings {
    /// The motor DSPs' settings (all three the same).
    pub motor: MotorDspSettings,
    /// The plant.
    pub plant: LegPlant,
    /// The card's clocks per period (the simulated clock is this times
    /// the period rate: a reduced clock keeps the run short).
    pub clocks_per_period: u64,
    /// Periods run after the motion ends, the legs settling.
    pub settle_periods: u64,
    /// The card's simulator.
    pub backend: Backend,
    /// The decoders' filter (`CARD_CONTROL.ENC_FILTER`).
    pub encoder_filter: u64,
    /// Leave out slave k's point for period n: (n, k).
    pub drop_point: Option<(u64, usize)>,
}

impl Default for CardSettings {
    /// [`MotorDspSettings::default`], [`LegPlant::default`], 250 clocks a
    /// 1 ms period (a 250 kHz card clock), 300 periods to settle, on
    /// Verilator, the decoders' reset filter (3), nothing left out.
    fn default() -> Self {
        Self {
            motor: MotorDspSettings::default(),
            plant: LegPlant::default(),
            clocks_per_period: 250,
            settle_periods: 300,
            backend: Backend::Verilator,
            encoder_filter: 3,
            drop_point: None,
        }
    }
}

/// Why a run did not start or could not go on.
#[derive(Debug, thiserror::Error)]
pub enum CardError {
    /// A point the machine cannot take, before any motion.
    #[error("period {period} (t = {seconds:.3} s): {source}")]
    Pose {
        /// Its period.
        period: u64,
        /// Its time.
        seconds: f64,
        /// Why.
        source: PoseError,
    },
    /// A point that does not fit its words, before any motion.
    #[error("period {period}: {source}")]
    Command {
        /// Its period.
        period: u64,
        /// Why.
        source: CommandError,
    },
    /// A loop setting.
    #[error(transparent)]
    Servo(#[from] ServoError),
    /// The simulator.
    #[error(transparent)]
    Sim(#[from] SimError),
    /// The period is too short for the control DSP's writes.
    #[error("{clocks} clocks a period: the control DSP needs {needed} for a point to every slave")]
    Period {
        /// Clocks per period.
        clocks: u64,
        /// Clocks its accesses take.
        needed: u64,
    },
}

/// What a run measured.
#[derive(Clone, Debug)]
pub struct CardRun {
    /// Periods run (releases).
    pub periods: u64,
    /// Clocks run.
    pub clocks: u64,
    /// Each leg's following error at the ticks, counts.
    pub following: [FollowingError; JOINTS],
    /// Each leg's count at the end.
    pub final_counts: [i64; JOINTS],
    /// Each leg's target at the end, counts from home.
    pub final_targets: [f64; JOINTS],
    /// Largest clocks between the slaves' data_ready rises of one release.
    pub skew: u64,
    /// Releases every slave saw.
    pub releases_seen: u64,
    /// The card's underrun, if one happened.
    pub underrun: Option<Underrun>,
    /// A motor DSP's bad point.
    pub motor_error: Option<MotorDspError>,
    /// Codes clamped at the DAC's range.
    pub saturated: u64,
    /// Each period's leg errors, commanded minus actual at the tick, counts.
    pub error_trace: Vec<[f64; JOINTS]>,
    /// The platform's pose at each tick, by the forward kinematics of the
    /// legs' encoder counts (the previous one where it did not converge).
    pub pose_trace: Vec<Pose>,
}

/// Control DSP writes per period: a point to each slave and SYNC, and the
/// fault read (2 clocks).
fn control_clocks() -> u64 {
    (super::super::WORDS * SLAVES) as u64 + 1 + 2
}

/// Runs `motion` on the card: every point is checked first; then the
/// control DSP primes the card, and each period's tick releases a point to
/// every motor DSP, whose codes drive the plants, whose encoders the card
/// counts.
pub fn run_card(
    motion: &dyn CartesianMotion,
    settings: &CardSettings,
) -> Result<CardRun, CardError> {
    let geometry = &settings.motor.geometry;
    let period_s = settings.motor.period_s;
    let motion_periods = (motion.duration() / period_s).ceil() as u64;
    let periods = motion_periods + settings.settle_periods;
    if settings.clocks_per_period < control_clocks() + 4 {
        return Err(CardError::Period {
            clocks: settings.clocks_per_period,
            needed: control_clocks() + 4,
        });
    }
    let points = (0..periods)
        .map(|n| {
            let point = motion.point(n, period_s, LEAD_PERIODS);
            check_pose(geometry, &point.pose).map_err(|source| CardError::Pose {
                period: n,
                seconds: (n + LEAD_PERIODS) as f64 * period_s,
                source,
            })?;
            point
                .encode()
                .map_err(|source| CardError::Command { period: n, source })?;
            Ok(point)
        })
        .collect::<Result<Vec<_>, CardError>>()?;

    let mut card = stepper(
        settings.backend,
        "parallel_card",
        ParallelCard::default(),
        None,
    )?;
    let mut control = ControlDsp::default();
    control.drop_point = settings.drop_point;
    let mut motors = (0..SLAVES)
        .map(|k| MotorDsp::new(k, settings.motor.clone()))
        .collect::<Result<Vec<_>, _>>()?;
    let p = settings.plant;
    let mut legs: Vec<ServoMotor> = (0..JOINTS)
        .map(|_| {
            ServoMotor::new(
                p.counts_per_s_per_volt,
                p.time_constant_s,
                p.max_velocity,
                p.max_acceleration,
            )
        })
        .collect();
    let mut dacs: Vec<Ad669Bank> = (0..SLAVES)
        .map(|_| Ad669Bank::new(JOINTS_PER_SLAVE))
        .collect();
    let home = inverse(geometry, &geometry.home);
    let home_load = leg_inertia(geometry, &geometry.home, &settings.motor.inertia);
    let mut plant_pose = geometry.home;
    let clock_s = period_s / settings.clocks_per_period as f64;
    let scale = settings.motor.scale;

    let mut inputs = CardInputs {
        reset: true,
        ..CardInputs::default()
    };
    card.step_vector(&inputs.to_vector())?;
    inputs.reset = false;
    let mut last_ready = 0u64;
    let mut rises: Vec<[Option<u64>; SLAVES]> = Vec::new();
    let mut clock = 0u64;
    let mut period = 0u64;
    let mut tick_at = u64::MAX;
    control
        .prime(&points[0], settings.encoder_filter)
        .map_err(|source| CardError::Command { period: 0, source })?;
    let mut error_trace = Vec::new();
    let mut pose_trace = Vec::new();
    loop {
        // The first tick once the priming writes are done; then one a period.
        if tick_at == u64::MAX && control.bus.idle() && clock > 2 {
            tick_at = clock;
        }
        let tick = tick_at != u64::MAX
            && clock >= tick_at
            && (clock - tick_at).is_multiple_of(settings.clocks_per_period);
        if tick && period == periods {
            break;
        }
        let m = control.bus.drive();
        inputs.m_address = m.address;
        inputs.m_write_data = m.write_data;
        inputs.m_write = m.write;
        inputs.m_read = m.read;
        for (k, dsp) in motors.iter_mut().enumerate() {
            let s = dsp.bus.drive();
            inputs.slaves[k] = SlaveBus {
                address: s.address,
                write_data: s.write_data,
                write: s.write,
                read: s.read,
            };
        }
        inputs.period_tick = tick;
        let (mut a, mut b) = (0u64, 0u64);
        for (j, leg) in legs.iter().enumerate() {
            let (pa, pb) = quadrature_state(leg.counts());
            a |= (pa as u64) << j;
            b |= (pb as u64) << j;
        }
        inputs.enc_a = a;
        inputs.enc_b = b;
        let out = CardOutputs::from_vector(&card.step_vector(&inputs.to_vector())?);

        control.bus.sample(out.m_read_data);
        control.clock();
        for (k, dsp) in motors.iter_mut().enumerate() {
            dsp.bus.sample(out.s_read_data[k]);
            dsp.clock(out.s_data_ready >> k & 1 != 0);
        }
        // A release raises data_ready in the tick's own clock.
        if tick {
            rises.push([None; SLAVES]);
        }
        let rose = out.s_data_ready & !last_ready;
        last_ready = out.s_data_ready;
        if let Some(release) = rises.last_mut() {
            for (k, at) in release.iter_mut().enumerate() {
                if rose >> k & 1 != 0 && at.is_none() {
                    *at = Some(clock);
                }
            }
        }
        for (k, bank) in dacs.iter_mut().enumerate() {
            bank.clock(
                out.dac_data >> (16 * k) & 0xFFFF,
                out.dac_cs_n >> (JOINTS_PER_SLAVE * k) & 0b11,
                out.dac_l1_n >> k & 1 != 0,
                out.dac_ldac >> k & 1 != 0,
            );
        }
        for (j, leg) in legs.iter_mut().enumerate() {
            let code = dacs[j / JOINTS_PER_SLAVE].code(j % JOINTS_PER_SLAVE);
            leg.advance(scale.volts(code), clock_s);
        }
        if tick {
            // The load each leg carries follows the platform's pose.
            let lengths: [f64; 6] = std::array::from_fn(|j| {
                home[j] + legs[j].counts() as f64 / settings.motor.counts_per_mm
            });
            if let Ok(f) = forward(geometry, &lengths, &plant_pose, &ForwardLimits::default()) {
                plant_pose = f.pose;
            }
            pose_trace.push(plant_pose);
            if let (Some(now), Some(home_load)) = (
                leg_inertia(geometry, &plant_pose, &settings.motor.inertia),
                home_load,
            ) {
                for (j, leg) in legs.iter_mut().enumerate() {
                    leg.time_constant_s = p.time_constant_s * now[j] / home_load[j];
                }
            }
            if period + 1 < periods {
                control
                    .after_tick(period, &points[period as usize + 1])
                    .map_err(|source| CardError::Command { period, source })?;
            }
            period += 1;
        }
        if tick {
            error_trace.push(std::array::from_fn(|j| {
                motors[j / JOINTS_PER_SLAVE].last_error[j % JOINTS_PER_SLAVE]
            }));
        }
        clock += 1;
    }
    let end = inverse(geometry, &points.last().expect("a point").pose);
    let cpm = settings.motor.counts_per_mm;
    let complete: Vec<[u64; SLAVES]> = rises
        .iter()
        .filter_map(|r| {
            let all: Option<Vec<u64>> = r.iter().copied().collect();
            all.map(|v| std::array::from_fn(|k| v[k]))
        })
        .collect();
    let skew = complete
        .iter()
        .map(|r| r.iter().max().unwrap() - r.iter().min().unwrap())
        .max()
        .unwrap_or(0);
    Ok(CardRun {
        periods,
        clocks: clock,
        following: std::array::from_fn(|j| {
            motors[j / JOINTS_PER_SLAVE].following[j % JOINTS_PER_SLAVE]
        }),
        final_counts: std::array::from_fn(|j| legs[j].counts()),
        final_targets: std::array::from_fn(|j| (end[j] - home[j]) * cpm),
        skew,
        releases_seen: complete.len() as u64,
        underrun: control.underrun,
        motor_error: motors.iter().find_map(|m| m.error.clone()),
        saturated: motors.iter().map(|m| m.saturated).sum(),
        error_trace,
        pose_trace,
    })
}
