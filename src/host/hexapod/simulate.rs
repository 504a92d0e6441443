//! `motion-hdl simulate PROGRAM --kinematics hexapod`: a G-code program in
//! X Y Z (mm) and A B C (degrees) run on the parallel-machine card
//! ([`run_card`]) twice, with the load-scheduled PID and with the same
//! gains held fixed, and what each run measured.
//!
//! The program starts at the geometry's home pose: its X Y Z are the
//! platform's position in the base frame (Z 508 at the default home),
//! A B C its roll, pitch and yaw. It is read by the G-code interpreter
//! with the rotary axes on ([`Setup::rotary_axes`]), planned by
//! [`PosePlan`] (exact stop at every move) and checked period by period
//! before any motion: a pose outside the workspace, a leg beyond its
//! stroke or too fast, or a near-singular pose is an error naming the
//! program line.
//!
//! Each run reports the final **pose error** (the forward kinematics of
//! the legs' final encoder counts against the program's end pose; a solve
//! that does not converge is an error, never a pose), every leg's
//! **following error** (largest and RMS, counts, at the ticks) and the
//! **skew** between the slaves' `data_ready` rises at each release
//! (clocks; the card's contract is 0). An underrun or a motor DSP's fault
//! is an error naming the slave and the period.

use std::path::{Path, PathBuf};
use std::time::Instant;

use crate::host::gcode::{Ignored, Message, Setup};
use crate::host::simulation::{read_gcode_text, run_gcode};
use crate::host::tool_table::ToolTable;
use crate::plots::{plot_following_error, plot_path_xy};

use super::card::{
    run_card, CardRun, CardSettings, CartesianMotion, GainSchedule, PoseLimits, PosePlan,
};
use super::{forward, inverse, ForwardLimits, Geometry, Pose};

/// What to run and how.
#[derive(Clone, Debug)]
pub struct HexapodOptions {
    /// The mechanism (also the motor DSPs').
    pub geometry: Geometry,
    /// The planner's limits.
    pub limits: PoseLimits,
    /// The card, its DSPs and plant; its geometry and schedule are set
    /// from `geometry` and per run.
    pub card: CardSettings,
    /// A tool table for G43 (default none: no offsets).
    pub tools: Option<ToolTable>,
    /// Folder for the figures; `None` draws none.
    pub out_dir: Option<PathBuf>,
}

impl Default for HexapodOptions {
    /// The default geometry, [`PoseLimits::default`],
    /// [`CardSettings::default`], no tool table, no figures.
    fn default() -> Self {
        Self {
            geometry: Geometry::default(),
            limits: PoseLimits::default(),
            card: CardSettings::default(),
            tools: None,
            out_dir: None,
        }
    }
}

/// One run of the program with one gain schedule.
#[derive(Clone, Debug)]
pub struct ScheduleRun {
    /// Scheduled or fixed.
    pub schedule: GainSchedule,
    /// What the card run measured.
    pub run: CardRun,
    /// The pose the legs' final counts give, by the forward kinematics.
    pub final_pose: Pose,
    /// `final_pose` minus the program's end: X Y Z mm, A B C degrees.
    pub pose_error: [f64; 6],
    /// Seconds the run took.
    pub seconds: f64,
}

impl ScheduleRun {
    /// The largest following error over the legs, counts.
    pub fn max_following(&self) -> f64 {
        self.run.following.iter().map(|f| f.max).fold(0.0, f64::max)
    }

    /// Every leg within one count of its target at the end.
    pub fn ends_within_a_count(&self) -> bool {
        self.run
            .final_counts
            .iter()
            .zip(&self.run.final_targets)
            .all(|(&c, &t)| (c as f64 - t).abs() <= 1.0)
    }
}

/// What a hexapod simulation measured.
#[derive(Clone, Debug)]
pub struct HexapodReport {
    /// How the program ended, as a sentence.
    pub ending: String,
    /// Words with no effect on the motion, each once.
    pub ignored: Vec<Ignored>,
    /// The program's MSG, DEBUG and PRINT comments.
    pub messages: Vec<Message>,
    /// Moves and dwells planned.
    pub items: usize,
    /// The motion's duration, s.
    pub duration_s: f64,
    /// The program's end pose.
    pub end_pose: Pose,
    /// The load-scheduled PID ([`GainSchedule::Load`]).
    pub scheduled: ScheduleRun,
    /// The same gains at every pose ([`GainSchedule::Fixed`]).
    pub fixed: ScheduleRun,
    /// Figures written.
    pub figures: Vec<PathBuf>,
}

