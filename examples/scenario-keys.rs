//! Prints docs/scenario-keys.md, every key of a scenario file from the program's own key table:
//! `cargo run --release --example scenario-keys > docs/scenario-keys.md`
//! (the test `scenario_keys` fails when the committed file differs).

fn main() {
    print!("{}", pounding::input::scenario::keys::markdown());
}
