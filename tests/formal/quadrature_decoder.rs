//! `formal/quadrature_decoder.sv`: proofs and mutations.
