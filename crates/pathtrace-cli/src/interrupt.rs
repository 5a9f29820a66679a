//! Stop requests: Ctrl-C (SIGINT), and the SIGTERM and SIGHUP that Slurm, Kubernetes, systemd and
//! `timeout` send (ctrlc's `termination` feature). The first asks the render to stop and keep what
//! it has; a second quits at once.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// The exit code of a render stopped by a signal: 128 + SIGINT's number, as shells report Ctrl-C.
/// (ctrlc's handler does not say which signal came, so SIGTERM and SIGHUP exit with it too.)
pub const EXIT_INTERRUPTED: u8 = 130;

/// A flag set by SIGINT, SIGTERM or SIGHUP.
#[derive(Clone)]
pub struct Interrupt(Arc<AtomicBool>);

impl Interrupt {
    /// Installs the handler (once per process; later calls return a flag that never trips).
    pub fn install() -> Self {
        let flag = Arc::new(AtomicBool::new(false));
        let handler_flag = Arc::clone(&flag);
        let _ = ctrlc::set_handler(move || {
            if handler_flag.swap(true, Ordering::SeqCst) {
                eprintln!("\ninterrupted twice: quitting without writing");
                std::process::exit(EXIT_INTERRUPTED.into());
            }
        });
        Self(flag)
    }

    pub fn triggered(&self) -> bool {
        self.0.load(Ordering::SeqCst)
    }
}
