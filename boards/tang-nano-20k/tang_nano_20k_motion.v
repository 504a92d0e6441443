// tang_nano_20k_motion: a four-axis motion_controller (K = 4) on the Sipeed
// Tang Nano 20K (Gowin GW2AR-LV18QN88C8/I7), reached by a Raspberry Pi or a
// microcontroller on SPI. Pins in tang_nano_20k_motion.cst; build.sh runs
// the flow:
//
//   yosys -p 'read_verilog tang_nano_20k_motion.v motion_controller_k4.v \
//             ../../rtl-out/spi_bus_adapter.v; \
//             synth_gowin -family gw2a -top tang_nano_20k_motion \
//                         -json build/tang_nano_20k_motion.json'
//   nextpnr-himbaechel --device GW2AR-LV18QN88C8/I7 --vopt family=GW2A-18C \
//             --vopt cst=tang_nano_20k_motion.cst --freq 54 \
//             --json build/tang_nano_20k_motion.json --write build/pnr.json
//   gowin_pack -d GW2A-18C --sspi_as_gpio \
//             -o build/tang_nano_20k_motion.fs build/pnr.json
//
// (the yowasp-* builds of yosys and nextpnr, gowin_pack from apycula).
//
// Pins: the two 20-pin headers carry 34 FPGA pins; 32 are used (25 and 26
// are left alone, README.md). K = 4 axes with step, direction and a drive
// enable each, positive and negative limit and home switches per axis, the
// E-stop, probe and feed hold, and the host's SPI with its interrupt. No
// encoders, drive alarms or general I/O: those inputs are tied inactive.
//
// Clocking: the board's 27 MHz oscillator (pin 4) feeds the rPLL, which
// makes the one system clock of exactly 54 MHz (gowin_pll -d GW2AR-18 -i 27
// -o 54: IDIV_SEL 0, FBDIV_SEL 1, ODIV_SEL 16; PFD 27 MHz, VCO 864 MHz).
// Everything runs on it: the step timing registers count its clocks
// (18.5 ns), and the SPI pins are synchronized inside spi_bus_adapter, whose
// SCLK may be at most f_clk / 4 = 13.5 MHz (each SCLK phase at least 2
// clocks).
//
// Reset: held while the PLL is unlocked, released synchronously. The
// board's buttons are not used. At reset every axis output and drive
// enable is low and the controller is stopped; the host then configures it
// through the register map in motion_controller_k4_regs.h (beside the
// controller).
//
// Machine I/O: the limit, home, E-stop, probe and feed-hold inputs are
// active high (high = tripped, stopped, held). The pin file pulls every one
// of them up, so normally-closed switches wired to ground read low while
// closed and an open or broken wire reads tripped (fail-safe). For
// normally-open wiring set INPUT_POLARITY (estop has no polarity bit: wire
// it NC). A machine without some switch disables it by register
// (IO_CONFIG); estop cannot be disabled. Each drive's enable is
// DRIVE_ENABLE[k], set per axis with IO_CONFIG.DRIVE_ENABLE and dropped by
// the controller on E-stop or watchdog expiry.

