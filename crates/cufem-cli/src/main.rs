//! The `cufem` command-line program: `check`, `run` (`--adapt`), `bench`, `export-ccx`, `verify` and `schema`.

mod cli;

fn main() -> std::process::ExitCode {
    // A reader that stops early (`cufem bench … | head`) closes the pipe:
    // end quietly as Unix tools do, instead of println! panicking on EPIPE
    // (Rust ignores SIGPIPE by default).
    // SAFETY: restores the default disposition of one signal before any
    // thread starts; no handler is involved.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    cli::main()
}
