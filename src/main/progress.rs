//! The progress bar of `pounding run` on a terminal.

use pounding::analysis::simulate::{Phase, RunSink};
use pounding::output::writer::RunWriter;

/// Streams a run into its writer (`RunWriter`, a pair's or a row's) and shows a progress bar on a terminal when the run
/// takes more than a second.
pub struct RunProgress<'a> {
    writer: &'a mut RunWriter,
    enabled: bool,
    bar: Option<indicatif::ProgressBar>,
    started: std::time::Instant,
    duration: f64,
    phases: f64,
    /// How far each phase has come, as a fraction of the duration (the self-check's phases
    /// go on beside the result's, `simulate_streaming_beside`).
    done: [f64; 4],
    ticks: u32,
}

impl<'a> RunProgress<'a> {
    /// A sink into `writer` for a run of `duration` s in `phases` phases (2, or 4 with the
    /// self-check); the bar shows only when `enabled` (stderr a terminal, not --quiet).
    pub fn new(writer: &'a mut RunWriter, enabled: bool, duration: f64, phases: f64) -> Self {
        RunProgress {
            writer,
            enabled,
            bar: None,
            started: std::time::Instant::now(),
            duration,
            phases,
            done: [0.0; 4],
            ticks: 0,
        }
    }

    /// The writer the run streams into.
    pub fn writer(&mut self) -> &mut RunWriter {
        self.writer
    }

    /// Clears the bar.
    pub fn finish(&mut self) {
        if let Some(b) = self.bar.take() {
            b.finish_and_clear();
        }
    }
}

impl RunSink for RunProgress<'_> {
    fn contact_row(&mut self, t: f64, w: [f64; 2], forces: &[f64]) {
        self.writer.contact_row(t, w, forces);
    }

    fn free_row(&mut self, t: f64, w: [f64; 2]) {
        self.writer.free_row(t, w);
    }

    fn row_contact_row(&mut self, t: f64, w: &[f64], forces: &[f64]) {
        self.writer.row_contact_row(t, w, forces);
    }

    fn row_free_row(&mut self, t: f64, w: &[f64]) {
        self.writer.row_free_row(t, w);
    }

    fn contact_floor_row(&mut self, t: f64, values: &[f64]) {
        self.writer.contact_floor_row(t, values);
    }

    fn free_floor_row(&mut self, t: f64, values: &[f64]) {
        self.writer.free_floor_row(t, values);
    }

    fn progress(&mut self, phase: Phase, t: f64) {
        if !self.enabled {
            return;
        }
        let index = match phase {
            Phase::WithContact => 0,
            Phase::WithoutContact => 1,
            Phase::CheckWithContact => 2,
            Phase::CheckWithoutContact => 3,
        };
        self.done[index] = (t / self.duration).clamp(0.0, 1.0);
        // (a thread's runs come one after the other: a run without contact follows its run
        // with contact's end)
        if index % 2 == 1 {
            self.done[index - 1] = 1.0;
        }
        self.ticks = self.ticks.wrapping_add(1);
        if self.bar.is_none() {
            if !self.ticks.is_multiple_of(64) || self.started.elapsed().as_secs_f64() < 1.0 {
                return;
            }
            let bar = indicatif::ProgressBar::new(1000);
            let style = indicatif::ProgressStyle::with_template(
                "{spinner} [{elapsed_precise}] {wide_bar} {percent:>3} %, ETA {eta} {msg}",
            )
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar());
            bar.set_style(style);
            bar.enable_steady_tick(std::time::Duration::from_millis(200));
            self.bar = Some(bar);
        }
        if let Some(b) = &self.bar {
            let done = self.done.iter().sum::<f64>() / self.phases;
            b.set_position((1000.0 * done).clamp(0.0, 1000.0) as u64);
            if self.ticks.is_multiple_of(256) {
                b.set_message(format!(
                    "{} at t = {t:.0} s of {} s",
                    phase.label(),
                    self.duration
                ));
            }
        }
    }
}
