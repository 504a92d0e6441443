//! The compiled simulation backend (`motion_hdl::sim::CompiledModel`):
//! ports wider than 64 bits, port names Verilator mangles, the power-up
//! state, the build cache, both backends behind one `Stepper`, and a VCD
//! from Verilator's tracer. The per-module agreement with the rust-hdl
//! simulation is in every block's cross-simulation test.

use motion_hdl::blocks::freq_divider::FreqDivider;
use motion_hdl::sim::{stepper, Backend, CompiledModel, Harness, VectorPorts};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use rust_hdl::prelude::*;

/// A 70-bit register beside two 8-bit lanes that export as `lane__0` and
/// `lane__1` (Verilator's C++ calls them `lane___05F0`, `lane___05F1`), and a
/// counter that starts from its `initial` value.
#[derive(LogicBlock)]
struct WideAndMangled {
    clock: Signal<In, Clock>,
    wide_in: Signal<In, Bits<70>>,
    lane: [Signal<In, Bits<8>>; 2],
    wide_out: Signal<Out, Bits<70>>,
    sum: Signal<Out, Bits<8>>,
    count_out: Signal<Out, Bits<8>>,
    wide: DFF<Bits<70>>,
    count: DFF<Bits<8>>,
    one: Constant<Bits<8>>,
}

impl WideAndMangled {
    fn new() -> Self {
        Self {
            clock: Default::default(),
            wide_in: Default::default(),
            lane: Default::default(),
            wide_out: Default::default(),
            sum: Default::default(),
            count_out: Default::default(),
            wide: Default::default(),
            count: Default::default(),
            one: Constant::new(1u64.into()),
        }
    }
}

impl Logic for WideAndMangled {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, wide, count);
        self.wide.d.next = self.wide_in.val();
        self.count.d.next = self.count.q.val() + self.one.val();
        self.wide_out.next = self.wide.q.val();
        self.sum.next = self.lane[0].val() + self.lane[1].val() + self.count.q.val();
        self.count_out.next = self.count.q.val();
    }
}

fn bits70(words: [u64; 2]) -> Bits<70> {
    let mut value: Bits<70> = (words[1] & 0x3f).into();
    value = value << 64;
    value | Bits::<70>::from(words[0])
}

#[test]
fn wide_ports_and_mangled_names_match_the_rust_simulation() {
    let mut block = WideAndMangled::new();
    let mut model = CompiledModel::from_block("wide_and_mangled", &mut block, false)
        .unwrap_or_else(|e| panic!("{e}"));
    let names: Vec<&str> = model.inputs().iter().map(|s| s.name.as_str()).collect();
    assert_eq!(names, ["wide_in", "lane__0", "lane__1"]);
    assert_eq!(model.inputs()[0].width, 70);

    let mut rust = WideAndMangled::new();
    rust.connect_all();
    let mut rng = StdRng::seed_from_u64(70);
    let (wide_in, lane0, lane1) = (0, 1, 2);
    let (wide_out, sum, count) = (
        model.output_index("wide_out").unwrap(),
        model.output_index("sum").unwrap(),
        model.output_index("count_out").unwrap(),
    );
    for cycle in 0..2000u64 {
        // Bits above a port's width are dropped, as the Rust side drops them.
        let words = [rng.gen::<u64>(), rng.gen::<u64>()];
        let lanes = [rng.gen::<u64>() & 0x1ff, rng.gen::<u64>() & 0xff];
        model.set_words(wide_in, &words);
        model.set(lane0, lanes[0]);
        model.set(lane1, lanes[1]);
        model.cycle();

        rust.wide_in.next = bits70(words);
        rust.lane[0].next = (lanes[0] & 0xff).into();
        rust.lane[1].next = lanes[1].into();
        step_rust(&mut rust);
        let expected = rust.wide_out.val();
        let got = model.get_words(wide_out);
        assert_eq!(
            bits70([got[0], got[1]]),
            expected,
            "cycle {cycle}: wide_out"
        );
        assert_eq!(got[1] >> 6, 0, "cycle {cycle}: bits above 70 are clean");
        assert_eq!(
            model.get(sum),
            rust.sum.val().to_u64(),
            "cycle {cycle}: sum"
        );
        assert_eq!(
            model.get(count),
            (cycle + 1) & 0xff,
            "cycle {cycle}: count from power-up 0"
        );
    }
}