impl HexapodReport {
    /// The report's lines, as `simulate` prints them: `pose error`
    /// (per schedule), one `following error` line per leg (both
    /// schedules), `skew`, and what the schedule gains.
    pub fn summary(&self) -> Vec<String> {
        let mut lines = Vec::new();
        let p = self.end_pose;
        lines.push(format!(
            "program    {} moves and dwells, {:.3} s of motion; {}",
            self.items, self.duration_s, self.ending
        ));
        lines.push(format!(
            "end pose   X {:.4} Y {:.4} Z {:.4} mm  A {:.4} B {:.4} C {:.4} deg",
            p.position[0], p.position[1], p.position[2], p.angles[0], p.angles[1], p.angles[2]
        ));
        let runs = [&self.scheduled, &self.fixed];
        for r in runs {
            let e = r.pose_error;
            lines.push(format!(
                "pose error ({:9}) X {:+.4} Y {:+.4} Z {:+.4} mm  A {:+.5} B {:+.5} C {:+.5} deg",
                schedule_name(r.schedule),
                e[0],
                e[1],
                e[2],
                e[3],
                e[4],
                e[5]
            ));
        }
        for leg in 0..6 {
            let (s, f) = (
                self.scheduled.run.following[leg],
                self.fixed.run.following[leg],
            );
            lines.push(format!(
                "leg {leg} following error  scheduled max {:.2} RMS {:.2}  fixed max {:.2} RMS {:.2} counts",
                s.max, s.rms, f.max, f.rms
            ));
        }
        let skew = self.scheduled.run.skew.max(self.fixed.run.skew);
        lines.push(format!(
            "skew       {skew} clocks: the largest between the slaves' data_ready rises at a release ({} releases scheduled, {} fixed)",
            self.scheduled.run.releases_seen, self.fixed.run.releases_seen
        ));
        let (s, f) = (self.scheduled.max_following(), self.fixed.max_following());
        lines.push(format!(
            "scheduling largest following error {s:.2} counts with the load-scheduled PID, {f:.2} with its gains at home held fixed ({})",
            if s < f {
                format!("{:.0} % less", 100.0 * (1.0 - s / f))
            } else if s == f {
                "the same on this path".to_string()
            } else {
                format!("{:.0} % more", 100.0 * (s / f - 1.0))
            }
        ));
        for r in runs {
            lines.push(format!(
                "card       {} PID: {} clocks ({} periods) in {:.1} s, {} DAC codes clamped",
                schedule_name(r.schedule),
                r.run.clocks,
                r.run.periods,
                r.seconds,
                r.run.saturated
            ));
        }
        lines
    }
}

/// Runs the G-code program in `file` on the hexapod card (see the module
/// documentation). Every error is a sentence naming the file and the line,
/// the setting, or the slave and period.
pub fn simulate_hexapod(file: &Path, options: &HexapodOptions) -> Result<HexapodReport, String> {
    let geometry = &options.geometry;
    let located = |e: &dyn std::fmt::Display| format!("{}: {e}", file.display());
    let text = read_gcode_text(file)?;
    let setup = Setup {
        start: geometry.home.position,
        start_angles: geometry.home.angles,
        rotary_axes: true,
        tools: options.tools.clone(),
        ..Setup::default()
    };
    let (program, ending) = run_gcode(file, &text, &setup)?;
    let plan =
        PosePlan::plan(&program.toolpath, geometry, &options.limits).map_err(|e| located(&e))?;
    let period_s = options.card.motor.period_s;
    plan.check(geometry, period_s).map_err(|e| located(&e))?;
    let end_pose = plan.end_pose();
    let run = |schedule| {
        let mut settings = options.card.clone();
        settings.motor.geometry = geometry.clone();
        settings.motor.schedule = schedule;
        run_schedule(&plan, &settings, &end_pose, schedule).map_err(|e| located(&e))
    };
    let scheduled = run(GainSchedule::Load)?;
    let fixed = run(GainSchedule::Fixed)?;
    let mut figures = Vec::new();
    if let Some(dir) = &options.out_dir {
        figures = draw(dir, file, &plan, &scheduled, &fixed, period_s)?;
    }
    Ok(HexapodReport {
        ending,
        ignored: program.ignored,
        messages: program.messages,
        items: plan.items(),
        duration_s: plan.duration(),
        end_pose,
        scheduled,
        fixed,
        figures,
    })
}

