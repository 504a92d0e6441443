//! `formal/interrupt_controller.sv`: proofs and mutations.
