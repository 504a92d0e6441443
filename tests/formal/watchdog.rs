//! `formal/watchdog.sv`: proofs and mutations.