/// One card run and its pose error; a fault the card or a DSP reports is
/// an error naming its slave and period.
fn run_schedule(
    plan: &PosePlan,
    settings: &CardSettings,
    end_pose: &Pose,
    schedule: GainSchedule,
) -> Result<ScheduleRun, String> {
    let started = Instant::now();
    let run = run_card(plan, settings).map_err(|e| e.to_string())?;
    let name = schedule_name(schedule);
    if let Some(u) = &run.underrun {
        let slaves = u.slave_list();
        let list: Vec<String> = slaves.iter().map(usize::to_string).collect();
        return Err(format!(
            "{name} PID: {} {} had no point at period {}: the card stopped every joint",
            if slaves.len() == 1 { "slave" } else { "slaves" },
            list.join(", "),
            u.period
        ));
    }
    if let Some(e) = &run.motor_error {
        return Err(format!("{name} PID: a motor DSP stopped: {e}"));
    }
    let geometry = &settings.motor.geometry;
    let home = inverse(geometry, &geometry.home);
    let lengths: [f64; 6] = std::array::from_fn(|j| {
        home[j] + run.final_counts[j] as f64 / settings.motor.counts_per_mm
    });
    let final_pose = forward(geometry, &lengths, end_pose, &ForwardLimits::default())
        .map_err(|e| format!("{name} PID: the final pose: {e}"))?
        .pose;
    let (f, e) = (
        final_pose.coordinates_degrees(),
        end_pose.coordinates_degrees(),
    );
    Ok(ScheduleRun {
        schedule,
        run,
        final_pose,
        pose_error: std::array::from_fn(|k| f[k] - e[k]),
        seconds: started.elapsed().as_secs_f64(),
    })
}

/// "scheduled" or "fixed".
pub fn schedule_name(schedule: GainSchedule) -> &'static str {
    match schedule {
        GainSchedule::Load => "scheduled",
        GainSchedule::Fixed => "fixed",
    }
}

fn draw(
    dir: &Path,
    file: &Path,
    plan: &PosePlan,
    scheduled: &ScheduleRun,
    fixed: &ScheduleRun,
    period_s: f64,
) -> Result<Vec<PathBuf>, String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    let stem = file
        .file_stem()
        .map_or("program".into(), |s| s.to_string_lossy().into_owned());
    let legs: Vec<(usize, String)> = (0..6).map(|j| (j, format!("leg {j}"))).collect();
    let legs: Vec<(usize, &str)> = legs.iter().map(|(j, n)| (*j, n.as_str())).collect();
    let mut figures = Vec::new();
    for run in [scheduled, fixed] {
        let name = schedule_name(run.schedule);
        let out = dir.join(format!("{stem}-hexapod-following-{name}.svg"));
        plot_following_error(
            &run.run.error_trace,
            &legs,
            &format!("Following error of the six legs, {name} PID"),
            period_s,
            &out,
        )
        .map_err(|e| e.to_string())?;
        figures.push(out);
    }
    let periods = scheduled.run.pose_trace.len();
    let planned: Vec<[f64; 3]> = (0..periods)
        .map(|n| plan.at(n as f64 * period_s).pose.position)
        .collect();
    // Tick n's pose answers the point for tick n.
    let measured: Vec<[f64; 3]> = scheduled
        .run
        .pose_trace
        .iter()
        .map(|p| p.position)
        .collect();
    let out = dir.join(format!("{stem}-hexapod-path.svg"));
    plot_path_xy(&planned, &measured, "mm", &out).map_err(|e| e.to_string())?;
    figures.push(out);
    Ok(figures)
}
