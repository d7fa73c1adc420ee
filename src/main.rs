use clap::Parser;
use std::io::{IsTerminal, Write};
use std::process::ExitCode;
use unitpack::cli::{Cli, Command, output};

/// Exit status of an error (usage errors too, as clap gives them).
const ERROR: u8 = 2;

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) if e.use_stderr() => {
            // Usage errors: clap's message on stderr (ignoring a closed stderr).
            let _ = e.print();
            return ExitCode::from(ERROR);
        }
        Err(e) => {
            // --help and --version go through the same stdout as every verb, so that a
            // closed or full stdout ends as it does for them (clap would stay silent).
            let text = if std::io::stdout().is_terminal() {
                e.render().ansi().to_string()
            } else {
                e.render().to_string()
            };
            return finish(output::print(&text).map(|()| 0));
        }
    };
    // Keep Mesa quiet (see `runtime_dir`). The guard removes the directory at the end.
    let _runtime_dir = if matches!(cli.command, Command::Verify { .. }) {
        let dir = unitpack::cli::runtime_dir::private_runtime_dir();
        if let Some(d) = &dir {
            // SAFETY: no other thread exists yet: nothing has run but argument parsing.
            unsafe { std::env::set_var("XDG_RUNTIME_DIR", d.path()) };
        }
        dir
    } else {
        None
    };
    finish(unitpack::cli::run(cli))
}

/// The exit status of a verb's result; an error is one line on stderr, except a closed
/// stdout, which ends quietly.
fn finish(result: anyhow::Result<i32>) -> ExitCode {
    match result {
        Ok(code) => ExitCode::from(u8::try_from(code).unwrap_or(ERROR)),
        Err(e) if output::is_stdout_closed(&e) => ExitCode::SUCCESS,
        Err(e) => {
            let line = format!("{e:#}").replace('\n', " ");
            let _ = writeln!(std::io::stderr(), "error: {line}");
            ExitCode::from(ERROR)
        }
    }
}
