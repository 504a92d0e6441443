// spi_bus_adapter: no partial write, and no write on a bad CRC, as its
// datasheet states them (src/blocks/spi_bus_adapter/mod.rs and frame.rs:
// the frame, the bad input, the latency).
//
// Spliced into the generated module before its `endmodule` (see
// src/tools/formal/mod.rs): the contract names only the ports and a
// monitor that frames the pins itself; the INDUCTION_INVARIANTS section
// ties the monitor to the block's registers and takes one premise about
// the frame buffer (a rust-hdl RAM this file cannot see; its proof is
// `spi_bus_adapter_ram`, on the RAM itself).
//
// Environment: none assumed. Every input is free at every clock: SCLK,
// CS and MOSI at any rate (SCLK faster than the adapter allows, CS
// released anywhere), `reset` and `bus_read_data`.
//
// The monitor samples the pins as the datasheet says the adapter does:
// through two flip-flops each. A frame lasts from CS's sampled fall to its
// sampled rise; a bit is MOSI's sample at an SCLK sampled rise inside it;
// an SCLK level held fewer than 2 samples inside a frame makes the frame
// too fast. It keeps the frame's bit count, its running CRC-8 (0x07, MSB
// first), the command and address bytes and the header check (byte 2).
// A frame *passes* at the SCLK rise that ends its CRC byte (a write's
// byte 3 + 4N, a read's header byte 2), with CS still low, when that CRC
// leaves 0, a write's header CRC passed too, no reset is on, and the
// frame was never too fast.
//
// The contract, at the pins:
// * every bus strobe belongs to a frame that passed: after the pass, one
//   clock of nothing, then exactly its strobes, one a clock: a read
//   frame's SNAPSHOT write (address SNAPSHOT, data 0) if it asked for one,
//   then its N words at the frame's address and up: writes for a write
//   frame, reads for a read frame. No other clock has `bus_write` or
//   `bus_read`. So a frame that fails a CRC, is cut short (CS rising before
//   its CRC byte ended), or is too fast writes nothing, and one that
//   passes writes all of its words (a reset stops the strobes still due);
// * each written word is the frame's word, all 32 bits of it. The proof
//   follows one word place `f_j` of the frame (free, constant: any of the
//   16), which covers them all;
// * a written word never comes from a buffer read that collided with a
//   buffer write (the buffer carries `no_rw_check`: such a word is
//   undefined on iCE40);
// * a frame's strobes are over before the next frame passes.

// The pins as the adapter samples them.
reg f_sclk_1 = 1'b0;
reg f_sclk_2 = 1'b0;
reg f_sclk_3 = 1'b0;
reg f_sel_1 = 1'b0;
reg f_sel_2 = 1'b0;
reg f_sel_3 = 1'b0;
reg f_mosi_1 = 1'b0;
reg f_mosi_2 = 1'b0;
always @(posedge clock) begin
    f_sclk_1 <= sclk;
    f_sclk_2 <= f_sclk_1;
    f_sclk_3 <= f_sclk_2;
    f_sel_1 <= !cs_n;
    f_sel_2 <= f_sel_1;
    f_sel_3 <= f_sel_2;
    f_mosi_1 <= mosi;
    f_mosi_2 <= f_mosi_1;
end

