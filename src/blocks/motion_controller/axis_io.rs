//! The machine I/O of one axis: its limit, alarm and home logic, its drive
//! enable, its probe latches, and the upper half of its register window
//! (`IO_CONFIG` to `HOME_ACT_POSITION`, `PROBE_CMD_POSITION` and
//! `PROBE_ACT_POSITION`).
//!
//! Internal to [`super::axis::MotionAxis`]; the behavior is specified in
//! [`super`] ("Machine I/O and safety") and modelled by
//! [`super::io_model::AxisIoModel`].
//!
//! The block sees the axis's step path at two points: the candidate step
//! that enters the request register in this clock (`pulse`) and the
//! registered request the output stage takes in this clock (`request`),
//! plus the stage's pending count (`pending_forward`/`pending_backward`).
//! A step toward an enabled, active limit at any of the three is *cut*:
//! the axis gates the candidate and flushes its stage in this clock, and
//! the sticky trip flag it sets holds every axis stopped.
//!
//! Formal proof: `formal/motion_controller_axis_io.sv` (the blocked
//! directions, the cut and the trip flags; see the controller's datasheet,
//! "Formal proof").

use rust_hdl::prelude::*;

use super::registers::{axis, fields};

/// Machine I/O of one axis. See the [module documentation](self).
#[derive(LogicBlock)]
pub struct AxisIo {
    /// Rising-edge clock.
    pub clock: Signal<In, Clock>,
    /// Synchronous reset.
    pub reset: Signal<In, Bit>,
    /// The bus addresses this axis's I/O half (window and offset bit 4).
    pub selected: Signal<In, Bit>,
    /// Word offset within the I/O half.
    pub offset: Signal<In, Bits<4>>,
    /// Bus write strobe.
    pub write: Signal<In, Bit>,
    /// Bus write data.
    pub write_data: Signal<In, Bits<32>>,
    /// limit_pos, filtered and polarity-corrected.
    pub limit_forward: Signal<In, Bit>,
    /// limit_neg, filtered and polarity-corrected.
    pub limit_backward: Signal<In, Bit>,
    /// home, filtered and polarity-corrected.
    pub home: Signal<In, Bit>,
    /// home became active at the last edge.
    pub home_rise: Signal<In, Bit>,
    /// drive_alarm, filtered and polarity-corrected.
    pub alarm: Signal<In, Bit>,
    /// No E-stop latched (from the next edge on) and no watchdog expiry.
    pub drive_allowed: Signal<In, Bit>,
    /// The probe trips in this clock: latch both positions.
    pub probe_latch: Signal<In, Bit>,
    /// The stage's next step is forward.
    pub pending_forward: Signal<In, Bit>,
    /// The stage's next step is backward.
    pub pending_backward: Signal<In, Bit>,
    /// The stage takes a request in this clock...
    pub request: Signal<In, Bit>,
    /// ...in this direction.
    pub request_forward: Signal<In, Bit>,
    /// The interpolator offers a step to the request register in this clock...
    pub pulse: Signal<In, Bit>,
    /// ...in this direction.
    pub pulse_forward: Signal<In, Bit>,
    /// The commanded position now.
    pub cmd_position: Signal<In, Bits<32>>,
    /// The actual position now.
    pub act_position: Signal<In, Bits<32>>,
    /// The addressed I/O register, 0 when not selected.
    pub read_data: Signal<Out, Bits<32>>,
    /// Forward steps are blocked (enabled, active positive limit).
    pub block_forward: Signal<Out, Bit>,
    /// Backward steps are blocked.
    pub block_backward: Signal<Out, Bit>,
    /// A step toward a blocked limit is cut in this clock: flush the stage.
    pub cut: Signal<Out, Bit>,
    /// A limit trip is held.
    pub limit_held: Signal<Out, Bit>,
    /// An alarm trip is held.
    pub alarm_held: Signal<Out, Bit>,
    /// A home stop is held (HOME_SEEN with STOP_ON_HOME).
    pub home_held: Signal<Out, Bit>,
    /// A limit trip flag rises at this edge.
    pub limit_event: Signal<Out, Bit>,
    /// The alarm trip flag rises at this edge.
    pub alarm_event: Signal<Out, Bit>,
    /// HOME_SEEN rises at this edge.
    pub home_event: Signal<Out, Bit>,
    /// The drive_enable pin, registered.
    pub drive_enable: Signal<Out, Bit>,

