//! `formal/step_output.sv`: proofs and mutations.
