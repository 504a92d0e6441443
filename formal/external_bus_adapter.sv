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
// included, and so is the "Bad input" of both strobes active in one sample
// (cs_n, we_n and rd_n all low): its outcome, as "Bad input" states it, is
// part of the contract below. A read run and a write run then overlap; the
// write is taken when it ends, as any write, and the read is issued once
// per run of active read samples, a clock later if the write's bus_write
// takes its clock (that is, if the write ends at the edge that qualifies
// the read), still with the address of its qualifying sample.
//
// The rest of the datasheet's minimum timing is what turns a legal access
// into a clean run of samples: a write strobe of 3 t_clk or more is a run
// of at least two active samples; 2 t_clk of strobe high between accesses
// puts at least one inactive sample between two runs; address and data
// stable for the 2 t_clk before the write strobe ends make the write's two
// last active samples clean, and a read address held 2 t_clk + t_h after
// rd_n falls makes the read's second active sample clean. The properties
// hold for EVERY sample sequence, so they need none of those rules as
// assumptions: a legal access gets exactly one strobe with its own address
// and data, and a runt (one active sample, a "Bad input") gets none.
//
// This proof found a bug under the bad input, since fixed in the
// synchronizer: after a read that overlapped a write's last sample and was
// put off a clock, a read starting one inactive sample later was never
// issued (read_served was not cleared on the clock the put-off read was
// issued).
//
// The contract, per clock edge (after the edge, outputs are registered):
// * write: the edge that first samples the write strobe inactive after at
//   least two active samples ends a write access; bus_write is high after
//   the second edge after it (at most 4 t_clk after we_n rises, with the
//   metastable sample), with bus_address and bus_write_data the address
//   and data sampled a clock before the access's last active sample. No
//   other bus_write.
// * read: the edge that samples the read strobe active a second time in a
//   row qualifies a read access (one per run of active samples);
//   bus_read is high after the second edge after it, with bus_address the
//   address sampled at the qualifying edge; if a write access ends at that
//   same edge (only possible after a sample with both strobes active), its
//   bus_write takes that clock and bus_read comes one clock later, with
//   the same address. No other bus_read, and never both strobes in one
//   clock.
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
// address it reads (f_r_addr<n>); f_r_late[n]: the same for a read put off
// a clock (a write ended at its qualifying edge).
reg [2:0] f_r_due = 3'b000;
reg [3:0] f_r_late = 4'b0000;
reg [F_A-1:0] f_r_addr0 = {F_A{1'b0}};
reg [F_A-1:0] f_r_addr1 = {F_A{1'b0}};
reg [F_A-1:0] f_r_addr2 = {F_A{1'b0}};
reg [F_A-1:0] f_r_addr3 = {F_A{1'b0}};
// The answer: bus_read was high in the clock before the last edge, so the
// slave's data is valid now; and data_out as the contract makes it.
reg f_answer = 1'b0;
reg [F_D-1:0] f_data_out = {F_D{1'b0}};
reg f_edge_reset = 1'b0;

always @(posedge clock) begin
    f_edge_reset <= reset;
    if (reset) begin
        f_w_seen <= 2'b00;
        f_r_seen <= 2'b00;
        f_a_seen0 <= {F_A{1'b0}};
        f_a_seen1 <= {F_A{1'b0}};
        f_d_seen0 <= {F_D{1'b0}};
        f_d_seen1 <= {F_D{1'b0}};
        f_w_due <= 3'b000;
        f_r_due <= 3'b000;
        f_r_late <= 4'b0000;
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
        f_r_due <= {f_r_due[1:0], f_r_qual && !f_w_end};
        f_r_late <= {f_r_late[2:0], f_r_qual && f_w_end};
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
    f_r_addr3 <= f_r_addr2;
end

always @(*) begin
    assert(data_oe == (!cs_n && !rd_n && we_n));
    assert(bus_write == f_w_due[2]);
    if (bus_write) begin
        assert(bus_address == f_w_addr2);
        assert(bus_write_data == f_w_data2);
    end
    assert(bus_read == (f_r_due[2] || f_r_late[3]));
    if (f_r_due[2])
        assert(bus_address == f_r_addr2);
    if (f_r_late[3])
        assert(bus_address == f_r_addr3);
    assert(!(bus_write && bus_read));
    assert(data_out == f_data_out);
    if (f_edge_reset) begin
        assert(bus_address == {F_A{1'b0}});
        assert(bus_write_data == {F_D{1'b0}});
    end
end

`ifdef INDUCTION_INVARIANTS
// INDUCTION INVARIANTS: none. Every register of the block is a function of
// the last six edges' inputs and outputs (the synchronizer's stages, the
// strobes, the read's "served" and "pending" flags, data_out, which the
// contract fixes), so k-induction of depth 6 closes on the contract alone.
`endif
