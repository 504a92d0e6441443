//! Reads LinuxCNC's canonical output (`rs274 -g`'s trace) into moves in
//! machine mm, to compare the interpreter with LinuxCNC's: the golden
//! programs in `tests/gcode_golden/` and, by hand, the corpus. Test
//! support only.

use motion_hdl::host::toolpath::{Item, MoveKind, Plane};

/// A move as LinuxCNC emits it, in machine mm.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct CanonMove {
    /// The canon line it came from (1-based, the trace's own numbering).
    pub(crate) trace_line: usize,
    pub(crate) end: [f64; 3],
    /// For an arc: the plane, its center in the plane's (first, second)
    /// coordinates, and LinuxCNC's signed turn (+P counter-clockwise).
    pub(crate) arc: Option<(Plane, [f64; 2], i64)>,
    /// G0 (true) or a feed.
    pub(crate) rapid: bool,
}

fn numbers(args: &str) -> Result<Vec<f64>, String> {
    // USE_TOOL_LENGTH_OFFSET writes "x y z, a b c, u v w".
    args.split([',', ' '])
        .filter(|a| !a.is_empty())
        .map(|a| a.parse::<f64>().map_err(|e| format!("{a:?}: {e}")))
        .collect()
}

/// The moves of a canon trace, in machine mm: work coordinates plus the
/// G5x, G92 and tool length offsets the trace sets, times the units' scale.
/// Zero-length lines are left out, as the interpreter leaves them out.
pub(crate) fn parse(trace: &str) -> Result<Vec<CanonMove>, String> {
    let mut scale = 1.0;
    let (mut g5x, mut g92, mut tlo) = ([0.0; 3], [0.0; 3], [0.0; 3]);
    let mut plane = Plane::Xy;
    let mut moves: Vec<CanonMove> = Vec::new();
    let mut last: Option<[f64; 3]> = None;
    for (index, line) in trace.lines().enumerate() {
        let Some(call) = line.split_whitespace().nth(2) else {
            continue;
        };
        let call = &line[line.find(call).unwrap_or(0)..];
        let Some((name, rest)) = call.split_once('(') else {
            continue;
        };
        let args = rest.trim_end().trim_end_matches(')');
        let xyz = |v: &[f64]| [v[0], v[1], v[2]];
        match name {
            "USE_LENGTH_UNITS" => {
                scale = if args.contains("INCHES") { 25.4 } else { 1.0 };
            }
            "SELECT_PLANE" => {
                plane = match args {
                    a if a.ends_with("XZ") => Plane::Zx,
                    a if a.ends_with("YZ") => Plane::Yz,
                    _ => Plane::Xy,
                };
            }
            "SET_G5X_OFFSET" => g5x = xyz(&numbers(args)?[1..]),
            "SET_G92_OFFSET" => g92 = xyz(&numbers(args)?),
            "USE_TOOL_LENGTH_OFFSET" => tlo = xyz(&numbers(args)?),
            "STRAIGHT_TRAVERSE" | "STRAIGHT_FEED" | "ARC_FEED" => {
                let v = numbers(args)?;
                let machine = |work: [f64; 3]| {
                    [0, 1, 2].map(|k| (work[k] + g5x[k] + g92[k] + tlo[k]) * scale)
                };
                let (first, second, normal) = plane.axes();
                let (end, arc) = if name == "ARC_FEED" {
                    let mut work = [0.0; 3];
                    work[first] = v[0];
                    work[second] = v[1];
                    work[normal] = v[5];
                    let mut center_work = [0.0; 3];
                    center_work[first] = v[2];
                    center_work[second] = v[3];
                    let c = machine(center_work);
                    (
                        machine(work),
                        Some((plane, [c[first], c[second]], v[4] as i64)),
                    )
                } else {
                    (machine(xyz(&v)), None)
                };
                if arc.is_none() && last == Some(end) {
                    continue;
                }
                last = Some(end);
                moves.push(CanonMove {
                    trace_line: index + 1,
                    end,
                    arc,
                    rapid: name == "STRAIGHT_TRAVERSE",
                });
            }
            _ => {}
        }
    }
    Ok(moves)
}

/// The toolpath's moves in the same form.
pub(crate) fn from_toolpath(items: &[Item]) -> Vec<CanonMove> {
    items
        .iter()
        .filter_map(|item| match item {
            Item::Move(m) => Some(CanonMove {
                trace_line: m.line,
                end: m.end,
                arc: match &m.kind {
                    MoveKind::Arc(a) => {
                        let turns = i64::from(a.turns) + 1;
                        Some((a.plane, a.center, if a.clockwise { -turns } else { turns }))
                    }
                    MoveKind::Line => None,
                },
                rapid: m.feed.is_none(),
            }),
            Item::Dwell { .. } | Item::Synced(_) => None,
        })
        .collect()
}

/// The first difference between LinuxCNC's moves and ours beyond
/// `tolerance` mm, described; `None` when they agree.
pub(crate) fn difference(lcnc: &[CanonMove], ours: &[CanonMove], tolerance: f64) -> Option<String> {
    let close = |a: &[f64], b: &[f64]| a.iter().zip(b).all(|(x, y)| (x - y).abs() <= tolerance);
    for (k, (l, o)) in lcnc.iter().zip(ours).enumerate() {
        let same_arc = match (&l.arc, &o.arc) {
            (None, None) => true,
            (Some((lp, lc, lt)), Some((op, oc, ot))) => lp == op && lt == ot && close(lc, oc),
            _ => false,
        };
        if l.rapid != o.rapid || !same_arc || !close(&l.end, &o.end) {
            return Some(format!(
                "move {k}: LinuxCNC (trace line {}) {l:?}, ours (program line {}) {o:?}",
                l.trace_line, o.trace_line
            ));
        }
    }
    (lcnc.len() != ours.len())
        .then(|| format!("LinuxCNC has {} moves, ours {}", lcnc.len(), ours.len()))
}
