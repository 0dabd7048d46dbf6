//! The `cufem` command-line program: `run`, `check` and `bench` a model file.

mod cli;

fn main() -> std::process::ExitCode {
    cli::main()
}
