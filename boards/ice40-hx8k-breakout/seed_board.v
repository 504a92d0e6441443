// seed_board: the seed card's FPGA on the iCE40-HX8K Breakout Board. A
// TMS320F28335 drives a three-axis motion controller over its 16-bit
// external interface (XINTF, one zone, XREADY), and a CH365 PCI bridge
// (8 data bits, no wait input) shares a 1024 x 16 dual-port mailbox with
// the DSP. Build (pins in seed_board.pcf):
//
//   yosys -p 'read_verilog seed_board.v ../../rtl-out/host_links.v \
//             ../../rtl-out/motion_controller_servo.v; \
//             synth_ice40 -dffe_min_ce_use 4 -top seed_board -json seed.json'
//   nextpnr-ice40 --hx8k --package ct256 --pcf seed_board.pcf --json seed.json --asc seed.asc --freq 48
//   icepack seed.asc seed.bin
//
// The controller is motion_controller_servo: the seed's own fine
// interpolation (one DDA per axis) and its analog axes (three AD669s on
// one bus, below). The dual-period uniform generators are the build option
// this card drops: with them and the DACs the controller does not fit the
// HX8K within the 85 % the card must stay under. rtl-out/scaling-report.md
// ("The seed card") places this file with each controller build and gives
// each one's logic cells, share of the device and Fmax.
//
// Clocking and reset are motion_board.v's: 12 MHz into the PLL, one 48 MHz
// system clock, a synchronized reset while the PLL is unlocked or
// RESET_N_PIN is low. Every output is low at reset; the mailbox RAM powers
// up all zero and keeps its words through a reset.
//
// DSP (XINTF zone 6, 16-bit, XA[10:0]):
//   XA 0x000-0x1FF  controller registers: MC_<REG>_ADDR16 of
//                   motion_controller_servo_regs.h, low half first
//   XA 0x400-0x7FF  mailbox words 0-1023; word 1023 (XA 0x7FF) is the
//                   PC's ring to the DSP (DSP_MBOX_IRQ_N), word 1022
//                   (XA 0x7FE) the DSP's ring to the PC (PC_INT_N)
//   Program XTIMING6 with USEREADY = 1, READYMODE = 1 (asynchronous
//   XREADY): DSP_READY stretches every access to what the FPGA needs.
//   DSP_IRQ_N is the controller's interrupt (XINT1), DSP_MBOX_IRQ_N the
//   mailbox's (XINT2).
// PC (CH365, 8-bit, A[10:0]): mailbox word w at byte addresses 2w (low)
//   and 2w + 1 (high): read the low byte first (it latches the word),
//   write the low byte first (the high byte commits the word). PC_INT_N
//   goes to the CH365's interrupt input.
//
// Machine I/O is motion_board.v's: every limit, home, alarm and E-stop
// input active high and pulled up (fail-safe with normally-closed
// contacts to ground), one drive enable per axis, 8 general inputs and
// outputs.
//
// Analog axes: three AD669s share DAC_D, DAC_L1_N (first rank, active
// low) and DAC_LDAC (second rank, active high); each has its own chip
// select (DAC_CS_N[0] X, [1] Y, [2] Z). An axis with AXIS_CONFIG.ANALOG set
// drives its DAC with its FIFO entries as codes; the others step. The
// AD669's digital inputs are TTL-compatible, so the 3.3 V outputs drive
// them directly.

