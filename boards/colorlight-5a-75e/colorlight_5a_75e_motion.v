// colorlight_5a_75e_motion: a six-axis motion_controller (K = 6) on the
// Colorlight 5A-75E LED receiver card (ECP5 LFE5U-25F, CABGA256), reached by
// a Raspberry Pi or a microcontroller on SPI. Pins in
// colorlight_5a_75e_motion.lpf, for hardware revision 8.2 (6.0 has the same
// pinout; 7.1 does not: it needs another pin file). build.sh runs the flow:
//
//   yosys -p 'read_verilog colorlight_5a_75e_motion.v motion_controller_k6.v \
//             ../../rtl-out/spi_bus_adapter.v; \
//             synth_ecp5 -top colorlight_5a_75e_motion \
//                        -json build/colorlight_5a_75e_motion.json'
//   nextpnr-ecp5 --25k --package CABGA256 --speed 6 \
//                --lpf colorlight_5a_75e_motion.lpf --freq 50 \
//                --json build/colorlight_5a_75e_motion.json \
//                --textcfg build/colorlight_5a_75e_motion.config
//   ecppack --compress build/colorlight_5a_75e_motion.config \
//           build/colorlight_5a_75e_motion.bit
//
// (the yowasp-* builds of the same tools). Speed grade 6 is the slower of
// the two cards' (6.0: -6, 8.2: -7). README.md has the wiring, and why the
// card's HUB75 buffers must be modified before any input works.
//
// Clocking: the card's 25 MHz oscillator (P6) feeds the EHXPLLL, which makes
// the one system clock of exactly 50 MHz (ecppll -i 25 -o 50: reference
// divider 1, feedback divider 2, output divider 12, VCO 600 MHz). Everything
// runs on it: the step timing registers count its clocks (20 ns), and the
// SPI pins are synchronized inside spi_bus_adapter, whose SCLK may be at
// most f_clk / 4 = 12.5 MHz (each SCLK phase at least 2 clocks).
//
// Reset: held while the PLL is unlocked or the card's button (J28, KEY+, R7,
// low while pressed) is pressed, released synchronously. At reset every axis
// output, every drive enable and every general output is low and the
// controller is stopped; the host then configures it through the register
// map in motion_controller_k6_regs.h (beside the controller).
//
// Machine I/O: the limit, home, drive-alarm, E-stop, probe and feed-hold
// inputs are active high (high = tripped, in alarm, stopped, held). The pin
// file pulls every one of them up, so normally-closed switches wired to
// ground read low while closed and an open or broken wire reads tripped
// (fail-safe) -- on a pin whose 74HC245 is bridged over. Behind a buffer
// turned round into an input (README.md) the FPGA's pull-up only pulls the
// buffer's output: the fail-safe pull-up then belongs on the connector side.
// For normally-open wiring set INPUT_POLARITY (estop has no polarity bit:
// wire it NC). A machine without some switch disables it by register
// (IO_CONFIG); estop cannot be disabled. Each drive's enable is
// DRIVE_ENABLE[k], set per axis with IO_CONFIG.DRIVE_ENABLE and dropped by
// the controller on E-stop, watchdog expiry or that drive's alarm.

