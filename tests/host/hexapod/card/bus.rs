//! Tests of `motion_hdl::host::hexapod::card::bus` (`src/host/hexapod/card/bus.rs`).

use motion_hdl::host::hexapod::card::*;

#[test]
fn a_read_takes_two_clocks_and_a_write_one() {
    let mut bus = BusAgent::default();
    bus.read(5);
    bus.write(6, 0xAB);
    let pins = bus.drive();
    assert_eq!((pins.address, pins.read, pins.write), (5, true, false));
    bus.sample(0);
    let pins = bus.drive();
    assert_eq!(
        (pins.read, pins.write),
        (false, false),
        "idle while the data comes"
    );
    bus.sample(42);
    assert_eq!(bus.take_results(), vec![42]);
    let pins = bus.drive();
    assert_eq!((pins.address, pins.write_data, pins.write), (6, 0xAB, true));
    bus.sample(0);
    assert!(bus.idle());
    assert_eq!(
        bus.drive(),
        BusPins {
            address: 6,
            ..BusPins::default()
        }
    );
}
