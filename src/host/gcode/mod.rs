//! G-code (RS-274/NGC) programs as the controller's input: a subset with
//! LinuxCNC's semantics, read into a [`Toolpath`](crate::host::toolpath::Toolpath)
//! of lines, arcs and dwells in mm by [`interpret`].
//!
//! # Reading
//! [`program_text`] turns a file's bytes into text: UTF-8, or Latin-1 on a
//! line whose bytes above 0x7F all lie in comments (Windows CAM posts);
//! such a byte outside a comment is an error naming its line.
//! [`lex_program`] reads lines into blocks of words (see [`lexer`]): either
//! case, spaces anywhere, `N` numbers, `( )` and `;` comments, block delete
//! `/`, RepRap `*NN` checksums, `%` lines (an opening `%` on the first
//! non-blank line, and the next `%` line closes the program: nothing after
//! it is read, as in LinuxCNC). Values are `f64`; G and M codes
//! are compared as integers (tenths: G90.1 is 901). The lexer is our own:
//! the `gcode` crate (0.7.0, and 0.6.1) keeps values as `f32` (`X1234.5678`
//! reads 1234.5677), rejects block delete and checksums, and drops a
//! malformed G number without an error.
//!
//! # Parameters and expressions
//! A word's value may be a parameter or an expression, evaluated when its
//! block runs ([`expr`]): `X#1`, `Z-#<depth>`, `F[#2 * 60]`, `G#3`, with
//! LinuxCNC's operators, precedence and functions. `#n = value` and
//! `#<name> = value` anywhere on a line set parameters after the line has
//! run, as LinuxCNC does. Numbered parameters are #1 to #5602; #5161 to
//! #5390 are the persistent ones, #5400 the loaded tool and #5420 to #5422
//! the current X, Y, Z (see [`param_store`]). `(MSG, ...)`, `(DEBUG, ...)`
//! and `(PRINT, ...)` are collected in [`Program::messages`], the last two
//! with their parameters replaced by values. The RepRap checksum `*NN` is
//! a `*` outside comments and `[ ]`.
//!
//! # Polar coordinates
//! `@` (distance) and `^` (angle, degrees) give X and Y about the work
//! origin for G0, G1 and G17 canned cycles, absolute or (G91) added to the
//! current point's distance and angle, on every repeat of a cycle (see
//! `polar`). Errors: `@2 with X1: give the end in X and Y or in polar
//! coordinates, not both (...)`; `@2 with G53: ...`; `@2: polar
//! coordinates give the end of a G0 or G1, or a canned cycle's hole in the
//! G17 plane`; incremental at the origin: `... (LinuxCNC: Incremental
//! motion with polar coordinates is indeterminate when at the origin)`.
//!
//! # O-words
//! `sub`/`endsub`/`call`/`return` (arguments #1 to #30, `#<_value>`, 10
//! levels), `if`/`elseif`/`else`/`endif`, `while`/`endwhile`,
//! `do`/`while`, `repeat`/`endrepeat`, `break`/`continue`, paired by label
//! (`o100`, `o<name>`) before the program runs ([`flow`]). Subroutines are
//! those of the file itself (LinuxCNC would also look for `name.ngc` files
//! in its subroutine path). The program's loops may jump back at most
//! 10^7 times together: past that the loop is an error, never a hang.
//!
//! # Modal state at the start
//! G17 (XY plane), G21 (mm), G90 (absolute), G91.1 (I, J, K are offsets
//! from the arc's start), G94 (feed per minute), no motion mode, no feed,
//! the position [`interpret_from`]'s `start` (the origin for [`interpret`]).
//!
//! # Order within a block
//! All words are read first (errors for unknown or repeated words), then
//! applied in RS-274/NGC's order of execution: F (in the units in force
//! before the block: F comes before G20/G21 in that order), G20/G21,
//! G17/G18/G19, G90/G91 and G90.1/G91.1, G4 (a dwell, then the block's
//! motion if it has axis words: `G4 P1 G0 X5` dwells, then moves), G80,
//! the motion (G0 to G3 with X, Y, Z, I, J, K, R, P), then M2/M30. A feed keeps its speed across a
//! change of units (it is held in mm/s), as in LinuxCNC. A block deleted by `/` is skipped whole. After M2 or M30
//! nothing more is interpreted (the lexer has read every line by then, so
//! a malformed line after the end is still an error); the blocks left are
//! counted ([`Program::blocks_after_end`]) and `simulate` reports them. A
//! closing `%` ends the program too ([`Program::closing_percent`]). A
//! file without M2, M30 or a closing `%` ends at its last line and
//! `simulate` says so (a leniency for posts that omit it: LinuxCNC 2.9
//! refuses such a file, "File ended with no percent sign (%) or program
//! end (M2)").
//!
//! # Supported
//! | Words | Effect |
//! |---|---|
//! | G0 | rapid line (`Move::feed` is `None`) |
//! | G1 | line at the modal feed |
//! | G2, G3 | clockwise, counter-clockwise arc seen from the plane's positive normal; the normal axis may move (helix) |
//! | G4 P | dwell, P in **seconds** (RS-274/NGC and LinuxCNC; not Fanuc's milliseconds), P ≥ 0; non-modal, keeps the motion mode; axis words beside it run the motion mode after the dwell |
//! | G80 | ends the motion mode (LinuxCNC's motion group 1): axis words after it need a motion code again; beside another motion code it gives way (LinuxCNC's reader) |
//! | G73, G81, G82, G83, G85 to G89 | canned cycles with R, Q, P, L (G87: I, J, K; G73, G83: D, the peck clearance, else 0.254 mm), modal: a later block with axis words repeats the cycle there. LinuxCNC's motion, move for move: see [`cycles`] |
//! | G74, G84 | tapping with a floating holder (LinuxCNC's G84: not geared): feed to the bottom, dwell P (default 0), feed out to the clear level; G84 needs M3, G74 M4 |
//! | G98, G99 | cycles retract to the initial level, or to R (G99, LinuxCNC's default) |
//! | M3, M4, M5 | the spindle turns (G86, G87, G88, G74, G84 and the geared moves need it) or stops; reported once |
//! | S | the spindle speed, rpm, ≥ 0; the geared moves need it above 0; reported once |
//! | G33 X Y Z K | one axis geared to the spindle, K its travel per revolution ([`SyncedMove`](crate::host::toolpath::SyncedMove)); a G33 that moves two axes is refused (the gearbox drives one). Modal: a later block with axis words and K is another geared move. See [`threading`] |
//! | G33.1 X Y Z K | rigid tap: geared in to the point, the spindle reverses there, geared back out; ends where it started |
//! | G76 X Z P I J K \[R Q H\] | LinuxCNC's threading cycle from the drive line (the tool's position): passes to depth \|I\| + J n^(1/R), compound angle Q, H spring passes, each pass a geared move along Z; then a rapid to X Z. E and L (the taper) are refused; R below 1 is refused where LinuxCNC takes 1. Runs on its own block: axis words after it need a motion code. See [`threading`] |
//! | G17, G18, G19 | arc plane XY, ZX, YZ |
//! | G20, G21 | inch, mm: every later length and F in those units |
//! | G90, G91 | X, Y, Z absolute or incremental |
//! | G90.1, G91.1 | I, J, K absolute positions or offsets from the arc's start |
//! | X Y Z | the end, in the current units; an axis not written keeps its position |
//! | A B C | only on a machine with rotary axes ([`Setup::rotary_axes`], the hexapod): the end angles in degrees (any units mode), absolute or G91 incremental, on G0 to G3 only (G53 too); they move linearly along the move ([`Move::angles`](crate::host::toolpath::Move::angles)); no offsets apply to them; a move of A B C alone (X Y Z travel below [`ANGLES_ONLY_TRAVEL`](crate::host::toolpath::ANGLES_ONLY_TRAVEL), 1e-7 mm) runs at F degrees per minute; an angle beyond ±10^6 degrees is an error |
//! | F | feed, units per minute, > 0, modal; stored as mm/s (F600 in G21 is 10 mm/s) |
//! | M2, M30 | end of program ([`Program::end`]) |
//! | G54 to G59, G59.1 to G59.3 | select coordinate system 1 to 9; the active one at the start is #5220 (1, G54, by default) |
//! | G10 L2 P X Y Z \[R0\] | system P's origin at X Y Z, machine coordinates (P0: the active system; G91 does not apply); R, the rotation, must be 0 |
//! | G10 L20 P X Y Z | system P's origin such that the current position reads X Y Z |
//! | G92 X Y Z | an offset such that the current position reads X Y Z; an axis not named keeps the offset in force (LinuxCNC's source); #5210 = 1 |
//! | G92.1, G92.2, G92.3 | clear the G92 offset and #5211..; stop applying it (kept); apply the kept one |
//! | G53 | with G0 or G1 (its own or the modal one) under G90: the block's X Y Z are machine coordinates |
//! | G28, G30 [X Y Z] | rapid through the point of the axis words (current distance mode and offsets), then the named axes (all when none is) to the stored position, #5161.. or #5181.. (machine mm); the motion mode is kept |
//! | G28.1, G30.1 | store the current machine position there |
//! | T | select a tool (a whole number; 0 is no tool); with a tool table it must be in it |
//! | M6 | load the selected tool (a T so far is needed); no motion |
//! | M61 Q | the loaded tool is Q, without a change |
//! | G43 \[H\] | tool length offset of tool H, or of the loaded tool: X, Y, Z from the table, mm |
//! | G43.1 X Y Z | tool length offset of the axis words (program units); an axis not named has none |
//! | G43.2 H or X Y Z | add tool H's offset, or the axis words, to the one in force |
//! | G49 | no tool length offset |
//! | G41 \[D\], G42 \[D\] | cutter radius compensation, the tool left (G41) or right of the path, in G17 or G18: the radius of tool D from the tool table, or of the loaded tool without D; a negative diameter takes the other side. LinuxCNC's geometry, move for move: see [`cutter_comp`] |
//! | G41.1 D, G42.1 D | the same with D the diameter, in program units |
//! | G40 | compensation off: the held-back move ends where it was going; the next move must be straight |
//! | G94 | accepted, no effect: the only feed mode |
//! | G38.2 to G38.5 | straight probe toward the axis words at the feed, until contact (.2, .3) or its loss (.4, .5); run by a [`Prober`] ([`interpret_probing`]), the trip in #5061 to #5063 and #5070; see [`probing`] |
//!
//! Coordinates: the toolpath is in machine mm; a program's X Y Z are work
//! coordinates, machine = work + the active system's origin + the G92
//! offset in force + the tool length offset (LinuxCNC's order of
//! execution: T, then M6 or M61, then the units, the tool length offset,
//! the system, then G10, G28, G30 and G92, then the motion; G53 and the
//! G28 and G30 positions are machine coordinates of the spindle, so the
//! tool length offset does not apply to them). A tool offset comes from the
//! tool table ([`Setup::tools`], LinuxCNC's `.tbl` format, in mm); without
//! one, every tool has no offset, which is reported once. The
//! origins, the offset and the stored positions are LinuxCNC's persistent
//! parameters: the machine settings give their values at the start
//! ([`PersistentParameters`], in mm), and [`Program::parameters`] has them
//! as the program left them. [`Program::final_position`] is the end in
//! work coordinates, [`Program::final_machine`] in machine mm. What LinuxCNC
//! does at M2 (select G54 again) is not modelled: the report names the
//! system the program ended in.
//!
//! Motion is modal: a block with only axis words runs the last G0 to G3. A
//! G0 or G1 (or a G2, G3) with no axis word only sets the mode; a line
//! ending exactly where it starts adds no move.
//!
//! Arcs: the center is either I, J, K (the plane's two: I and J for G17,
//! K and I for G18's (Z, X), J and K for G19; under G91.1 a missing one
//! counts 0), or
//! R. Under G90.1 (absolute centers) both of the plane's offsets must be
//! given. With I, J, K an end equal to the start in the plane (within 1e-9 mm)
//! is a full circle; the radius at the end must match the start's within
//! max(0.002 mm, 0.1 %). R > 0 is the arc of at most half a circle, R < 0
//! the longer one (LinuxCNC's rule); |R| short of half the chord by less
//! than 0.005 mm (LinuxCNC's tolerance) is taken as a half circle. P, the number of turns (a
//! whole number, at least 1, the default), gives `Arc::turns` = P − 1. An
//! arc given by R needs at least one of the plane's two axis words; I, J,
//! K alone make a full circle.
//!
//! Cutter radius compensation (G41, G42) is LinuxCNC's: the entry move
//! ends one tool radius to the side of its end, convex corners become
//! arcs about the programmed corner, a move into a concave corner is held
//! back and shortened to where the tool touches both sides (a corner too
//! tight for the tool is an error, never a gouge), and M0, M1, M2, M30 or
//! the file's end let the held-back move run as it is. While it is on,
//! [`Program::final_position`] and the work position are the programmed
//! point, and the toolpath (and [`Program::final_machine`]) the tool's.
//! What it refuses and why is in [`cutter_comp`] and
//! below.
//!
//! # Ignored, reported once
//! These words do not change the motion; each is listed in
//! [`Program::ignored`] at its first occurrence (once per M code, per G
//! code, per letter S, T, H, D) and otherwise ignored:
//! M0, M1, M60 (program pause); M3, M4, M5, G96, G97 (spindle); S (spindle
//! speed: the geared moves take it); M6 (tool change) and T, M61 (tool), which change no motion by
//! themselves; H without G43 or G43.2 and D without G41, G42, G41.1,
//! G42.1 or a canned cycle (tool offset); M7, M8, M9 (coolant); M48 to M53 (override); M62
//! to M68 (digital and analog I/O); G61, G61.1, G64, and a P or Q beside them (path
//! control: the planner always blends within its own contour error); and
//! **any other M code** ("unknown M
//! code": user M100 to M199 macros and RepRap's M104, M106... run nothing
//! here, so the path is the program's own).
//!
//! Two posts' conventions are accepted and reported once:
//! * `O1003`, a whole number alone on its block (comments aside) before
//!   the program's first move or dwell: the program number Fanuc- and
//!   Haas-style posts write at the top ("program number"). After a move,
//!   or beside another word, an O word is flow control and refused.
//! * An arc's out-of-plane offset of exactly zero (`K0.000` on a G17 arc,
//!   which FreeCAD's grbl post writes on every arc; grbl ignores it): it
//!   is dropped, reported once per plane as `K0 on G2`. Any other value
//!   is LinuxCNC's error, below.
//!
//! # Errors
//! Every error is a [`GcodeError`], "line N: message", naming the word:
//! * `G52 (local coordinate offset) changes the motion and is not
//!   supported`; likewise G33
//!   (spindle-synchronized motion); G33.1 (rigid tapping: it needs spindle
//!   synchronisation); G74, G84 (tapping: it needs spindle synchronisation);
//!   G76 (lathe threading cycle); G93
//!   (inverse-time feed); G95 (feed per revolution); G5 to G5.3 (spline);
//!   G7, G8 (lathe diameter, radius mode).
//! * Cutter compensation: `G1: the cutter compensation entry move, 2.0000
//!   mm, is not longer than the tool radius, 3.0000 mm (LinuxCNC: Length
//!   of cutter compensation entry move is not greater than the tool
//!   radius)`; `G3: the arc's radius, 2.0000 mm, is not more than the
//!   tool's, 3.0000 mm, and the tool is inside it (LinuxCNC: ...)`;
//!   `straight feed in concave corner cannot be reached by the tool
//!   without gouging (...)` (and straight traverse, arc move, arc to
//!   straight, arc to arc); `G2: the move just after G40 must be straight
//!   (...)`; `T2 M6 with cutter radius compensation on (G41 on line 3):
//!   turn it off with G40 first (LinuxCNC: Cannot change tools with cutter
//!   radius compensation on)`, and likewise G43 to G49, G54 to G59.3,
//!   G92 to G92.3, G28, G30, G28.1, G30.1, G10 L2 or L20 of the active
//!   system, G53, canned cycles, G98, G99, G61, G64 and a change of plane;
//!   `G42: cutter radius compensation is already on (...)`; `G41 in G19:
//!   ... G17 and G18 only`; `G42.1 needs D`; `L3 with G41.1: lathe tool
//!   orientations are not supported`.
//! * `G12 is not a supported G code`; `G1.25 is not a G code`;
//!   `M1.5 is not an M code`.
//! * `A5 moves an axis this machine does not have (X, Y and Z only)` (A, B,
//!   C, U, V, W; with rotary axes, U, V, W: `(X, Y, Z, A, B and C
//!   only)`); with rotary axes, `A5 with G92: the rotary axes move with
//!   G0, G1, G2 and G3 only; their offsets and stored positions are not
//!   supported` (G10, G28, G30, G43.1, G43.2, G92), `A3 with G81: ... not
//!   in canned cycles`, `A1: the rotary axes cannot move while cutter
//!   radius compensation is on (G40 first)`; `E5 drives an extruder (RepRap), an axis this machine
//!   does not have`; `O100: subroutines and flow control (O words) are
//!   not supported` (an O number beside other words, not a statement; and
//!   `O1003: a program number stands before any motion; ...` after a move); `L2 has no G10 or canned cycle to use it`.
//! * `X appears twice`; `G0 and G1 in one block: one motion per block`;
//!   `G90 and G91 in one block: both select the distance mode` (and so for
//!   every modal group); `M2 and M30 in one block: both stop the program`.
//! * `X10 needs a motion mode (G0, G1, G2 or G3) first`; `G1 needs a feed
//!   rate: no F word so far` (G2, G3 likewise); `F0 is not a feed rate: it
//!   must be above zero`.
//! * `G4 needs a dwell time: P, in seconds`; `P-1 is not a dwell time: it
//!   must be 0 or more seconds`.
//! * `X2 with G80: G80 cancels the motion mode and takes no axis or arc
//!   words (LinuxCNC: Cannot use axis values with g80)`.
//! * `G4 and G53 in one block: one non-modal code (G4, G10, G28, G30, G53,
//!   G92) per block`; `G28 and G1 in one block: both use the axis words
//!   (LinuxCNC: Cannot use two g codes that both use axis values)`;
//!   `X1 with G92.1: it takes no axis words` (G28.1, G30.1, G92.1 to G92.3).
//! * `G53 needs a G0 or G1 move with axis words (LinuxCNC: Must use g0 or
//!   g1 with g53)`; `G53 with G91: machine coordinates are absolute
//!   (LinuxCNC: Cannot use g53 incremental)`; `G92 needs an axis word
//!   (LinuxCNC: All axes missing with g92)`.
//! * Tools: `T7: tool 7 is not in the tool table (LinuxCNC: Requested tool
//!   7 not found in the tool table)` (and for H, Q); `M6 needs a tool
//!   selected first with T (LinuxCNC: Need tool prepared -Txx- for
//!   toolchange)`; `T1.5 is not a tool number: a whole number, 0 (no tool)
//!   or more`; `M61 needs Q: the tool now in the spindle`; `G43.2 needs H
//!   (a tool) or axis words (the offset to add)`; `G43.1 and G0 in one
//!   block: both use the axis words (...)`.
//! * G10: `G10 needs P: the coordinate system, 0 (the active one) or 1
//!   (G54) to 9 (G59.3)`; `P10 is not a coordinate system: ...`; `G10 with
//!   L1: L2 and L20 set a coordinate system; L1, L10 and L11 set the tool
//!   table, which is not supported` (or `with no L`); `R30 on G10 rotates
//!   the coordinate system, which is not supported`.
//! * `%` on a line after others, with no `%` on the first line: "`%`
//!   closes a program only when its first line is `%` too (LinuxCNC: Bad
//!   character '%' used)".
//! * Canned cycles, with LinuxCNC's text in brackets: `Q0 is not a peck
//!   depth: it must be above zero (LinuxCNC: Negative or zero q value
//!   used)`; `G83 needs Q (LinuxCNC: Q word missing with g83)`; `G82 needs P
//!   (...)`; `G81 needs R, the retract level (...)`; `G81 needs Z, the bottom
//!   of the hole (...)`; `R-2 is below the bottom Z0 (...)`; `L0 is not a
//!   number of repeats: ...`; `G86 needs the spindle turning: M3 or M4 first
//!   (...)`; `G87 needs K (...)`; `I1 has no G2, G3 or G87 to use it`. R, Z,
//!   Q, P, I, J, K may be left out only when the cycle repeats itself.
//! * `P2 has no G2, G3, G4, G10, G64 or canned cycle to use it`; `Q1 has no
//!   G64, M61 or canned cycle to use it`;
//!   `I5 has no G2 or G3 to use it` (I, J, K, R without an arc).
//! * Arcs: `G2 needs a center (I, J or K) or a radius (R)`; `R5 with I, J
//!   or K: give the center or the radius, not both`; `K5 is not in the G17
//!   plane's offsets (I and J)`; `G2 with R needs X or Y (its end in the G17
//!   plane): R cannot make a full circle`; `R cannot make a full circle (the end is the start); give
//!   the center with I, J or K`; `R5 cannot reach the end: |R| must be at
//!   least half the chord, 6.0000 mm`; `G2 needs J with G90.1: absolute
//!   arc centers need both of the G17 plane's offsets (LinuxCNC: J word
//!   missing in absolute center arc)`; `the arc's radius is 10.0000 mm at
//!   its start and 10.0100 mm at its end`; `the arc's center is its start
//!   (zero radius)` (or `its end`); `P1.5 is not a number of turns: a whole
//!   number, 1 or more`. Lengths are in the program's units, 4 decimals.
//! * `the X axis would be at 2000000.0000 mm, beyond ±1000000 mm` (and
//!   `the arc's center ...`); `X1000…0 is not a finite number` (more digits
//!   than f64 holds).
//! * Values: `X[1/0]: division by zero (LinuxCNC: Attempt to divide by
//!   zero)`; `SQRT[-1]: the argument must be 0 or more (...)`; `LN[0]: ...`;
//!   `ACOS[2]: the argument must be from -1 to 1 (...)`; `X#<nope>:
//!   #<nope> is not set (LinuxCNC: Named parameter #<nope> not defined)`;
//!   `#6000 is not a parameter: a whole number from 1 to 5602 (...)`; `#5420
//!   is read-only here: the current position`; a persistent parameter's
//!   value is checked as the settings file's is.
//! * O-words: `O1 if is never closed`; `O1 endif closes no open O1 if`;
//!   `O1 else has no open O1 if`; `O1 break is in no O1 loop`; `O1 sub is
//!   defined twice`; `O2 sub inside another O-word structure`; `O9 call:
//!   this file has no O9 sub (...)`; `O1 return outside a subroutine`;
//!   `O<f> call: more than 10 calls deep (LinuxCNC: Too many subroutine
//!   levels)`; `O1: the program's loops jumped back 10000000 times: a loop
//!   that does not end (...)`; `O1 frobnicate: not an O-word keyword`; an
//!   error inside a subroutine adds `(in O<f> called on line N)`.
//! * The lexer's errors, with their line and message unchanged; for
//!   values: `` `[` is not closed by `]` ``, `` `?` is not an operator ``,
//!   `` `FOO` is not a function ``, `` a parameter alone on a line is set
//!   with `=`: `#1 = 2` ``.

mod arc_center;
mod block_words;
mod comp_queue;
pub mod cutter_comp;
pub mod cycles;
pub mod expr;
pub mod flow;
mod flow_run;
pub mod interpreter;
pub mod lexer;
mod messages;
mod non_modal;
pub mod param_store;
pub mod parameters;
mod polar;
pub mod probing;
mod text;
pub mod threading;
mod tools;

pub use interpreter::{
    interpret, interpret_from, interpret_probing, interpret_with, GcodeError, Ignored, Program,
    Setup, Units,
};
pub use lexer::{lex_line, lex_program, Block, LexError, Lexed, Word};
pub use messages::Message;
pub use parameters::PersistentParameters;
pub use probing::{ProbeCode, ProbeOutcome, ProbeRequest, Prober};
pub use text::program_text;