    /// IO_CONFIG XOR its reset value, so that the flip-flops' power-up 0
    /// is the reset value (limits and alarms enabled before any reset).
    /// The bits above its fields are always 0 (yosys removes them).
    io_config_x: DFF<Bits<32>>,
    io_config: Signal<Local, Bits<32>>,
    limit_forward_tripped: DFF<Bit>,
    limit_backward_tripped: DFF<Bit>,
    alarm_tripped: DFF<Bit>,
    home_seen: DFF<Bit>,
    home_cmd: DFF<Bits<32>>,
    home_act: DFF<Bits<32>>,
    probe_cmd: DFF<Bits<32>>,
    probe_act: DFF<Bits<32>>,
    drive_enable_reg: DFF<Bit>,

    command: Signal<Local, Bit>,
    cut_forward: Signal<Local, Bit>,
    cut_backward: Signal<Local, Bit>,
    alarm_now: Signal<Local, Bit>,
    alarm_tripped_next: Signal<Local, Bit>,
    home_latch: Signal<Local, Bit>,
    status: Signal<Local, Bits<32>>,

    off_config: Constant<Bits<4>>,
    off_status: Constant<Bits<4>>,
    off_command: Constant<Bits<4>>,
    off_home_cmd: Constant<Bits<4>>,
    off_home_act: Constant<Bits<4>>,
    off_probe_cmd: Constant<Bits<4>>,
    off_probe_act: Constant<Bits<4>>,
    config_reset: Constant<Bits<32>>,
    config_mask: Constant<Bits<32>>,
    zero32: Constant<Bits<32>>,
    m_limit_pos: Constant<Bits<32>>,
    m_limit_neg: Constant<Bits<32>>,
    m_home: Constant<Bits<32>>,
    m_alarm: Constant<Bits<32>>,
    m_limit_pos_tripped: Constant<Bits<32>>,
    m_limit_neg_tripped: Constant<Bits<32>>,
    m_alarm_tripped: Constant<Bits<32>>,
    m_home_seen: Constant<Bits<32>>,
    m_drive_enable: Constant<Bits<32>>,
    /// IO_CONFIG's field masks.
    c_limit_enable: Constant<Bits<32>>,
    c_alarm_enable: Constant<Bits<32>>,
    c_stop_on_home: Constant<Bits<32>>,
    c_drive_enable: Constant<Bits<32>>,
    /// IO_COMMAND's field masks.
    k_clear_limits: Constant<Bits<32>>,
    k_clear_alarm: Constant<Bits<32>>,
    k_clear_home: Constant<Bits<32>>,
}

impl Default for AxisIo {
    fn default() -> Self {
        let c4 = |v: u32| Constant::new(((v - axis::IO_CONFIG) as u64).into());
        let m32 = |bit: u32| Constant::new((1u64 << bit).into());
        let m4u = |bit: u32| 1u64 << bit;
        Self {
            clock: Default::default(),
            reset: Default::default(),
            selected: Default::default(),
            offset: Default::default(),
            write: Default::default(),
            write_data: Default::default(),
            limit_forward: Default::default(),
            limit_backward: Default::default(),
            home: Default::default(),
            home_rise: Default::default(),
            alarm: Default::default(),
            drive_allowed: Default::default(),
            probe_latch: Default::default(),
            pending_forward: Default::default(),
            pending_backward: Default::default(),
            request: Default::default(),
            request_forward: Default::default(),
            pulse: Default::default(),
            pulse_forward: Default::default(),
            cmd_position: Default::default(),
            act_position: Default::default(),
            read_data: Default::default(),
            block_forward: Default::default(),
            block_backward: Default::default(),
            cut: Default::default(),
            limit_held: Default::default(),
            alarm_held: Default::default(),
            home_held: Default::default(),
            limit_event: Default::default(),
            alarm_event: Default::default(),
            home_event: Default::default(),
            drive_enable: Default::default(),
            io_config_x: Default::default(),
            io_config: Default::default(),
            limit_forward_tripped: Default::default(),
            limit_backward_tripped: Default::default(),
            alarm_tripped: Default::default(),
            home_seen: Default::default(),
            home_cmd: Default::default(),
            home_act: Default::default(),
            probe_cmd: Default::default(),
            probe_act: Default::default(),
            drive_enable_reg: Default::default(),
            command: Default::default(),
            cut_forward: Default::default(),
            cut_backward: Default::default(),
            alarm_now: Default::default(),
            alarm_tripped_next: Default::default(),
            home_latch: Default::default(),
            status: Default::default(),
            off_config: c4(axis::IO_CONFIG),
            off_status: c4(axis::IO_STATUS),
            off_command: c4(axis::IO_COMMAND),
            off_home_cmd: c4(axis::HOME_CMD_POSITION),
            off_home_act: c4(axis::HOME_ACT_POSITION),
            off_probe_cmd: c4(axis::PROBE_CMD_POSITION),
            off_probe_act: c4(axis::PROBE_ACT_POSITION),
            config_reset: Constant::new((fields::IO_CONFIG_RESET as u64).into()),
            config_mask: Constant::new(
                (m4u(fields::LIMIT_ENABLE)
                    | m4u(fields::ALARM_ENABLE)
                    | m4u(fields::STOP_ON_HOME)
                    | m4u(fields::DRIVE_ENABLE))
                .into(),
            ),
            zero32: Constant::new(0u64.into()),
            m_limit_pos: m32(fields::IO_LIMIT_POS),
            m_limit_neg: m32(fields::IO_LIMIT_NEG),
            m_home: m32(fields::IO_HOME),
            m_alarm: m32(fields::IO_DRIVE_ALARM),
            m_limit_pos_tripped: m32(fields::IO_LIMIT_POS_TRIPPED),
            m_limit_neg_tripped: m32(fields::IO_LIMIT_NEG_TRIPPED),
            m_alarm_tripped: m32(fields::IO_ALARM_TRIPPED),
            m_home_seen: m32(fields::IO_HOME_SEEN),
            m_drive_enable: m32(fields::IO_DRIVE_ENABLE),
            c_limit_enable: m32(fields::LIMIT_ENABLE),
            c_alarm_enable: m32(fields::ALARM_ENABLE),
            c_stop_on_home: m32(fields::STOP_ON_HOME),
            c_drive_enable: m32(fields::DRIVE_ENABLE),
            k_clear_limits: m32(fields::CLEAR_LIMITS),
            k_clear_alarm: m32(fields::CLEAR_ALARM),
            k_clear_home: m32(fields::CLEAR_HOME),
        }
    }
}

