//! Progress bars on standard error (indicatif): a counting bar for the command line's own
//! loops, and a bar that follows a [`Progress`] handle a library loop advances. Hidden
//! when standard error is not a terminal or the command prints JSON.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::thread::JoinHandle;
use std::time::Duration;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use shatter_geom::progress::Progress;

const BAR_TEMPLATE: &str = "{elapsed_precise} [{bar:40}] {pos}/{len} {msg} (eta {eta})";
const SPINNER_TEMPLATE: &str = "{elapsed_precise} {spinner} {msg}";

/// A progress bar; cleared when dropped.
pub struct Bar {
    bar: ProgressBar,
    follower: Option<(Arc<AtomicBool>, JoinHandle<()>)>,
}

fn target(visible: bool) -> ProgressDrawTarget {
    if visible {
        ProgressDrawTarget::stderr()
    } else {
        ProgressDrawTarget::hidden()
    }
}

fn styled(bar: ProgressBar, template: &str) -> ProgressBar {
    if let Ok(style) = ProgressStyle::with_template(template) {
        bar.set_style(style.progress_chars("=> "));
    }
    bar
}

impl Bar {
    /// A bar of `len` units.
    pub fn counting(len: u64, visible: bool) -> Self {
        let bar = styled(
            ProgressBar::with_draw_target(Some(len), target(visible)),
            BAR_TEMPLATE,
        );
        Self {
            bar,
            follower: None,
        }
    }

    /// A spinner with `message` that becomes a bar of the library's stage once the
    /// library reports a total through `progress`; redrawn ten times a second.
    pub fn following(progress: &Progress, message: &str, visible: bool) -> Self {
        let bar = styled(
            ProgressBar::with_draw_target(None, target(visible)),
            SPINNER_TEMPLATE,
        );
        bar.set_message(message.to_string());
        if !visible {
            return Self {
                bar,
                follower: None,
            };
        }
        let stop = Arc::new(AtomicBool::new(false));
        let handle = {
            let (bar, stop, progress) = (bar.clone(), stop.clone(), progress.clone());
            let message = message.to_string();
            std::thread::spawn(move || {
                let mut counting = false;
                while !stop.load(Ordering::Relaxed) {
                    let s = progress.snapshot();
                    if s.total > 0 {
                        if !counting {
                            bar.set_style(styled(ProgressBar::hidden(), BAR_TEMPLATE).style());
                            counting = true;
                        }
                        bar.set_length(s.total);
                        bar.set_position(s.done.min(s.total));
                    } else {
                        bar.tick();
                    }
                    let stage = if s.stage.is_empty() {
                        message.clone()
                    } else {
                        format!("{message}: {}", s.stage)
                    };
                    bar.set_message(stage);
                    std::thread::sleep(Duration::from_millis(100));
                }
            })
        };
        Self {
            bar,
            follower: Some((stop, handle)),
        }
    }

    /// One more unit done, now working on `message`.
    pub fn tick(&self, message: &str) {
        self.bar.set_message(message.to_string());
        self.bar.inc(1);
    }

    /// Prints a line on standard output above the bar (as `println!` when the bar is
    /// hidden).
    pub fn println(&self, line: String) {
        if self.bar.is_hidden() {
            println!("{line}");
        } else {
            self.bar.suspend(|| println!("{line}"));
        }
    }

    /// Prints a line on standard error above the bar: diagnostics, which must not mix
    /// with a command's output on standard output (e.g. `--json`).
    pub fn eprintln(&self, line: String) {
        if self.bar.is_hidden() {
            eprintln!("{line}");
        } else {
            self.bar.suspend(|| eprintln!("{line}"));
        }
    }
}

impl Drop for Bar {
    fn drop(&mut self) {
        if let Some((stop, handle)) = self.follower.take() {
            stop.store(true, Ordering::Relaxed);
            let _ = handle.join();
        }
        self.bar.finish_and_clear();
    }
}
