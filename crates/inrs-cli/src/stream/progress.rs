//! The progress bar of a long run: bytes of a points file read, or cells of a grid written.

use std::time::{Duration, Instant};

/// Progress is shown (on a terminal) once a run has taken this long.
const PROGRESS_AFTER: Duration = Duration::from_secs(2);

/// What a bar counts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Unit {
    /// Bytes of the input read.
    Bytes,
    /// Cells of a grid written.
    Cells,
}

/// A progress bar on standard error, shown only on a terminal and only once the run has
/// lasted [`PROGRESS_AFTER`].
pub(crate) struct Progress {
    start: Instant,
    total: u64,
    unit: Unit,
    bar: Option<indicatif::ProgressBar>,
    enabled: bool,
    /// How long a run goes before the bar appears.
    after: Duration,
    /// Where the bar is drawn (standard error; hidden in tests).
    target: fn() -> indicatif::ProgressDrawTarget,
}

impl Progress {
    /// A bar over `total` bytes, on standard error if it is a terminal.
    pub(super) fn new(total: u64) -> Self {
        Self::on_stderr(total, Unit::Bytes)
    }

    /// A bar over `total` grid cells, on standard error if it is a terminal.
    pub(crate) fn cells(total: u64) -> Self {
        Self::on_stderr(total, Unit::Cells)
    }

    fn on_stderr(total: u64, unit: Unit) -> Self {
        use std::io::IsTerminal;
        let enabled = total > 0 && std::io::stderr().is_terminal();
        let mut p = Self::shown_after(
            total,
            PROGRESS_AFTER,
            enabled,
            indicatif::ProgressDrawTarget::stderr,
        );
        p.unit = unit;
        p
    }

    /// A bar over `total` bytes that appears once `after` has passed, if `enabled`.
    fn shown_after(
        total: u64,
        after: Duration,
        enabled: bool,
        target: fn() -> indicatif::ProgressDrawTarget,
    ) -> Self {
        Self {
            start: Instant::now(),
            total,
            unit: Unit::Bytes,
            bar: None,
            enabled,
            after,
            target,
        }
    }

    /// Reports `done` bytes read (cells written).
    pub(crate) fn update(&mut self, done: u64) {
        if !self.enabled {
            return;
        }
        if self.bar.is_none() && self.start.elapsed() >= self.after {
            // Started where the run is, so that its clock and rate count the whole run.
            let bar = indicatif::ProgressBar::with_draw_target(Some(self.total), (self.target)())
                .with_position(done.min(self.total))
                .with_elapsed(self.start.elapsed());
            let template = match self.unit {
                Unit::Bytes => "{elapsed_precise} [{bar:40}] {bytes}/{total_bytes} {msg}",
                // Short enough for an 80-column terminal (a longer line wraps and redraws).
                Unit::Cells => "{elapsed_precise} [{bar:30}] {percent:>3}% of the cells {msg}",
            };
            if let Ok(style) = indicatif::ProgressStyle::with_template(template) {
                bar.set_style(style.progress_chars("=> "));
            }
            self.bar = Some(bar);
        }
        if let Some(bar) = &self.bar {
            let done = done.min(self.total);
            bar.set_position(done);
            bar.set_message(rate_and_time_left(
                done,
                self.total,
                self.start.elapsed(),
                self.unit,
            ));
        }
    }

    /// Removes the bar, if shown.
    pub(crate) fn finish(&mut self) {
        if let Some(bar) = self.bar.take() {
            bar.finish_and_clear();
        }
    }
}

/// `(12.3 MiB/s, 4 s left)` (`M cells/s` for cells): the average rate of the whole run so far
/// and the time the rest takes at that rate (the bar's own estimate follows the bursts in
/// which runs are written).
fn rate_and_time_left(done: u64, total: u64, elapsed: Duration, unit: Unit) -> String {
    let seconds = elapsed.as_secs_f64();
    if done == 0 || seconds <= 0.0 {
        return String::new();
    }
    let rate = done as f64 / seconds;
    let left = (total - done.min(total)) as f64 / rate;
    match unit {
        Unit::Bytes => format!("({:.1} MiB/s, {left:.0} s left)", rate / (1 << 20) as f64),
        Unit::Cells => format!("({:.1} M cells/s, {left:.0} s left)", rate / 1e6),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use indicatif::ProgressDrawTarget;

    /// The bar appears only when enabled (standard error a terminal) and once the run has
    /// lasted long enough; it follows the bytes read, never past the total, and goes away at
    /// the end.
    #[test]
    fn the_progress_bar_appears_late_and_only_on_a_terminal() {
        let hour = Duration::from_secs(3600);
        let mut quiet =
            Progress::shown_after(100, Duration::ZERO, false, ProgressDrawTarget::hidden);
        quiet.update(50);
        assert!(quiet.bar.is_none(), "not a terminal");
        let mut early = Progress::shown_after(100, hour, true, ProgressDrawTarget::hidden);
        early.update(50);
        assert!(early.bar.is_none(), "a short run");
        let mut long = Progress::shown_after(100, Duration::ZERO, true, ProgressDrawTarget::hidden);
        long.update(50);
        assert_eq!(
            long.bar.as_ref().map(indicatif::ProgressBar::position),
            Some(50)
        );
        long.update(500);
        assert_eq!(
            long.bar.as_ref().map(indicatif::ProgressBar::position),
            Some(100)
        );
        long.finish();
        assert!(long.bar.is_none());
    }

    #[test]
    fn the_rate_is_the_average_so_far_and_the_time_left_follows_from_it() {
        let mib = 1 << 20;
        assert_eq!(
            rate_and_time_left(10 * mib, 40 * mib, Duration::from_secs(2), Unit::Bytes),
            "(5.0 MiB/s, 6 s left)"
        );
        assert_eq!(
            rate_and_time_left(0, 40, Duration::from_secs(2), Unit::Bytes),
            ""
        );
        assert_eq!(
            rate_and_time_left(50 * mib, 40 * mib, Duration::from_secs(5), Unit::Bytes),
            "(10.0 MiB/s, 0 s left)"
        );
        assert_eq!(
            rate_and_time_left(3_000_000, 9_000_000, Duration::from_secs(2), Unit::Cells),
            "(1.5 M cells/s, 4 s left)"
        );
    }
}
