//! `formal/command_fifo.sv`: proofs and mutations.
