// narrow_bus_adapter (external_bus_adapter_16, external_bus_adapter_8): an
// N-bit external bus to W-bit registers, without tearing, as its datasheet
// states it (src/blocks/narrow_bus_adapter/mod.rs: the intro's two
// bullets, "Timing" and "What firmware must do", which refer to the
// BusSynchronizer's pin timing and `ready` rules,
// src/blocks/bus_synchronizer/mod.rs "Minimum timing at the pins" and
// "With `ready`", and to the WordAssembler's access order and outcomes,
// src/blocks/word_assembler/mod.rs "Required order, and what breaking it
// does").
//
// Spliced into the generated top module before its `endmodule` (see
// src/tools/formal/mod.rs): the contract names only the ports; the
// INDUCTION_INVARIANTS section names the submodules' registers.
//
// The pins, as in formal/external_bus_adapter.sv: the model sees them as
// the synchronizer's first flip-flops do, one sample per clock edge; a pin
// changing near an edge may be sampled either way, and a word changing
// there as any value: the free inputs cover all of it. "Active" is cs_n
// and the strobe both low.
//
// Environment: none assumed. Every input is free at every clock, `reset`
// included, and firmware may break the access order at will: the
// datasheet states the outcome of every broken order, and those outcomes
// are part of the contract. One rule of the datasheet is observed instead
// of assumed (the 32-bit adapter's proof no longer needs it; lifting it
// here needs new invariants and a later `ready` for a put-off read): no
// clock edge samples both
// strobes active (the synchronizer's datasheet forbids we_n and rd_n low
// together, "Bad input", and keeps the strobes high 2 t_clk between
// accesses, "Minimum timing at the pins"; the narrow adapter's "Timing"
// keeps that timing for every narrow access). The contract below holds
// while no edge since reset has sampled both; data_oe's holds always.
//
// The contract, per clock edge. A narrow access is a run of active samples
// at the pins, as for the 32-bit adapter: a narrow write ends at the edge
// that first samples its strobe inactive after two or more active
// samples, and takes effect 2 edges later (the synchronizer's bus_write
// clock) with the address and data sampled a clock before its last active
// sample; a narrow read is qualified by its second active sample and takes
// effect 2 edges later with the address sampled then. A narrow address is
// register address * (W/N) + part. In the clock a narrow access takes
// effect (the assembler adds no latency):
// * writes are atomic: a write of a lower part gives no bus_write; a write
//   of the highest part gives exactly one bus_write, with the register
//   address and the whole word (every lower part as last written, the
//   highest part from this write), if and only if every lower part of the
//   same register was written since the last highest-part write, reset or
//   lower-part write of another register; otherwise no bus_write at all
//   (a torn word never reaches the register).
// * reads never tear: a read of part 0, or of a higher part of a register
//   other than the one latched by the last bus_read, gives exactly one
//   bus_read with the register address; a read of a higher part of the
//   latched register gives none. The part returned is that of the
//   slave's word in the clock after the read's bus_read (which is the
//   latched word), or of the latched word: it is on data_out from the
//   second edge after the narrow read on, until the next answer.
// * order_error is high in the clock after a read of a higher part that
//   gave a bus_read, after a highest-part write that gave no bus_write,
//   and after a lower-part write while parts of another register were
//   held; low otherwise.
// * data_oe is !cs_n & !rd_n & we_n. (No narrow write and narrow read
//   take effect in one clock, so the above never has both bus strobes.)
// * ready ("With `ready`"): high while no strobe is active. A master
//   samples it no earlier than 3 t_clk after the strobe falls, that is
//   with the strobe sampled active at the last two edges or more; then,
//   while a write strobe is active, ready is high exactly from its third
//   active sample on (2 to 3 t_clk after the fall: two active samples are
//   through the synchronizer, so ending the strobe now gives its one
//   write); while a read strobe is active, ready is high exactly from its
//   sixth active sample on (6 to 7 t_clk after the fall), the edge that
//   puts the read's answer on data_out, provided every earlier read strobe
//   since reset lasted until its own answer was on data_out (six active
//   samples), as every strobe of a master that holds it until ready does.
//   (A read that ends early has its answer arrive during the next strobe,
//   and ready may show it: the datasheet's reason for its rules.)
// * reset: an edge in reset ends every access in progress, empties the
//   read latch and the holding register, and leaves every output 0.

