// external_bus_adapter: exactly one bus strobe per access at the pins, with
// the access's address and data, as its datasheet states it
// (src/blocks/external_bus_adapter/mod.rs, the intro's two bullets,
// "Synchronous bus timing", "Minimum timing at the pins" and "Bad input";
// the block is the BusSynchronizer at 32 bits, whose datasheet
// src/blocks/bus_synchronizer/mod.rs says the same).
//
// Spliced into the generated top module before its `endmodule` (see
// src/tools/formal/mod.rs): the contract names only the ports; induction
// needs no invariants (see the INDUCTION_INVARIANTS section).
//
// The pins are asynchronous to the clock. The model sees them as the
// synchronizer's first flip-flops do: one sample per clock edge, the value
// the free inputs hold before that edge. A pin that changes near an edge
// may be sampled as either its old or its new value (metastability
// resolves one way or the other); free inputs cover every such choice, and
// a multi-bit address or data word sampled while it changes is any value.
// "Active" is cs_n and the strobe both low (write: we_n; read: rd_n).
//
// Environment: none assumed. Every input is free at every clock, `reset`
// included. One rule of the datasheet is observed instead: no clock edge
// samples both strobes active (cs_n, we_n and rd_n all low). "Bad input"
// says not to drive we_n and rd_n low together, and "Minimum timing at the
// pins" keeps the strobes high for 2 t_clk between accesses (a write and a
// read included), so the edge near one strobe's end cannot also see the
// other one active. The strobe contract below holds while no edge since
// reset has sampled both; data_oe's holds always (it keeps the pins
// undriven in exactly that bad case).
//
// The rest of the datasheet's minimum timing is what turns a legal access
// into a clean run of samples: a write strobe of 3 t_clk or more is a run
// of at least two active samples; 2 t_clk of strobe high between accesses
// puts at least one inactive sample between two runs; address and data
// stable for the 2 t_clk before the write strobe ends make the write's two
// last active samples clean, and a read address held 2 t_clk + t_h after
// rd_n falls makes the read's second active sample clean. The properties
// hold for EVERY sample sequence without both strobes in one sample, so
// they need none of those rules as assumptions: a legal access gets
// exactly one strobe with its own address and data, and a runt (one
// active sample, a "Bad input") gets none.
//
// Not covered: the strobes after the "Bad input" of we_n and rd_n low
// together, whose read the datasheet has issued once, a clock late if a
// write takes its clock. With the contract extended to it, the bounded
// check finds a read that overlaps a write's last sample, is put off a
// clock and lasts two samples: the one inactive sample after it is lost
// (read_served is not cleared in the clock the put-off read is issued), and
// a legal read that starts right after it is never issued. Without both
// strobes in one sample, no read is ever put off.
//
// The contract, per clock edge (after the edge, outputs are registered),
// while no edge since the last reset (or power-up) sampled both strobes:
// * write: the edge that first samples the write strobe inactive after at
//   least two active samples ends a write access; bus_write is high after
//   the second edge after it (at most 4 t_clk after we_n rises, with the
//   metastable sample), with bus_address and bus_write_data the address
//   and data sampled a clock before the access's last active sample. No
//   other bus_write.
// * read: the edge that samples the read strobe active a second time in a
//   row qualifies a read access (one per run of active samples);
//   bus_read is high after the second edge after it, with bus_address the
//   address sampled at the qualifying edge. No other bus_read, and never
//   both strobes in one clock.
//   So: one strobe per access, on both sides.
// * data_out: the slave's bus_read_data of the clock after bus_read is on
//   data_out from the next edge on, held until the next answer.
// * always: data_oe is !cs_n & !rd_n & we_n, combinationally.
// * reset: an edge in reset ends every access in progress (the samples it
//   and earlier edges took are forgotten, strobes due are dropped) and
//   leaves every output 0.

localparam F_A = $bits(address);
localparam F_D = $bits(data_in);

wire f_w_pin = !cs_n && !we_n;
wire f_r_pin = !cs_n && !rd_n;