impl Logic for AxisIo {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(
            self,
            clock,
            io_config_x,
            limit_forward_tripped,
            limit_backward_tripped,
            alarm_tripped,
            home_seen,
            home_cmd,
            home_act,
            probe_cmd,
            probe_act,
            drive_enable_reg
        );
        self.command.next =
            self.write.val() & self.selected.val() & (self.offset.val() == self.off_command.val());

        // IO_CONFIG.
        self.io_config.next = self.io_config_x.q.val() ^ self.config_reset.val();
        if self.write.val() & self.selected.val() & (self.offset.val() == self.off_config.val()) {
            self.io_config_x.d.next =
                (self.write_data.val() & self.config_mask.val()) ^ self.config_reset.val();
        }
        if self.reset.val() {
            self.io_config_x.d.next = self.zero32.val();
        }

        // Limits: a step toward an enabled, active limit is cut wherever it
        // is on the step path: offered, requested or pending in the stage.
        self.block_forward.next = self.limit_forward.val()
            & ((self.io_config.val() & self.c_limit_enable.val()) != self.zero32.val());
        self.block_backward.next = self.limit_backward.val()
            & ((self.io_config.val() & self.c_limit_enable.val()) != self.zero32.val());
        self.cut_forward.next = self.block_forward.val()
            & (self.pending_forward.val()
                | (self.request.val() & self.request_forward.val())
                | (self.pulse.val() & self.pulse_forward.val()));
        self.cut_backward.next = self.block_backward.val()
            & (self.pending_backward.val()
                | (self.request.val() & !self.request_forward.val())
                | (self.pulse.val() & !self.pulse_forward.val()));
        self.cut.next = self.cut_forward.val() | self.cut_backward.val();
        self.limit_event.next = (self.cut_forward.val() & !self.limit_forward_tripped.q.val())
            | (self.cut_backward.val() & !self.limit_backward_tripped.q.val());
        // A trip on the clearing clock wins.
        if self.command.val()
            & ((self.write_data.val() & self.k_clear_limits.val()) != self.zero32.val())
        {
            self.limit_forward_tripped.d.next = false;
            self.limit_backward_tripped.d.next = false;
        }
        if self.cut_forward.val() {
            self.limit_forward_tripped.d.next = true;
        }
        if self.cut_backward.val() {
            self.limit_backward_tripped.d.next = true;
        }
        if self.reset.val() {
            self.limit_forward_tripped.d.next = false;
            self.limit_backward_tripped.d.next = false;
        }
        self.limit_held.next =
            self.limit_forward_tripped.q.val() | self.limit_backward_tripped.q.val();

