// motion_board: a three-axis motion_controller on the iCE40-HX8K Breakout
// Board, reached by a DSP through its asynchronous external memory
// interface. Build (pins in motion_board.pcf):
//
//   yosys -p 'read_verilog motion_board.v ../../rtl-out/motion_controller.v \
//             ../../rtl-out/external_bus_adapter.v; synth_ice40 -top motion_board -json board.json'
//   nextpnr-ice40 --hx8k --package ct256 --pcf motion_board.pcf --json board.json --asc board.asc --freq 48
//   icepack board.asc board.bin
//
// Clocking: the board's 12 MHz oscillator feeds the PLL, which makes the
// one 48 MHz system clock (icepll -i 12 -o 48). Everything runs on it; the
// step timing registers count its clocks (20.8 ns) and the DSP strobes are
// synchronized inside external_bus_adapter (minimum strobe widths are in
// that file's header, in system clocks).
//
// Reset: held while the PLL is unlocked or RESET_N_PIN is low, released
// synchronously. At reset every axis output is low and the controller is
// stopped; the DSP then configures it through the register map in
// rtl-out/motion_controller_regs.h.

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
    output wire        DRIVE_ENABLE,
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
    motion_controller controller (
        .clock(clock), .reset(reset),
        .bus_address(reg_address), .bus_write_data(reg_write_data),
        .bus_write(reg_write), .bus_read(reg_read), .bus_read_data(reg_read_data),
        .irq(irq), .running(running), .active(active),
        .enc_a__0(X_ENC_A), .enc_b__0(X_ENC_B), .enc_index__0(X_ENC_Z),
        .enc_a__1(Y_ENC_A), .enc_b__1(Y_ENC_B), .enc_index__1(Y_ENC_Z),
        .enc_a__2(Z_ENC_A), .enc_b__2(Z_ENC_B), .enc_index__2(Z_ENC_Z),
        .step_a__0(X_STEP), .step_b__0(X_DIR),
        .step_a__1(Y_STEP), .step_b__1(Y_DIR),
        .step_a__2(Z_STEP), .step_b__2(Z_DIR)
    );

    assign DSP_IRQ_N    = ~irq;
    // `active`, not `running`: the last steps of a move leave after the
    // periods stop.
    assign DRIVE_ENABLE = active;
    assign LED_RUNNING  = running;
    assign LED_IRQ      = irq;
endmodule

`default_nettype wire