// The samples of the last two edges since reset, index 0 the last one. An
// edge in reset samples nothing and forgets the earlier samples.
reg [1:0] f_w_seen = 2'b00;
reg [1:0] f_r_seen = 2'b00;
reg [F_A-1:0] f_a_seen0 = {F_A{1'b0}};
reg [F_A-1:0] f_a_seen1 = {F_A{1'b0}};
reg [F_D-1:0] f_d_seen0 = {F_D{1'b0}};
reg [F_D-1:0] f_d_seen1 = {F_D{1'b0}};

// This edge ends a write access (its sample is inactive, the two before it
// active), or qualifies a read access (its sample is the run's second).
wire f_w_end = !f_w_pin && f_w_seen[0] && f_w_seen[1];
wire f_r_qual = f_r_pin && f_r_seen[0] && !f_r_seen[1];

// Strobes due: f_w_due[n], a write access ended n edges before the last
// one, with the address and data it writes (f_w_addr<n>, f_w_data<n>).
reg [2:0] f_w_due = 3'b000;
reg [F_A-1:0] f_w_addr0 = {F_A{1'b0}};
reg [F_A-1:0] f_w_addr1 = {F_A{1'b0}};
reg [F_A-1:0] f_w_addr2 = {F_A{1'b0}};
reg [F_D-1:0] f_w_data0 = {F_D{1'b0}};
reg [F_D-1:0] f_w_data1 = {F_D{1'b0}};
reg [F_D-1:0] f_w_data2 = {F_D{1'b0}};
// f_r_due[n]: a read qualified n edges before the last one, with the
// address it reads (f_r_addr<n>).
reg [2:0] f_r_due = 3'b000;
reg [F_A-1:0] f_r_addr0 = {F_A{1'b0}};
reg [F_A-1:0] f_r_addr1 = {F_A{1'b0}};
reg [F_A-1:0] f_r_addr2 = {F_A{1'b0}};
// The answer: bus_read was high in the clock before the last edge, so the
// slave's data is valid now; and data_out as the contract makes it.
reg f_answer = 1'b0;
reg [F_D-1:0] f_data_out = {F_D{1'b0}};
reg f_edge_reset = 1'b0;
// The rule observed: no edge since reset sampled both strobes active.
reg f_legal = 1'b1;

always @(posedge clock) begin
    f_edge_reset <= reset;
    f_legal <= reset || (f_legal && !(f_w_pin && f_r_pin));
    if (reset) begin
        f_w_seen <= 2'b00;
        f_r_seen <= 2'b00;
        f_a_seen0 <= {F_A{1'b0}};
        f_a_seen1 <= {F_A{1'b0}};
        f_d_seen0 <= {F_D{1'b0}};
        f_d_seen1 <= {F_D{1'b0}};
        f_w_due <= 3'b000;
        f_r_due <= 3'b000;
        f_answer <= 1'b0;
        f_data_out <= {F_D{1'b0}};
    end else begin
        f_w_seen <= {f_w_seen[0], f_w_pin};
        f_r_seen <= {f_r_seen[0], f_r_pin};
        f_a_seen0 <= address;
        f_a_seen1 <= f_a_seen0;
        f_d_seen0 <= data_in;
        f_d_seen1 <= f_d_seen0;
        f_w_due <= {f_w_due[1:0], f_w_end};
        f_r_due <= {f_r_due[1:0], f_r_qual};
        f_answer <= bus_read;
        if (f_answer)
            f_data_out <= bus_read_data;
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

always @(*) begin
    assert(data_oe == (!cs_n && !rd_n && we_n));
    if (f_legal) begin
        assert(bus_write == f_w_due[2]);
        if (bus_write) begin
            assert(bus_address == f_w_addr2);
            assert(bus_write_data == f_w_data2);
        end
        assert(bus_read == f_r_due[2]);
        if (bus_read)
            assert(bus_address == f_r_addr2);
        assert(!(bus_write && bus_read));
        assert(data_out == f_data_out);
    end
    if (f_edge_reset) begin
        assert(bus_address == {F_A{1'b0}});
        assert(bus_write_data == {F_D{1'b0}});
    end
end

`ifdef INDUCTION_INVARIANTS
// INDUCTION INVARIANTS: none. Every register of the block is a function of
// the last five edges' inputs and outputs (the synchronizer's stages, the
// strobes, the read's "served" flag, data_out, which the contract fixes),
// so k-induction of depth 5 closes on the contract alone.
`endif