localparam F_NA = $bits(address);
localparam F_N = $bits(data_in);
localparam F_A = $bits(bus_address);
localparam F_W = $bits(bus_write_data);
localparam F_PB = F_NA - F_A;
localparam F_PARTS = F_W / F_N;
localparam [F_PB-1:0] F_TOP = F_PARTS - 1;
localparam [F_PARTS-1:0] F_LOWER = {1'b0, {(F_PARTS-1){1'b1}}};

// `word` with part `part` replaced by `value`, and part `part` of `word`.
function automatic [F_W-1:0] f_with_part(input [F_W-1:0] word, input [F_PB-1:0] part, input [F_N-1:0] value);
    integer i;
    begin
        f_with_part = word;
        for (i = 0; i < F_PARTS; i = i + 1)
            if (part == i)
                f_with_part[i*F_N +: F_N] = value;
    end
endfunction
function automatic [F_N-1:0] f_part_of(input [F_W-1:0] word, input [F_PB-1:0] part);
    integer i;
    begin
        f_part_of = {F_N{1'b0}};
        for (i = 0; i < F_PARTS; i = i + 1)
            if (part == i)
                f_part_of = word[i*F_N +: F_N];
    end
endfunction

wire f_w_pin = !cs_n && !we_n;
wire f_r_pin = !cs_n && !rd_n;

// ---- The pins: narrow accesses (as formal/external_bus_adapter.sv) ----

// The samples of the last two edges since reset, index 0 the last one. An
// edge in reset samples nothing and forgets the earlier samples.
reg [1:0] f_w_seen = 2'b00;
reg [1:0] f_r_seen = 2'b00;
reg [F_NA-1:0] f_a_seen0 = {F_NA{1'b0}};
reg [F_NA-1:0] f_a_seen1 = {F_NA{1'b0}};
reg [F_N-1:0] f_d_seen0 = {F_N{1'b0}};
reg [F_N-1:0] f_d_seen1 = {F_N{1'b0}};
// Active samples in a row up to the last edge (saturating): the `ready`
// rules count them.
reg [1:0] f_w_run = 2'd0;
reg [2:0] f_r_run = 3'd0;

// This edge ends a narrow write, or qualifies a narrow read.
wire f_w_end = !f_w_pin && f_w_seen[0] && f_w_seen[1];
wire f_r_qual = f_r_pin && f_r_seen[0] && !f_r_seen[1];

// f_w_due[n]: a narrow write ended n edges before the last one, with its
// narrow address and data; f_r_due[n]: a narrow read qualified then.
reg [2:0] f_w_due = 3'b000;
reg [F_NA-1:0] f_w_addr0 = {F_NA{1'b0}};
reg [F_NA-1:0] f_w_addr1 = {F_NA{1'b0}};
reg [F_NA-1:0] f_w_addr2 = {F_NA{1'b0}};
reg [F_N-1:0] f_w_data0 = {F_N{1'b0}};
reg [F_N-1:0] f_w_data1 = {F_N{1'b0}};
reg [F_N-1:0] f_w_data2 = {F_N{1'b0}};
reg [2:0] f_r_due = 3'b000;
reg [F_NA-1:0] f_r_addr0 = {F_NA{1'b0}};
reg [F_NA-1:0] f_r_addr1 = {F_NA{1'b0}};
reg [F_NA-1:0] f_r_addr2 = {F_NA{1'b0}};

// The narrow access taking effect in this clock.
wire f_nw = f_w_due[2];
wire [F_PB-1:0] f_nw_part = f_w_addr2[F_PB-1:0];
wire [F_A-1:0] f_nw_reg = f_w_addr2[F_NA-1:F_PB];
wire f_nr = f_r_due[2];
wire [F_PB-1:0] f_nr_part = f_r_addr2[F_PB-1:0];
wire [F_A-1:0] f_nr_reg = f_r_addr2[F_NA-1:F_PB];

// ---- The words ----

// Write side: the lower parts held (one bit each), whose register, and the
// data last written to each part.
reg [F_PARTS-1:0] f_held = {F_PARTS{1'b0}};
reg [F_A-1:0] f_hold_reg = {F_A{1'b0}};
reg [F_W-1:0] f_hold_word = {F_W{1'b0}};
// Read side: the register latched by the last bus_read, and its word.
reg f_latch_valid = 1'b0;
reg [F_A-1:0] f_latch_reg = {F_A{1'b0}};
reg [F_W-1:0] f_latch_word = {F_W{1'b0}};
// The narrow read of the last clock (its answer is due in this one): from
// the slave (it gave a bus_read) or from the latch, and which part.
reg f_answer = 1'b0;
reg f_answer_bus = 1'b0;
reg [F_PB-1:0] f_answer_part = {F_PB{1'b0}};
reg [F_N-1:0] f_data_out = {F_N{1'b0}};
reg f_error = 1'b0;
reg f_edge_reset = 1'b0;
// The rule observed: no edge since reset sampled both strobes active.
reg f_legal = 1'b1;

wire f_commit = f_nw && f_nw_part == F_TOP && f_hold_reg == f_nw_reg && f_held == F_LOWER;
wire [F_W-1:0] f_commit_word = f_with_part(f_hold_word, F_TOP, f_w_data2);
wire f_latch_hit = f_latch_valid && f_latch_reg == f_nr_reg;
wire f_fresh = f_nr && (f_nr_part == {F_PB{1'b0}} || !f_latch_hit);
wire [F_W-1:0] f_answer_word = f_answer_bus ? bus_read_data : f_latch_word;
wire f_order_broken = (f_nr && f_nr_part != {F_PB{1'b0}} && !f_latch_hit)
    || (f_nw && f_nw_part == F_TOP && !f_commit)
    || (f_nw && f_nw_part != F_TOP && f_held != {F_PARTS{1'b0}} && f_hold_reg != f_nw_reg);

// ---- `ready`'s observer: every read strobe since reset lasted until its
// answer was on data_out (six active samples or more), as the strobes of a
// master that holds them until ready do. An observer, not an assumption:
// the other properties hold for every master. ----
reg f_reads_waited = 1'b1;

always @(posedge clock) begin
    f_edge_reset <= reset;
    f_legal <= reset || (f_legal && !(f_w_pin && f_r_pin));
    if (reset) begin
        f_w_seen <= 2'b00;
        f_r_seen <= 2'b00;
        f_a_seen0 <= {F_NA{1'b0}};
        f_a_seen1 <= {F_NA{1'b0}};
        f_d_seen0 <= {F_N{1'b0}};
        f_d_seen1 <= {F_N{1'b0}};
        f_w_run <= 2'd0;
        f_r_run <= 3'd0;
        f_w_due <= 3'b000;
        f_r_due <= 3'b000;
        f_held <= {F_PARTS{1'b0}};
        f_hold_reg <= {F_A{1'b0}};
        f_hold_word <= {F_W{1'b0}};
        f_latch_valid <= 1'b0;
        f_latch_reg <= {F_A{1'b0}};
        f_latch_word <= {F_W{1'b0}};
        f_answer <= 1'b0;
        f_answer_bus <= 1'b0;
        f_answer_part <= {F_PB{1'b0}};
        f_data_out <= {F_N{1'b0}};
        f_error <= 1'b0;
        f_reads_waited <= 1'b1;
    end else begin
        f_w_seen <= {f_w_seen[0], f_w_pin};
        f_r_seen <= {f_r_seen[0], f_r_pin};
        f_a_seen0 <= address;
        f_a_seen1 <= f_a_seen0;
        f_d_seen0 <= data_in;
        f_d_seen1 <= f_d_seen0;
        f_w_run <= !f_w_pin ? 2'd0 : f_w_run == 2'd3 ? 2'd3 : f_w_run + 2'd1;
        f_r_run <= !f_r_pin ? 3'd0 : f_r_run == 3'd6 ? 3'd6 : f_r_run + 3'd1;
        f_w_due <= {f_w_due[1:0], f_w_end};
        f_r_due <= {f_r_due[1:0], f_r_qual};
        if (f_nw) begin
            if (f_nw_part == F_TOP) begin
                f_held <= {F_PARTS{1'b0}};
            end else begin
                f_held <= (f_hold_reg == f_nw_reg ? f_held : {F_PARTS{1'b0}})
                    | ({{(F_PARTS-1){1'b0}}, 1'b1} << f_nw_part);
                f_hold_reg <= f_nw_reg;
                f_hold_word <= f_with_part(f_hold_word, f_nw_part, f_w_data2);
            end
        end
        if (f_fresh) begin
            f_latch_valid <= 1'b1;
            f_latch_reg <= f_nr_reg;
        end
        if (f_answer_bus)
            f_latch_word <= bus_read_data;
        f_answer <= f_nr;
        f_answer_bus <= f_fresh;
        if (f_nr)
            f_answer_part <= f_nr_part;
        if (f_answer)
            f_data_out <= f_part_of(f_answer_word, f_answer_part);
        f_error <= f_order_broken;
        if (!f_r_pin && f_r_run != 3'd0 && f_r_run != 3'd6)
            f_reads_waited <= 1'b0;
    end
    f_w_addr0 <= f_a_seen1;
    f_w_data0 <= f_d_seen1;
    f_w_addr1 <= f_w_addr0;
    f_w_data1 <= f_w_data0;
    f_w_addr2 <= f_w_addr1;
    f_w_data2 <= f_w_data1;
    f_r_addr0 <= address;
    f_r_addr1 <= f_r_addr0;
    f_r_addr2 <= f_r_addr1;
end

// The form of these assertions is z3's: z3 4.8 takes seconds, or minutes,
// to read models where the same condition guards many assertions through
// `if` (f_legal here, or the assembler's combinational bus_write and
// bus_read), so f_legal is in each assertion (`!f_legal || ...`), and the
// strobes' address and data are checked under the model's f_commit and
// f_fresh, which the assertions make equal to bus_write and bus_read.
always @(*) begin
    assert(data_oe == (!cs_n && !rd_n && we_n));
    // Atomic writes.
    assert(!f_legal || (bus_write == f_commit));
    if (f_commit) begin
        assert(!f_legal || (bus_address == f_nw_reg));
        assert(!f_legal || (bus_write_data == f_commit_word));
    end
    // Tear-free reads.
    assert(!f_legal || (bus_read == f_fresh));
    if (f_fresh)
        assert(!f_legal || (bus_address == f_nr_reg));
    assert(!f_legal || (data_out == f_data_out));
    assert(!f_legal || (order_error == f_error));
    // ready (combinational from the pins: the rule holds for them too).
    if (!f_w_pin && !f_r_pin)
        assert(!f_legal || (ready));
    if (f_w_pin && !f_r_pin && f_w_run >= 2'd2)
        assert(!f_legal || (ready == (f_w_run >= 2'd3)));
    if (f_r_pin && !f_w_pin && f_r_run >= 3'd2 && f_reads_waited)
        assert(!f_legal || (ready == (f_r_run >= 3'd6)));
    if (f_edge_reset) begin
        assert(bus_address == {F_A{1'b0}});
        assert(bus_write_data == {F_W{1'b0}});
    end
end

`ifdef INDUCTION_INVARIANTS
// INDUCTION INVARIANTS: the submodules' registers against the model. The
// properties sit in the top module and yosys 0.23 reads no hierarchical
// references, but its `flatten` connects a top-module wire named
// `\<instance>.<wire>` that has the `hierconn` attribute to that wire of
// the flattened instance: that is how these name the registers of `pins`
// (the synchronizer) and `words` (the assembler).

// The last four samples of each strobe (index 0 the last), as the
// synchronizer's stages hold them, and the read's run length one and two
// edges ago. (A misspelt `hierconn` name would be an undriven, free wire:
// its invariant would fail, not pass.)
reg [3:0] f_w_hist = 4'b0000;
reg [3:0] f_r_hist = 4'b0000;
reg [2:0] f_r_run1 = 3'd0;
reg [2:0] f_r_run2 = 3'd0;
always @(posedge clock) begin
    f_w_hist <= reset ? 4'b0000 : {f_w_hist[2:0], f_w_pin};
    f_r_hist <= reset ? 4'b0000 : {f_r_hist[2:0], f_r_pin};
    f_r_run1 <= reset ? 3'd0 : f_r_run;
    f_r_run2 <= reset ? 3'd0 : f_r_run1;
end

(* hierconn *) wire \pins.write_meta__q ;
(* hierconn *) wire \pins.write_sync__q ;
(* hierconn *) wire \pins.write_prev__q ;
(* hierconn *) wire \pins.write_older__q ;
(* hierconn *) wire \pins.read_meta__q ;
(* hierconn *) wire \pins.read_sync__q ;
(* hierconn *) wire \pins.read_prev__q ;
(* hierconn *) wire \pins.read_served__q ;
(* hierconn *) wire \pins.read_pending__q ;
(* hierconn *) wire \pins.read_answer__q ;
(* hierconn *) wire \pins.read_done__q ;
(* hierconn *) wire [F_NA-1:0] \pins.address_meta__q ;
(* hierconn *) wire [F_NA-1:0] \pins.address_sync__q ;
(* hierconn *) wire [F_NA-1:0] \pins.address_prev__q ;
(* hierconn *) wire [F_NA-1:0] \pins.address_older__q ;
(* hierconn *) wire [F_N-1:0] \pins.data_meta__q ;
(* hierconn *) wire [F_N-1:0] \pins.data_sync__q ;
(* hierconn *) wire [F_N-1:0] \pins.data_prev__q ;
(* hierconn *) wire [F_N-1:0] \pins.data_older__q ;
(* hierconn *) wire \pins.bus_write_reg__q ;
(* hierconn *) wire \pins.bus_read_reg__q ;
(* hierconn *) wire [F_NA-1:0] \pins.bus_address_reg__q ;
(* hierconn *) wire [F_N-1:0] \pins.bus_write_data_reg__q ;
(* hierconn *) wire [F_W-1:0] \words.holding__q ;
(* hierconn *) wire [7:0] \words.held_parts__q ;
(* hierconn *) wire [F_A-1:0] \words.holding_address__q ;
(* hierconn *) wire [F_W-1:0] \words.latch__q ;
(* hierconn *) wire [F_A-1:0] \words.latch_address__q ;
(* hierconn *) wire \words.latch_valid__q ;
(* hierconn *) wire \words.answer_from_bus__q ;
(* hierconn *) wire [F_NA-1:0] \words.answer_offset__q ;
// The block's registers are the model's while no edge since reset sampled
// both strobes (`!f_legal || ...`: see the contract's assertions); the
// model's own invariants hold always.
always @(*) begin
    // The synchronizer: its stages are the samples; a read is served once
    // its run has two samples in the stages; nothing is ever put off.
    assert(f_w_hist[1:0] == f_w_seen);
    assert(f_r_hist[1:0] == f_r_seen);
    assert(!f_legal || (\pins.write_meta__q == f_w_hist[0]));
    assert(!f_legal || (\pins.write_sync__q == f_w_hist[1]));
    assert(!f_legal || (\pins.write_prev__q == f_w_hist[2]));
    assert(!f_legal || (\pins.write_older__q == f_w_hist[3]));
    assert(!f_legal || (\pins.read_meta__q == f_r_hist[0]));
    assert(!f_legal || (\pins.read_sync__q == f_r_hist[1]));
    assert(!f_legal || (\pins.read_prev__q == f_r_hist[2]));
    assert(!f_legal || (\pins.read_served__q == (f_r_hist[2] && f_r_hist[3])));
    assert(!f_legal || (!\pins.read_pending__q ));
    assert(!f_legal || (\pins.address_meta__q == f_a_seen0));
    assert(!f_legal || (\pins.address_sync__q == f_a_seen1));
    assert(!f_legal || (\pins.data_meta__q == f_d_seen0));
    assert(!f_legal || (\pins.data_sync__q == f_d_seen1));
    assert(f_w_due[0] == (!f_w_hist[0] && f_w_hist[1] && f_w_hist[2]));
    assert(f_w_due[1] == (!f_w_hist[1] && f_w_hist[2] && f_w_hist[3]));
    assert(f_r_due[0] == (f_r_hist[0] && f_r_hist[1] && !f_r_hist[2]));
    assert(f_r_due[1] == (f_r_hist[1] && f_r_hist[2] && !f_r_hist[3]));
    if (f_w_due[0]) begin
        assert(!f_legal || (\pins.address_prev__q == f_w_addr0));
        assert(!f_legal || (\pins.data_prev__q == f_w_data0));
    end
    if (f_w_due[1]) begin
        assert(!f_legal || (\pins.address_older__q == f_w_addr1));
        assert(!f_legal || (\pins.data_older__q == f_w_data1));
    end
    if (f_r_due[0])
        assert(!f_legal || (\pins.address_meta__q == f_r_addr0));
    if (f_r_due[1])
        assert(!f_legal || (\pins.address_sync__q == f_r_addr1));
    assert(!f_legal || (\pins.bus_write_reg__q == f_w_due[2]));
    assert(!f_legal || (\pins.bus_read_reg__q == f_r_due[2]));
    if (f_w_due[2]) begin
        assert(!f_legal || (\pins.bus_address_reg__q == f_w_addr2));
        assert(!f_legal || (\pins.bus_write_data_reg__q == f_w_data2));
    end
    if (f_r_due[2])
        assert(!f_legal || (\pins.bus_address_reg__q == f_r_addr2));
    assert(!f_legal || (\pins.read_answer__q == f_answer));
    // The run counters against the samples.
    assert(f_w_run == (!f_w_hist[0] ? 2'd0 : !f_w_hist[1] ? 2'd1 : !f_w_hist[2] ? 2'd2 : 2'd3));
    assert(f_r_run == (!f_r_hist[0] ? 3'd0 : f_r_run1 == 3'd6 ? 3'd6 : f_r_run1 + 3'd1));
    assert(f_r_run1 == (!f_r_hist[1] ? 3'd0 : f_r_run2 == 3'd6 ? 3'd6 : f_r_run2 + 3'd1));
    assert(f_r_run2 <= 3'd6);
    assert(f_r_run2 == 3'd0 || f_r_hist[2]);
    if (f_r_hist[2])
        assert(f_r_run2 == 3'd1 || f_r_run2 >= 3'd2 && f_r_hist[3]);
    if (f_r_hist[2] && f_r_hist[3])
        assert(f_r_run2 >= 3'd2);
    // `ready` of a read: while every read so far waited, the read in
    // flight belongs to the run still going on, and the synchronizer's
    // "answered" flag is up once that run, seen by the stage two edges
    // behind, has four samples.
    if (f_reads_waited) begin
        if (f_r_due[1])
            assert(!f_legal || (f_r_hist[0]));
        if (f_r_due[2])
            assert(!f_legal || (f_r_hist[0] && f_r_hist[1]));
        if (f_answer)
            assert(!f_legal || (f_r_hist[0] && f_r_hist[1] && f_r_hist[2]));
        assert(!f_legal || (\pins.read_done__q == (f_r_run2 >= 3'd4)));
    end
    // The assembler: its registers are the model's.
    assert(!f_legal || (\words.holding__q == f_hold_word));
    assert(!f_legal || (\words.held_parts__q == {{(8-F_PARTS){1'b0}}, f_held}));
    assert(!f_legal || (\words.holding_address__q == f_hold_reg));
    assert(!f_legal || (\words.latch__q == f_latch_word));
    assert(!f_legal || (\words.latch_address__q == f_latch_reg));
    assert(!f_legal || (\words.latch_valid__q == f_latch_valid));
    assert(!f_legal || (\words.answer_from_bus__q == f_answer_bus));
    assert(!f_legal || (\words.answer_offset__q == {{(F_NA-F_PB){1'b0}}, f_answer_part} << $clog2(F_N)));
    // The model's own: the highest part is never held.
    assert(!f_held[F_TOP]);
end
`endif