`default_nettype none

module colorlight_5a_75e_motion (
    input  wire       CLK_25MHZ,
    // The card's button (J28, KEY+): low while pressed.
    input  wire       BUTTON_N,
    // The card's LED (DATA_LED-), lit by pulling its pin low: open drain.
    output wire       LED_N,
    // Host SPI (mode 0, SCLK at most 12.5 MHz) and its interrupt.
    input  wire       SPI_SCLK,
    input  wire       SPI_CS_N,
    input  wire       SPI_MOSI,
    output wire       SPI_MISO,
    output wire       SPI_IRQ_N,
    // Axes: bit k is axis k (X = 0, Y = 1, Z = 2, A = 3, B = 4, C = 5).
    output wire [5:0] STEP,
    output wire [5:0] DIR,
    output wire [5:0] DRIVE_ENABLE,
    input  wire [5:0] ENC_A,
    input  wire [5:0] ENC_B,
    input  wire [5:0] ENC_Z,
    // Machine I/O: switches and alarms (active high, pulled up: fail-safe).
    input  wire [5:0] LIMIT_POS,
    input  wire [5:0] LIMIT_NEG,
    input  wire [5:0] HOME,
    input  wire [5:0] ALARM,
    input  wire       ESTOP,
    // Touch probe or tool setter (pulled up: a probe closing to ground
    // trips on the falling edge, PROBE_CONTROL.EDGE = 1).
    input  wire       PROBE,
    // Feed hold (pulled up: a normally-closed button to ground holds when
    // pressed or when its wire breaks; HOLD_CONTROL.INVERT = 0).
    input  wire       FEED_HOLD,
    // General I/O (spindle, coolant, ...).
    input  wire [7:0] GPIO_IN,
    output wire [7:0] GPIO_OUT,
    // HUB75 pins 8 to 15 (E, A, B, C, D, CLK, STB, OE): wired to all 16
    // connectors at once, through their own buffers. Driven low, so every
    // connector's pins 8 to 15 sit at a defined level.
    output wire [7:0] HUB75_SHARED
);
    // 25 MHz -> 50 MHz (yowasp-ecppll -i 25 -o 50).
    wire clock;
    wire pll_locked;
    (* FREQUENCY_PIN_CLKI="25" *)
    (* FREQUENCY_PIN_CLKOP="50" *)
    (* ICP_CURRENT="12" *) (* LPF_RESISTOR="8" *) (* MFG_ENABLE_FILTEROPAMP="1" *) (* MFG_GMCREF_SEL="2" *)
    EHXPLLL #(
        .PLLRST_ENA("DISABLED"),
        .INTFB_WAKE("DISABLED"),
        .STDBY_ENABLE("DISABLED"),
        .DPHASE_SOURCE("DISABLED"),
        .OUTDIVIDER_MUXA("DIVA"),
        .OUTDIVIDER_MUXB("DIVB"),
        .OUTDIVIDER_MUXC("DIVC"),
        .OUTDIVIDER_MUXD("DIVD"),
        .CLKI_DIV(1),
        .CLKOP_ENABLE("ENABLED"),
        .CLKOP_DIV(12),
        .CLKOP_CPHASE(5),
        .CLKOP_FPHASE(0),
        .FEEDBK_PATH("CLKOP"),
        .CLKFB_DIV(2)
    ) pll (
        .RST(1'b0),
        .STDBY(1'b0),
        .CLKI(CLK_25MHZ),
        .CLKOP(clock),
        .CLKFB(clock),
        .PHASESEL0(1'b0),
        .PHASESEL1(1'b0),
        .PHASEDIR(1'b1),
        .PHASESTEP(1'b1),
        .PHASELOADREG(1'b1),
        .PLLWAKESYNC(1'b0),
        .ENCLKOP(1'b0), .ENCLKOS(1'b0), .ENCLKOS2(1'b0), .ENCLKOS3(1'b0),
        .CLKOS(), .CLKOS2(), .CLKOS3(), .CLKINTFB(), .REFCLK(), .INTLOCK(),
        .LOCK(pll_locked)
    );

    // Reset from an unlocked PLL or the button, synchronized. It starts
    // asserted at configuration, so the controller sees a reset before its
    // first clock edges after lock.
    reg [1:0] reset_sync = 2'b11;
    always @(posedge clock) begin
        reset_sync <= {reset_sync[0], ~(pll_locked & BUTTON_N)};
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
    wire        spi_frame_error;
    spi_bus_adapter host_spi (
        .clock(clock), .reset(reset),
        .sclk(SPI_SCLK), .cs_n(SPI_CS_N), .mosi(SPI_MOSI),
        .miso(spi_miso), .miso_oe(spi_miso_oe),
        .bus_address(reg_address), .bus_write_data(reg_write_data),
        .bus_write(reg_write), .bus_read(reg_read), .bus_read_data(reg_read_data),
        .frame_error(spi_frame_error)
    );
    // MISO is driven only while CS is low, so other devices may share the
    // line (this reaches the connector only where the buffer is bridged
    // over: README.md).
    assign SPI_MISO = spi_miso_oe ? spi_miso : 1'bz;

    wire irq;
    wire running;
    motion_controller_k6 controller (
        .clock(clock), .reset(reset),
        .bus_address(reg_address), .bus_write_data(reg_write_data),
        .bus_write(reg_write), .bus_read(reg_read), .bus_read_data(reg_read_data),
        // `active` (steps still leaving after `running` falls) is not
        // brought out: the drive enables are the controller's drive_enable.
        .irq(irq), .running(running), .active(),
        .enc_a(ENC_A), .enc_b(ENC_B), .enc_index(ENC_Z),
        .limit_pos(LIMIT_POS), .limit_neg(LIMIT_NEG),
        .home(HOME), .drive_alarm(ALARM),
        .estop(ESTOP),
        .gpio_in(GPIO_IN),
        .probe(PROBE),
        .feed_hold(FEED_HOLD),
        // No spindle encoder in this build (a SPINDLE build's spindle_* pins).
        .spindle_a(1'b0), .spindle_b(1'b0), .spindle_index(1'b0),
        .step_a(STEP), .step_b(DIR),
        .drive_enable(DRIVE_ENABLE),
        .gpio_out(GPIO_OUT),
        // No analog outputs and no laser on this card: their pins idle.
        .dac_data(), .dac_cs_n(), .dac_l1_n(), .dac_ldac(),
        .laser_pwm()
    );

    assign SPI_IRQ_N    = ~irq;
    assign HUB75_SHARED = 8'h00;

    // The LED is lit while the controller runs; a frame that failed (bad
    // CRC, SCLK too fast, cut short) flips it for 2^22 clocks (84 ms), so
    // errors show as flashes both when idle and when running.
    reg [21:0] error_flash = 22'd0;
    always @(posedge clock) begin
        if (reset) begin
            error_flash <= 22'd0;
        end else if (spi_frame_error) begin
            error_flash <= {22{1'b1}};
        end else if (error_flash != 22'd0) begin
            error_flash <= error_flash - 22'd1;
        end
    end
    wire led_lit = running ^ (error_flash != 22'd0);
    assign LED_N = led_lit ? 1'b0 : 1'bz;
endmodule

`default_nettype wire
