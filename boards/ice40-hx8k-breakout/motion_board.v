// motion_board: a three-axis motion_controller on the iCE40-HX8K Breakout
// Board, reached by a DSP through its asynchronous external memory
// interface. Build (pins in motion_board.pcf):
//
//   yosys -p 'read_verilog motion_board.v ../../rtl-out/motion_controller.v \
//             ../../rtl-out/external_bus_adapter.v; \
//             synth_ice40 -dffe_min_ce_use 4 -top motion_board -json board.json'
//   nextpnr-ice40 --hx8k --package ct256 --pcf motion_board.pcf --json board.json --asc board.asc --freq 48
//   icepack board.asc board.bin
//
// The design fills most of the HX8K's logic cells (its test prints the
// figures; no number is kept here, where it would drift). Without
// `-dffe_min_ce_use 4` (an enable shared by fewer than 4 flip-flops goes
// into their LUTs rather than onto the clock enable, which the 8 cells of
// a tile share) nextpnr could not legalise the placement.
//
// Clocking: the board's 12 MHz oscillator feeds the PLL, which makes the
// one 48 MHz system clock (icepll -i 12 -o 48). Everything runs on it; the
// step timing registers count its clocks (20.8 ns) and the DSP strobes are
// synchronized inside external_bus_adapter (minimum strobe widths are in
// that file's header, in system clocks).
//
// Reset: held while the PLL is unlocked or RESET_N_PIN is low, released
// synchronously. At reset every axis output, every drive enable and every
// general output is low and the controller is stopped; the DSP then
// configures it through the register map in
// rtl-out/motion_controller_regs.h.
//
// Machine I/O: the limit, home, drive-alarm and E-stop inputs are active
// high (high = tripped, in alarm, stopped). The pin file pulls every one of
// them up, so normally-closed switches wired to ground read low while closed
// and an open or broken wire reads tripped (fail-safe). For normally-open
// wiring set INPUT_POLARITY (estop has no polarity bit: wire it NC). A
// machine without some switch disables it by register (IO_CONFIG) or ties
// the input low here; estop cannot be disabled. Each drive's enable is
// X/Y/Z_DRIVE_ENABLE, set per axis with IO_CONFIG.DRIVE_ENABLE and dropped
// by the controller on E-stop, watchdog expiry or that drive's alarm.

`default_nettype none

module motion_board (
    input  wire        CLK_12MHZ,
    input  wire        RESET_N_PIN,
    // DSP external memory interface
    input  wire        DSP_CS_N,
    input  wire        DSP_WE_N,
    input  wire        DSP_RD_N,
    input  wire [7:0]  DSP_A,
    inout  wire [31:0] DSP_D,
    output wire        DSP_IRQ_N,
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
    // General I/O (spindle, coolant, probe, ...)
    input  wire [7:0]  GPIO_IN,
    output wire [7:0]  GPIO_OUT,
    output wire        LED_RUNNING,
    output wire        LED_IRQ
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

    // Reset from an unlocked PLL or the button, synchronized. (The first
    // clocks after configuration need no reset: every flip-flop of the
    // controller powers up in its reset state.)
    reg [1:0] reset_sync;
    always @(posedge clock) begin
        reset_sync <= {reset_sync[0], ~(pll_locked & RESET_N_PIN)};
    end
    wire reset = reset_sync[1];

    // DSP bus -> synchronous register bus.
    wire [7:0]  reg_address;
    wire [31:0] reg_write_data;
    wire [31:0] reg_read_data;
    wire        reg_write;
    wire        reg_read;
    wire [31:0] dsp_data_out;
    wire        dsp_data_oe;
    assign DSP_D = dsp_data_oe ? dsp_data_out : 32'bz;
    external_bus_adapter dsp_bus (
        .clock(clock), .reset(reset),
        .cs_n(DSP_CS_N), .we_n(DSP_WE_N), .rd_n(DSP_RD_N),
        .address(DSP_A), .data_in(DSP_D),
        .data_out(dsp_data_out), .data_oe(dsp_data_oe),
        .bus_address(reg_address), .bus_write_data(reg_write_data),
        .bus_write(reg_write), .bus_read(reg_read), .bus_read_data(reg_read_data)
    );

    wire irq;
    wire running;
    wire active;
    // Bit k of each vector is axis k: X = 0, Y = 1, Z = 2.
    wire [2:0] step_a;
    wire [2:0] step_b;
    wire [2:0] drive_enable;
    motion_controller controller (
        .clock(clock), .reset(reset),
        .bus_address(reg_address), .bus_write_data(reg_write_data),
        .bus_write(reg_write), .bus_read(reg_read), .bus_read_data(reg_read_data),
        .irq(irq), .running(running), .active(active),
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
        // This build has no analog outputs (see seed_board.v for the
        // build that has): its DAC pins idle.
        .dac_data(), .dac_cs_n(), .dac_l1_n(), .dac_ldac()
    );

    assign {Z_STEP, Y_STEP, X_STEP} = step_a;
    assign {Z_DIR, Y_DIR, X_DIR}    = step_b;
    assign {Z_DRIVE_ENABLE, Y_DRIVE_ENABLE, X_DRIVE_ENABLE} = drive_enable;
    assign DSP_IRQ_N    = ~irq;
    // `active` (steps still leaving after `running` falls) is not brought
    // out: the drive enables are the controller's drive_enable outputs.
    assign LED_RUNNING  = running;
    assign LED_IRQ      = irq;
endmodule

`default_nettype wire