/// One clock of a bare rust-hdl block (it has a 70-bit port, which the
/// harness's u64 vectors cannot carry): settle, rise, settle, fall, settle.
fn step_rust(block: &mut WideAndMangled) {
    let settle = |b: &mut WideAndMangled| {
        for _ in 0..100 {
            b.update_all();
            if !b.has_changed() {
                return;
            }
        }
        panic!("no settle");
    };
    settle(block);
    block.clock.next = Clock { clk: true };
    settle(block);
    block.clock.next = Clock { clk: false };
    settle(block);
}

#[test]
fn a_second_build_of_the_same_verilog_comes_from_the_cache() {
    let build = || {
        let started = std::time::Instant::now();
        CompiledModel::from_block("cache_probe", &mut FreqDivider::<9>::default(), false)
            .unwrap_or_else(|e| panic!("{e}"));
        started.elapsed()
    };
    build();
    let again = build();
    // A compile takes seconds; a cache hit only hashes and loads.
    assert!(again.as_millis() < 1500, "second build took {again:?}");
}

/// The same stimulus through `Stepper` on both backends: identical outputs
/// on every cycle, and the same cycle count.
#[test]
fn both_backends_step_identically_through_one_interface() {
    let mut rng = StdRng::seed_from_u64(0xbac);
    let stimulus: Vec<Vec<u64>> = (0..20_000)
        .map(|i| {
            vec![
                (i % 5000 == 0) as u64,
                rng.gen_bool(0.9) as u64,
                rng.gen_range(0..9),
            ]
        })
        .collect();
    let mut sims: Vec<_> = Backend::ALL
        .iter()
        .map(|&b| stepper(b, "freq_divider", FreqDivider::<16>::default(), None).unwrap())
        .collect();
    assert_eq!(FreqDivider::<16>::output_names().len(), 1);
    for (cycle, inputs) in stimulus.iter().enumerate() {
        let a = sims[0].step_vector(inputs).unwrap();
        let b = sims[1].step_vector(inputs).unwrap();
        assert_eq!(
            a,
            b,
            "cycle {cycle}: {:?} vs {:?}",
            sims[0].backend(),
            sims[1].backend()
        );
    }
    assert_eq!(sims[0].cycles(), sims[1].cycles());
}

#[test]
fn verilators_tracer_writes_a_vcd_of_the_run() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("divider.vcd");
    {
        let mut sim = stepper(
            Backend::Verilator,
            "freq_divider",
            FreqDivider::<8>::default(),
            Some(&path),
        )
        .unwrap_or_else(|e| panic!("{e}"));
        for _ in 0..50 {
            sim.step_vector(&[0, 1, 3]).unwrap();
        }
    }
    let vcd = std::fs::read_to_string(&path).unwrap();
    assert!(vcd.contains("$enddefinitions"), "no VCD header");
    assert!(vcd.contains("latched_divisor"), "internal signal missing");
    assert!(
        vcd.lines().filter(|l| l.starts_with('#')).count() >= 100,
        "fewer than 2 stamps per clock"
    );
}

#[test]
fn a_model_built_without_tracing_refuses_a_vcd() {
    let mut model =
        CompiledModel::from_block("no_trace", &mut FreqDivider::<8>::default(), false).unwrap();
    let error = model
        .record_vcd(std::path::Path::new("/tmp/never.vcd"))
        .unwrap_err();
    assert!(error.to_string().contains("without tracing"), "{error}");
    // And the harness still agrees on the design: both start from power-up.
    let mut harness = Harness::new("freq_divider", FreqDivider::<8>::default()).unwrap();
    for _ in 0..20 {
        let rust = harness.step_vector(&[0, 1, 2]).unwrap();
        for (i, v) in [0u64, 1, 2].iter().enumerate() {
            model.set(i, *v);
        }
        model.cycle();
        assert_eq!(rust[0], model.get(0));
    }
}
