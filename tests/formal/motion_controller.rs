//! `formal/motion_controller.sv`: proofs and mutations.