        // Drive alarm: sticky while active, cleared only once it is gone.
        self.alarm_now.next = self.alarm.val()
            & ((self.io_config.val() & self.c_alarm_enable.val()) != self.zero32.val());
        self.alarm_tripped_next.next = self.alarm_tripped.q.val();
        if self.command.val()
            & ((self.write_data.val() & self.k_clear_alarm.val()) != self.zero32.val())
        {
            self.alarm_tripped_next.next = false;
        }
        if self.alarm_now.val() {
            self.alarm_tripped_next.next = true;
        }
        if self.reset.val() {
            self.alarm_tripped_next.next = false;
        }
        self.alarm_tripped.d.next = self.alarm_tripped_next.val();
        self.alarm_event.next = self.alarm_now.val() & !self.alarm_tripped.q.val();
        self.alarm_held.next = self.alarm_tripped.q.val();

        // Home: the first edge since CLEAR_HOME latches both positions of
        // this clock.
        self.home_latch.next = self.home_rise.val() & !self.home_seen.q.val();
        self.home_event.next = self.home_latch.val();
        if self.command.val()
            & ((self.write_data.val() & self.k_clear_home.val()) != self.zero32.val())
        {
            self.home_seen.d.next = false;
        }
        if self.home_latch.val() {
            self.home_seen.d.next = true;
            self.home_cmd.d.next = self.cmd_position.val();
            self.home_act.d.next = self.act_position.val();
        }
        if self.reset.val() {
            self.home_seen.d.next = false;
            self.home_cmd.d.next = self.zero32.val();
            self.home_act.d.next = self.zero32.val();
        }
        // Probe: the controller's trip strobe, on every axis at once.
        if self.probe_latch.val() {
            self.probe_cmd.d.next = self.cmd_position.val();
            self.probe_act.d.next = self.act_position.val();
        }
        if self.reset.val() {
            self.probe_cmd.d.next = self.zero32.val();
            self.probe_act.d.next = self.zero32.val();
        }
        self.home_held.next = self.home_seen.q.val()
            & ((self.io_config.val() & self.c_stop_on_home.val()) != self.zero32.val());

        // Drive enable: falls at the edge that latches the alarm or the
        // E-stop (the caller's drive_allowed is computed from the next state).
        self.drive_enable_reg.d.next = ((self.io_config.val() & self.c_drive_enable.val())
            != self.zero32.val())
            & self.drive_allowed.val()
            & !self.alarm_tripped_next.val();
        if self.reset.val() {
            self.drive_enable_reg.d.next = false;
        }
        self.drive_enable.next = self.drive_enable_reg.q.val();

        // Reads.
        self.status.next = self.zero32.val();
        if self.limit_forward.val() {
            self.status.next = self.status.val() | self.m_limit_pos.val();
        }
        if self.limit_backward.val() {
            self.status.next = self.status.val() | self.m_limit_neg.val();
        }
        if self.home.val() {
            self.status.next = self.status.val() | self.m_home.val();
        }
        if self.alarm.val() {
            self.status.next = self.status.val() | self.m_alarm.val();
        }
        if self.limit_forward_tripped.q.val() {
            self.status.next = self.status.val() | self.m_limit_pos_tripped.val();
        }
        if self.limit_backward_tripped.q.val() {
            self.status.next = self.status.val() | self.m_limit_neg_tripped.val();
        }
        if self.alarm_tripped.q.val() {
            self.status.next = self.status.val() | self.m_alarm_tripped.val();
        }
        if self.home_seen.q.val() {
            self.status.next = self.status.val() | self.m_home_seen.val();
        }
        if self.drive_enable_reg.q.val() {
            self.status.next = self.status.val() | self.m_drive_enable.val();
        }
        self.read_data.next = self.zero32.val();
        if self.selected.val() {
            if self.offset.val() == self.off_config.val() {
                self.read_data.next = self.read_data.val() | self.io_config.val();
            }
            if self.offset.val() == self.off_status.val() {
                self.read_data.next = self.read_data.val() | self.status.val();
            }
            if self.offset.val() == self.off_home_cmd.val() {
                self.read_data.next = self.read_data.val() | self.home_cmd.q.val();
            }
            if self.offset.val() == self.off_home_act.val() {
                self.read_data.next = self.read_data.val() | self.home_act.q.val();
            }
            if self.offset.val() == self.off_probe_cmd.val() {
                self.read_data.next = self.read_data.val() | self.probe_cmd.q.val();
            }
            if self.offset.val() == self.off_probe_act.val() {
                self.read_data.next = self.read_data.val() | self.probe_act.q.val();
            }
        }
    }
}
