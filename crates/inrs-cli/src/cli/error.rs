//! Why a command stopped.

/// The error of every subcommand: a message for standard error, or a closed pipe.
#[derive(Debug)]
pub(crate) enum CliError {
    /// A one-line message for standard error; the exit status is 1.
    Message(String),
    /// Standard output was closed by its reader (`| head`): end quietly, as other tools do.
    ClosedPipe,
}

impl From<String> for CliError {
    fn from(m: String) -> Self {
        CliError::Message(m)
    }
}
