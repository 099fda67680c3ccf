//! The `shatter` command line.

fn main() {
    println!("shatter");
}
