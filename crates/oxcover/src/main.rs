//! The `oxcover` command line; see `oxcover --help` and the contract. The
//! commands live in [`cli`], each a thin layer over the `oxcover` library.

mod cli;

fn main() -> std::process::ExitCode {
    cli::main()
}
