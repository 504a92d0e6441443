// command_fifo's RAM (`HoldingRam`, as the FIFO instantiates it): the premise that formal/command_fifo.sv's induction takes, proved
// here on the RAM's own ports. Together the two files are an
// assume-guarantee proof of the FIFO: this file guarantees what that one
// assumes.
//
// Spliced into the generated RAM module before its `endmodule` (see
// src/tools/formal/mod.rs); the INDUCTION_INVARIANTS section names the
// RAM's array.
//
// Environment: none assumed; every input is free at every clock (the
// FIFO ties read_enable high; the proof leaves it free).
//
// The contract: an enabled read of an address returns, one clock later,
// the word last written to that address before the read's edge
// (read-first: a write on the same edge is not seen), or 0 if none was
// written since power-up (the array's initial value), and holds it until
// the next enabled read. Stated for one address, any address (`f_addr`,
// free but constant), which covers them all. (The read-first word of a
// collision is the Verilog's; the FIFO's RAM carries `no_rw_check`, so on
// iCE40 that word is undefined, and formal/command_fifo.sv proves the
// FIFO never shows it.)

localparam F_AW = $bits(write_address);
localparam F_DW = $bits(write_data);
(* anyconst *) reg [F_AW-1:0] f_addr;
reg [F_DW-1:0] f_word = {F_DW{1'b0}};
reg f_read = 1'b0;
reg [F_DW-1:0] f_read_word = {F_DW{1'b0}};
always @(posedge clock)
    if (write_enable && write_address == f_addr) f_word <= write_data;
always @(posedge clock) begin
    if (read_enable) begin
        f_read <= read_address == f_addr;
        f_read_word <= f_word;
    end
end
always @(*) if (f_read) assert(read_data == f_read_word);

`ifdef INDUCTION_INVARIANTS
// INDUCTION INVARIANT: the array holds the word last written.
always @(*) assert(mem[f_addr] == f_word);
`endif
