//! `formal/external_bus_adapter.sv`: proofs and mutations.
