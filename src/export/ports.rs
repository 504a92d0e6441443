use rust_hdl::core::atom::{Atom, AtomKind};
use rust_hdl::core::prelude::*;

/// Direction of a top-level port.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PortDirection {
    /// Driven by the user's design.
    Input,
    /// Driven by the block.
    Output,
    /// Bidirectional.
    InOut,
}

impl PortDirection {
    /// `in`, `out` or `inout`, as in the port tables.
    pub fn as_str(self) -> &'static str {
        match self {
            PortDirection::Input => "in",
            PortDirection::Output => "out",
            PortDirection::InOut => "inout",
        }
    }
}

/// One top-level port of a block, as rust-hdl will write it to Verilog.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Port {
    /// Port name, identical in Rust and Verilog.
    pub name: String,
    /// Port direction.
    pub direction: PortDirection,
    /// Width in bits.
    pub width: usize,
}

/// The top-level ports of `block`, in declaration order.
pub fn top_ports(block: &dyn Block) -> Vec<Port> {
    let mut probe = TopPorts {
        depth: 0,
        ports: vec![],
    };
    block.accept("top", &mut probe);
    probe.ports
}

struct TopPorts {
    depth: usize,
    ports: Vec<Port>,
}

impl Probe for TopPorts {
    fn visit_start_scope(&mut self, _name: &str, _node: &dyn Block) {
        self.depth += 1;
    }
    fn visit_start_namespace(&mut self, _name: &str, _node: &dyn Block) {
        self.depth += 1;
    }
    fn visit_atom(&mut self, name: &str, signal: &dyn Atom) {
        if self.depth != 1 {
            return;
        }
        let direction = match signal.kind() {
            AtomKind::InputParameter => PortDirection::Input,
            AtomKind::OutputParameter | AtomKind::OutputPassthrough => PortDirection::Output,
            AtomKind::InOutParameter => PortDirection::InOut,
            _ => return,
        };
        // Arrays of signals are named `name$index` by rust-hdl; the export
        // writes `name__index`.
        self.ports.push(Port {
            name: name.replace('$', "__"),
            direction,
            width: signal.bits(),
        });
    }
    fn visit_end_namespace(&mut self, _name: &str, _node: &dyn Block) {
        self.depth -= 1;
    }
    fn visit_end_scope(&mut self, _name: &str, _node: &dyn Block) {
        self.depth -= 1;
    }
}