// The frame.
reg f_in = 1'b0;
wire f_start = f_sel_2 && !f_sel_3;
wire f_stop = f_in && !f_sel_2;
wire f_edge = f_sclk_2 != f_sclk_3;
wire f_rise = f_in && f_sel_2 && f_sclk_2 && !f_sclk_3;
// Samples since SCLK's last edge, to 2 (2 at a frame's start).
reg [1:0] f_since = 2'd0;
reg f_fast = 1'b0;
wire f_fast_now = f_fast || (f_in && f_sel_2 && f_edge && !f_since[1]);
// Bits of the frame (to 1023), the last 32 bits, the CRC so far.
reg [9:0] f_bits = 10'd0;
reg [31:0] f_last_bits = 32'd0;
reg [7:0] f_crc = 8'd0;
reg [7:0] f_cmd = 8'd0;
reg [7:0] f_addr = 8'd0;
reg f_header_ok = 1'b0;
wire [31:0] f_last_bits_next = {f_last_bits[30:0], f_mosi_2};
wire [7:0] f_crc_next = {f_crc[6:0], 1'b0} ^ ((f_crc[7] ^ f_mosi_2) ? 8'h07 : 8'h00);
wire f_write_frame = f_cmd[7];
wire f_snapshot = !f_cmd[7] && f_cmd[6];
wire [4:0] f_words = {1'b0, f_cmd[3:0]} + 5'd1;
// The bit that ends the CRC byte: 8 (4 + 4N) - 1 for a write, 23 for a read.
wire [9:0] f_crc_bit = f_write_frame ? {1'b0, f_cmd[3:0], 5'd0} + 10'd63 : 10'd23;
wire f_pass = f_rise && !reset && f_bits == f_crc_bit && f_crc_next == 8'd0
    && !f_fast_now && (!f_write_frame || f_header_ok);

// The followed word place, and the frame's word there (bits 24 + 32 j on).
(* anyconst *) reg [3:0] f_j;
reg [31:0] f_word = 32'd0;
wire [9:0] f_word_last_bit = {1'b0, f_j, 5'd0} + 10'd55;

always @(posedge clock) begin
    if (f_edge)
        f_since <= 2'd1;
    else if (!f_since[1])
        f_since <= f_since + 2'd1;
    f_fast <= f_fast_now;
    if (f_rise) begin
        if (f_bits != 10'd1023)
            f_bits <= f_bits + 10'd1;
        f_last_bits <= f_last_bits_next;
        f_crc <= f_crc_next;
        if (f_bits == 10'd7)
            f_cmd <= f_last_bits_next[7:0];
        if (f_bits == 10'd15)
            f_addr <= f_last_bits_next[7:0];
        if (f_bits == 10'd23)
            f_header_ok <= f_crc_next == 8'd0;
        if (f_bits == f_word_last_bit)
            f_word <= f_last_bits_next;
    end
    if (f_start) begin
        f_in <= 1'b1;
        f_bits <= 10'd0;
        f_crc <= 8'd0;
        f_fast <= 1'b0;
        f_since <= 2'd2;
    end
    if (f_stop)
        f_in <= 1'b0;
    if (reset) begin
        f_in <= 1'b0;
        f_since <= 2'd0;
        f_fast <= 1'b0;
        f_bits <= 10'd0;
        f_last_bits <= 32'd0;
        f_crc <= 8'd0;
        f_cmd <= 8'd0;
        f_addr <= 8'd0;
        f_header_ok <= 1'b0;
    end
end

// The strobes a frame that passed still owes.
reg f_wait = 1'b0;
reg [4:0] f_left = 5'd0;
reg f_owe_snapshot = 1'b0;
reg f_owe_write = 1'b0;
reg [7:0] f_address = 8'd0;
reg [3:0] f_index = 4'd0;
wire f_due = f_left != 5'd0 && !f_wait;
always @(posedge clock) begin
    if (f_pass) begin
        f_wait <= 1'b1;
        f_left <= f_words + {4'd0, f_snapshot};
        f_owe_snapshot <= f_snapshot;
        f_owe_write <= f_write_frame;
        f_address <= f_addr;
        f_index <= 4'd0;
    end else if (f_wait) begin
        f_wait <= 1'b0;
    end else if (f_due) begin
        f_left <= f_left - 5'd1;
        if (f_owe_snapshot) begin
            f_owe_snapshot <= 1'b0;
        end else begin
            f_address <= f_address + 8'd1;
            f_index <= f_index + 4'd1;
        end
    end
    if (reset) begin
        f_wait <= 1'b0;
        f_left <= 5'd0;
        f_owe_snapshot <= 1'b0;
    end
end

// Clocks since the last frame passed (to 31), and whether a frame has
// started since: the strobes end within 19 clocks of a pass, and a new
// frame cannot reach its CRC byte that fast.
reg [4:0] f_age = 5'd31;
reg f_new = 1'b1;
always @(posedge clock) begin
    if (f_pass) begin
        f_age <= 5'd1;
        f_new <= 1'b0;
    end else begin
        if (f_age != 5'd31)
            f_age <= f_age + 5'd1;
        if (f_start)
            f_new <= 1'b1;
    end
    if (reset) begin
        f_age <= 5'd31;
        f_new <= 1'b1;
    end
end

// A buffer read at the last edge that collided with a buffer write.
reg f_collided = 1'b0;
always @(posedge clock)
    f_collided <= buffer__read_enable && buffer__write_enable
        && buffer__read_address == buffer__write_address;

always @(*) begin
    if (f_due && f_owe_snapshot) begin
        assert(bus_write && !bus_read);
        assert(bus_address == snapshot_address);
        assert(bus_write_data == 32'd0);
    end else if (f_due && f_owe_write) begin
        assert(bus_write && !bus_read);
        assert(bus_address == f_address);
        assert(!f_collided);
        if (f_index == f_j)
            assert(bus_write_data == f_word);
    end else if (f_due) begin
        assert(bus_read && !bus_write);
        assert(bus_address == f_address);
    end else begin
        assert(!bus_write && !bus_read);
    end
    if (f_pass)
        assert(f_left == 5'd0 && !f_wait);
end

`ifdef INDUCTION_INVARIANTS
// RAM PREMISE (assumed here, proved by `spi_bus_adapter_ram` on the same
// RAM with formal/command_fifo_ram.sv: an assume-guarantee pair, as for
// command_fifo). The followed word waits in the buffer, a rust-hdl RAM
// submodule whose array this file cannot name, so the induction takes the
// RAM's contract on its ports: an enabled read returns, one clock later,
// the word last written to its address before the read's edge. Stated for
// the followed place only.
reg [31:0] f_slot_word = 32'd0;
reg f_read_slot = 1'b0;
reg [31:0] f_read_word = 32'd0;
always @(posedge clock) begin
    if (buffer__write_enable && buffer__write_address == f_j)
        f_slot_word <= buffer__write_data;
    if (buffer__read_enable) begin
        f_read_slot <= buffer__read_address == f_j;
        f_read_word <= f_slot_word;
    end
end
always @(*) begin
    if (f_read_slot)
        assume(buffer__read_data == f_read_word);
end

// INDUCTION INVARIANTS: the block's registers against the monitor.
wire f_word_taken = f_write_frame && f_j < f_words && f_bits > f_word_last_bit;
wire f_engine_busy = remaining__q != 5'd0 || bus_read_reg__q || read_ack__q
    || write_stage__q;
always @(*) begin
    assert(sclk_meta__q == f_sclk_1);
    assert(sclk_sync__q == f_sclk_2);
    assert(sclk_last__q == f_sclk_3);
    assert(select_meta__q == f_sel_1);
    assert(select_sync__q == f_sel_2);
    assert(select_last__q == f_sel_3);
    assert(mosi_meta__q == f_mosi_1);
    assert(mosi_sync__q == f_mosi_2);
    assert(in_frame__q == f_in);
    assert(since_edge__q == f_since);
    assert(overspeed__q == f_fast);
    assert(crc_in__q == f_crc);
    assert(in_word__q == f_last_bits);
    if (f_bits != 10'd1023)
        assert({position__q, bit_count__q} == f_bits);
    else
        assert(position__q == 7'd127);
    if (f_bits >= 10'd8)
        assert(command__q == f_cmd);
    if (f_bits >= 10'd16) begin
        assert(address__q == f_addr);
        assert(crc_position__q == (f_cmd[7] ? 7'd7 + {1'b0, f_cmd[3:0], 2'b00} : 7'd2));
        assert(end_position__q == 7'd7 + {1'b0, f_cmd[3:0], 2'b00});
    end
    assert(geometry__q == (f_bits >= 10'd16));
    assert(complete__q == ((f_bits >= 10'd24 && (!f_cmd[7] || !f_header_ok))
                           || (f_bits >= 10'd16 && f_bits > f_crc_bit)));
    // The bus engine against the strobes owed, and how recent the pass.
    assert(f_left <= 5'd17);
    assert({1'b0, f_index} + f_left <= 5'd16 + {4'd0, f_owe_snapshot});
    if (f_wait)
        assert(f_age == 5'd1);
    if (f_due)
        assert(f_age >= 5'd2 && f_age + f_left <= 5'd19);
    if (f_engine_busy)
        assert(f_age <= 5'd19);
    // The frame that passed is past its CRC byte; a newer one has taken at
    // most a bit every 2 clocks since the pass (a rise needs SCLK's
    // sampled level low, then high).
    if (!f_new) begin
        assert(f_bits > f_crc_bit);
        if (f_wait || f_due) begin
            assert(f_owe_write == f_write_frame);
            assert({1'b0, f_index} + f_left == f_words + {4'd0, f_owe_snapshot});
        end
    end
    if (f_new && f_age != 5'd31)
        assert({f_bits, 1'b0} <= {6'd0, f_age} + {10'd0, f_sclk_3});
    if (f_wait) begin
        assert(remaining__q == f_left);
        assert(snapshot_pending__q == f_owe_snapshot);
        assert(writing__q == f_owe_write);
        assert(index__q == 4'd0);
        assert(op_address__q == f_address);
    end else if (f_due) begin
        assert(remaining__q == f_left - 5'd1);
        assert(!snapshot_pending__q);
        assert(writing__q == f_owe_write);
        if (f_owe_snapshot) begin
            assert(index__q == f_index);
            assert(op_address__q == f_address);
        end else begin
            assert(index__q == f_index + 4'd1);
            assert(op_address__q == f_address + 8'd1);
        end
    end else begin
        assert(remaining__q == 5'd0);
        assert(!snapshot_pending__q);
    end
    // A write frame's words wait in the buffer while the engine is idle.
    if (f_write_frame && f_bits >= 10'd16 && f_bits <= f_crc_bit)
        assert(!f_engine_busy && !f_wait && f_left == 5'd0);
    if (f_word_taken && f_bits <= f_crc_bit)
        assert(f_slot_word == f_word);
    if ((f_wait || f_due) && f_owe_write && f_index <= f_j
            && {1'b0, f_j} - {1'b0, f_index} < f_left)
        assert(f_slot_word == f_word);
end

`endif
