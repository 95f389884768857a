//! The `oxcover` command line; see `oxcover --help` and the contract.

fn main() -> std::process::ExitCode {
    oxcover::cli::main()
}