`default_nettype none

module seed_board (
    input  wire        CLK_12MHZ,
    input  wire        RESET_N_PIN,
    // F28335 XINTF
    input  wire        DSP_CS_N,
    input  wire        DSP_WE_N,
    input  wire        DSP_RD_N,
    input  wire [10:0] DSP_A,
    inout  wire [15:0] DSP_D,
    output wire        DSP_READY,
    output wire        DSP_IRQ_N,
    output wire        DSP_MBOX_IRQ_N,
    // CH365 local bus
    input  wire        PC_CS_N,
    input  wire        PC_WE_N,
    input  wire        PC_RD_N,
    input  wire [10:0] PC_A,
    inout  wire [7:0]  PC_D,
    output wire        PC_INT_N,
    // Axes
    output wire        X_STEP, X_DIR, Y_STEP, Y_DIR, Z_STEP, Z_DIR,
    input  wire        X_ENC_A, X_ENC_B, X_ENC_Z,
    input  wire        Y_ENC_A, Y_ENC_B, Y_ENC_Z,
    input  wire        Z_ENC_A, Z_ENC_B, Z_ENC_Z,
    // Machine I/O: switches and alarms (active high, pulled up: fail-safe)
    input  wire        X_LIMIT_POS, X_LIMIT_NEG, X_HOME, X_ALARM,
    input  wire        Y_LIMIT_POS, Y_LIMIT_NEG, Y_HOME, Y_ALARM,
    input  wire        Z_LIMIT_POS, Z_LIMIT_NEG, Z_HOME, Z_ALARM,
    input  wire        ESTOP,
    // Touch probe or tool setter (pulled up: a probe closing to ground
    // trips on the falling edge, PROBE_CONTROL.EDGE = 1).
    input  wire        PROBE,
    // Feed hold (pulled up: a normally-closed button to ground holds when
    // pressed or when its wire breaks; HOLD_CONTROL.INVERT = 0).
    input  wire        FEED_HOLD,
    output wire        X_DRIVE_ENABLE, Y_DRIVE_ENABLE, Z_DRIVE_ENABLE,
    // AD669 DACs (analog axes)
    output wire [15:0] DAC_D,
    output wire [2:0]  DAC_CS_N,
    output wire        DAC_L1_N,
    output wire        DAC_LDAC,
    // General I/O (spindle, coolant, probe, ...)
    input  wire [7:0]  GPIO_IN,
    output wire [7:0]  GPIO_OUT,
    output wire        LED_RUNNING,
    output wire        LED_MAILBOX
);
    // 12 MHz -> 48 MHz.
    wire clock;
    wire pll_locked;
    SB_PLL40_CORE #(
        .FEEDBACK_PATH("SIMPLE"),
        .DIVR(4'b0000),
        .DIVF(7'b0111111),
        .DIVQ(3'b100),
        .FILTER_RANGE(3'b001)
    ) pll (
        .REFERENCECLK(CLK_12MHZ),
        .PLLOUTGLOBAL(clock),
        .LOCK(pll_locked),
        .RESETB(1'b1),
        .BYPASS(1'b0)
    );

    reg [1:0] reset_sync;
    always @(posedge clock) begin
        reset_sync <= {reset_sync[0], ~(pll_locked & RESET_N_PIN)};
    end
    wire reset = reset_sync[1];

    // Both buses -> the controller's register bus and the mailbox.
    wire [7:0]  reg_address;
    wire [31:0] reg_write_data;
    wire [31:0] reg_read_data;
    wire        reg_write;
    wire        reg_read;
    wire [15:0] dsp_data_out;
    wire        dsp_data_oe;
    wire [7:0]  pc_data_out;
    wire        pc_data_oe;
    wire        irq_dsp;
    wire        irq_pc;
    assign DSP_D = dsp_data_oe ? dsp_data_out : 16'bz;
    assign PC_D  = pc_data_oe ? pc_data_out : 8'bz;
    // The order-error pulses and the mailbox's collision and overrun
    // pulses are for a design with a status register to latch them in;
    // this card has none (the tests show firmware that keeps the access
    // order never raises them).
    host_links links (
        .clock(clock), .reset(reset),
        .dsp_cs_n(DSP_CS_N), .dsp_we_n(DSP_WE_N), .dsp_rd_n(DSP_RD_N),
        .dsp_address(DSP_A), .dsp_data_in(DSP_D),
        .dsp_data_out(dsp_data_out), .dsp_data_oe(dsp_data_oe),
        .dsp_ready(DSP_READY), .dsp_order_error(),
        .pc_cs_n(PC_CS_N), .pc_we_n(PC_WE_N), .pc_rd_n(PC_RD_N),
        .pc_address(PC_A), .pc_data_in(PC_D),
        .pc_data_out(pc_data_out), .pc_data_oe(pc_data_oe),
        .pc_ready(), .pc_order_error(),
        .reg_address(reg_address), .reg_write_data(reg_write_data),
        .reg_write(reg_write), .reg_read(reg_read), .reg_read_data(reg_read_data),
        .irq_dsp(irq_dsp), .irq_pc(irq_pc),
        .mailbox_collision(), .mailbox_overrun()
    );

    wire irq;
    wire running;
    // Bit k of each vector is axis k: X = 0, Y = 1, Z = 2.
    wire [2:0] step_a;
    wire [2:0] step_b;
    wire [2:0] drive_enable;
    motion_controller_servo controller (
        .clock(clock), .reset(reset),
        .bus_address(reg_address), .bus_write_data(reg_write_data),
        .bus_write(reg_write), .bus_read(reg_read), .bus_read_data(reg_read_data),
        .irq(irq), .running(running), .active(),
        .enc_a({Z_ENC_A, Y_ENC_A, X_ENC_A}),
        .enc_b({Z_ENC_B, Y_ENC_B, X_ENC_B}),
        .enc_index({Z_ENC_Z, Y_ENC_Z, X_ENC_Z}),
        .limit_pos({Z_LIMIT_POS, Y_LIMIT_POS, X_LIMIT_POS}),
        .limit_neg({Z_LIMIT_NEG, Y_LIMIT_NEG, X_LIMIT_NEG}),
        .home({Z_HOME, Y_HOME, X_HOME}),
        .drive_alarm({Z_ALARM, Y_ALARM, X_ALARM}),
        .estop(ESTOP),
        .gpio_in(GPIO_IN),
        .probe(PROBE),
        .feed_hold(FEED_HOLD),
        // No spindle encoder on this card (a SPINDLE build's spindle_* pins).
        .spindle_a(1'b0), .spindle_b(1'b0), .spindle_index(1'b0),
        .step_a(step_a), .step_b(step_b),
        .drive_enable(drive_enable),
        .gpio_out(GPIO_OUT),
        .dac_data(DAC_D), .dac_cs_n(DAC_CS_N),
        .dac_l1_n(DAC_L1_N), .dac_ldac(DAC_LDAC)
    );

    assign {Z_STEP, Y_STEP, X_STEP} = step_a;
    assign {Z_DIR, Y_DIR, X_DIR}    = step_b;
    assign {Z_DRIVE_ENABLE, Y_DRIVE_ENABLE, X_DRIVE_ENABLE} = drive_enable;
    assign DSP_IRQ_N      = ~irq;
    assign DSP_MBOX_IRQ_N = ~irq_dsp;
    assign PC_INT_N       = ~irq_pc;
    assign LED_RUNNING    = running;
    assign LED_MAILBOX    = irq_dsp | irq_pc;
endmodule

`default_nettype wire
