//! G38.2 to G38.5 against a scripted prober: what it is asked to run, and
//! what the program sees after.

use std::cell::RefCell;
use std::rc::Rc;

use motion_hdl::host::gcode::probing::*;
use motion_hdl::host::gcode::{interpret_probing, Program, Setup};
use motion_hdl::host::toolpath::Item;

/// What a request asked: the code, where the pending moves start, how
/// many there are, and the probe move's start and end.
type Asked = (ProbeCode, [f64; 3], usize, [f64; 3], [f64; 3]);

/// A prober that trips where the move crosses z = `plane` (toward
/// contact) or leaves it (away), stops `overtravel` mm further along the
/// move, and records each request.
#[derive(Clone)]
struct PlaneProber {
    plane: f64,
    overtravel: f64,
    log: Rc<RefCell<Vec<Asked>>>,
}

impl Prober for PlaneProber {
    fn probe(&mut self, r: &ProbeRequest) -> Result<ProbeOutcome, String> {
        self.log.borrow_mut().push((
            r.code,
            r.pending_start,
            r.pending.len(),
            r.start_mm,
            r.end_mm,
        ));
        let (z0, z1) = (r.start_mm[2], r.end_mm[2]);
        let touching = z0 <= self.plane;
        if touching == r.code.toward_contact() {
            return Err(format!(
                "the probe is already {}",
                if touching { "touching" } else { "clear" }
            ));
        }
        let crosses = (z0 - self.plane) * (z1 - self.plane) <= 0.0 && z0 != z1;
        if !crosses {
            return Ok(ProbeOutcome {
                trip_mm: None,
                stop_mm: r.end_mm,
            });
        }
        let t = (self.plane - z0) / (z1 - z0);
        let at =
            |t: f64| std::array::from_fn(|k| r.start_mm[k] + t * (r.end_mm[k] - r.start_mm[k]));
        let length = (0..3)
            .map(|k| (r.end_mm[k] - r.start_mm[k]).powi(2))
            .sum::<f64>()
            .sqrt();
        Ok(ProbeOutcome {
            trip_mm: Some(at(t)),
            stop_mm: at(t + self.overtravel / length),
        })
    }
}

fn run(program: &str, prober: &PlaneProber) -> Result<Program, String> {
    interpret_probing(program, &Setup::default(), Box::new(prober.clone()))
        .map_err(|e| e.to_string())
}

fn prober() -> PlaneProber {
    PlaneProber {
        plane: -1.0,
        overtravel: 0.25,
        log: Default::default(),
    }
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-9
}

#[test]
fn g38_2_runs_the_pending_moves_and_goes_on_from_where_the_probe_stopped() {
    let p = prober();
    let program = run(
        "G0 X1 Y2\nG1 X2 F600\nG38.2 Z-5 F60\n#1 = #5063\n#2 = #5070\nG91 G0 Z2\nG90 G1 X#1",
        &p,
    )
    .unwrap();
    let log = p.log.borrow();
    assert_eq!(log.len(), 1);
    let (code, pending_start, pending, start, end) = log[0];
    assert_eq!(code, ProbeCode::G38_2);
    assert_eq!(
        (pending_start, pending),
        ([0.0; 3], 2),
        "both moves before it"
    );
    assert_eq!((start, end), ([2.0, 2.0, 0.0], [2.0, 2.0, -5.0]));
    assert_eq!(program.items_run, 3, "the two moves and the probe move");
    assert_eq!(program.pending_start, [2.0, 2.0, -1.25]);
    let Item::Move(probe) = &program.toolpath.items[2] else {
        panic!("{:?}", program.toolpath.items)
    };
    assert_eq!(
        (probe.end, probe.feed, probe.line),
        ([2.0, 2.0, -1.25], Some(1.0), 3)
    );
    // G91 Z2 counts from the stop; X#1 is the trip's Z.
    let Item::Move(up) = &program.toolpath.items[3] else {
        panic!()
    };
    assert!(close(up.end[2], 0.75), "{:?}", up.end);
    assert!(
        close(program.final_machine[0], -1.0),
        "{:?}",
        program.final_machine
    );
}

#[test]
fn the_trip_is_stored_in_program_units_and_coordinates() {
    let p = prober();
    // G54 origin at Z = -0.5 mm, inches: the trip at machine -1 mm is
    // work (-1 + 0.5) / 25.4 in.
    let program = run(
        "G10 L2 P1 Z-0.5\nG20\nG38.3 Z-1 F10\n#1 = #5063\n#2 = #5070\nG0 X#1 Y#2",
        &p,
    )
    .unwrap();
    let end = program.final_position;
    assert!(close(end[0], -0.5 / 25.4), "{end:?}");
    assert_eq!(end[1], 1.0, "#5070");
}

#[test]
fn without_a_trip_g38_3_goes_on_and_g38_2_is_an_error() {
    let p = prober();
    let program = run("G38.3 Z-0.5 F60\nG0 X#5070 Y#5063", &p).unwrap();
    assert_eq!(
        program.final_machine,
        [0.0, -0.5, -0.5],
        "#5070 = 0, #5063 the end"
    );
    assert_eq!(
        run("G38.2 Z-0.5 F60", &p).unwrap_err(),
        "line 1: G38.2: the move reached the probe point without the probe making contact (G38.3 and G38.5 go on without it)"
    );
    // G38.4 and .5 wait for the loss of contact: from below the plane.
    let program = run("G0 Z-2\nG38.5 Z0 F60\nG0 X#5070", &p).unwrap();
    assert_eq!(program.final_machine[0], 1.0);
    assert_eq!(
        run("G0 Z-2\nG38.4 Z-3 F60", &p).unwrap_err(),
        "line 2: G38.4: the move reached the probe point without the probe losing contact (G38.3 and G38.5 go on without it)"
    );
}

#[test]
fn bad_probe_moves_are_named_by_line() {
    let p = prober();
    assert_eq!(
        run("G0 Z-2\nG38.2 Z-3 F60", &p).unwrap_err(),
        "line 2: the probe is already touching"
    );
    assert_eq!(
        run("G38.2 Z-3", &p).unwrap_err(),
        "line 1: G38.2 needs a feed rate: no F word so far"
    );
    assert_eq!(
        run("G38.2 Z0 F60", &p).unwrap_err(),
        "line 1: G38.2: the probe point is where the move starts (LinuxCNC: Start point too close to probe point)"
    );
    assert!(run("G41.1 D2 G1 X5 F60\nG38.2 X10 Z-3", &p)
        .unwrap_err()
        .starts_with("line 2: G38.2 with cutter radius compensation on"));
    assert_eq!(
        motion_hdl::host::gcode::interpret("G38.2 Z-3 F60").unwrap_err().to_string(),
        "line 1: G38.2: probing needs a probe, and this run has none (`simulate --probe-plane z=-1.5` simulates one)"
    );
}