`default_nettype none

module tang_nano_20k_motion (
    input  wire       CLK_27MHZ,
    // Host SPI (mode 0, SCLK at most 13.5 MHz) and its interrupt.
    input  wire       SPI_SCLK,
    input  wire       SPI_CS_N,
    input  wire       SPI_MOSI,
    output wire       SPI_MISO,
    output wire       SPI_IRQ_N,
    // Axes: bit k is axis k (X = 0, Y = 1, Z = 2, A = 3).
    output wire [3:0] STEP,
    output wire [3:0] DIR,
    output wire [3:0] DRIVE_ENABLE,
    // Machine I/O: switches (active high, pulled up: fail-safe).
    input  wire [3:0] LIMIT_POS,
    input  wire [3:0] LIMIT_NEG,
    input  wire [3:0] HOME,
    input  wire       ESTOP,
    // Touch probe or tool setter (pulled up: a probe closing to ground
    // trips on the falling edge, PROBE_CONTROL.EDGE = 1).
    input  wire       PROBE,
    // Feed hold (pulled up: a normally-closed button to ground holds when
    // pressed or when its wire breaks; HOLD_CONTROL.INVERT = 0).
    input  wire       FEED_HOLD
);
    // 27 MHz -> 54 MHz (gowin_pll -d GW2AR-18 -i 27 -o 54).
    wire clock;
    wire pll_locked;
    rPLL #(
        .FCLKIN("27.0"),
        .IDIV_SEL(0),   // PFD 27 MHz
        .FBDIV_SEL(1),  // CLKOUT 27 MHz x 2 = 54 MHz
        .ODIV_SEL(16)   // VCO 54 MHz x 16 = 864 MHz (500 to 1250 MHz)
    ) pll (
        .CLKIN(CLK_27MHZ),
        .CLKOUT(clock),
        .LOCK(pll_locked),
        .CLKOUTP(), .CLKOUTD(), .CLKOUTD3(),
        .RESET(1'b0), .RESET_P(1'b0), .CLKFB(1'b0),
        .FBDSEL(6'b0), .IDSEL(6'b0), .ODSEL(6'b0),
        .PSDA(4'b0), .DUTYDA(4'b0), .FDLY(4'b0)
    );

    // Reset from an unlocked PLL, synchronized. It starts asserted at
    // configuration, so the controller sees a reset before its first clock
    // edges after lock.
    reg [1:0] reset_sync = 2'b11;
    always @(posedge clock) begin
        reset_sync <= {reset_sync[0], ~pll_locked};
    end
    wire reset = reset_sync[1];

    // Host SPI -> synchronous register bus.
    wire [7:0]  reg_address;
    wire [31:0] reg_write_data;
    wire [31:0] reg_read_data;
    wire        reg_write;
    wire        reg_read;
    wire        spi_miso;
    wire        spi_miso_oe;
    spi_bus_adapter host_spi (
        .clock(clock), .reset(reset),
        .sclk(SPI_SCLK), .cs_n(SPI_CS_N), .mosi(SPI_MOSI),
        .miso(spi_miso), .miso_oe(spi_miso_oe),
        .bus_address(reg_address), .bus_write_data(reg_write_data),
        .bus_write(reg_write), .bus_read(reg_read), .bus_read_data(reg_read_data),
        // No spare pin for an error LED: the host reads each frame's
        // verdict on MISO.
        .frame_error()
    );
    // MISO is driven only while CS is low, so other devices may share it.
    assign SPI_MISO = spi_miso_oe ? spi_miso : 1'bz;

    wire irq;
    motion_controller_k4 controller (
        .clock(clock), .reset(reset),
        .bus_address(reg_address), .bus_write_data(reg_write_data),
        .bus_write(reg_write), .bus_read(reg_read), .bus_read_data(reg_read_data),
        // `running` and `active` have no pin (no spare LED); the host reads
        // STATE.
        .irq(irq), .running(), .active(),
        // No encoders, no drive alarms, no general inputs on this board:
        // tied inactive (each axis's ACT_POSITION stays 0).
        .enc_a(4'b0), .enc_b(4'b0), .enc_index(4'b0),
        .limit_pos(LIMIT_POS), .limit_neg(LIMIT_NEG),
        .home(HOME), .drive_alarm(4'b0),
        .estop(ESTOP),
        .gpio_in(8'h00),
        .probe(PROBE),
        .feed_hold(FEED_HOLD),
        // No spindle encoder in this build (a SPINDLE build's spindle_* pins).
        .spindle_a(1'b0), .spindle_b(1'b0), .spindle_index(1'b0),
        .step_a(STEP), .step_b(DIR),
        .drive_enable(DRIVE_ENABLE),
        // No pin left for general outputs, analog outputs or a laser.
        .gpio_out(),
        .dac_data(), .dac_cs_n(), .dac_l1_n(), .dac_ldac(),
        .laser_pwm()
    );

    assign SPI_IRQ_N = ~irq;
endmodule

`default_nettype wire
