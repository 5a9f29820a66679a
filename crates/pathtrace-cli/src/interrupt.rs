//! Ctrl-C handling: the first press asks the render to stop and keep what it has; a second
//! press quits at once.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// A flag set by Ctrl-C.
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
                std::process::exit(130);
            }
        });
        Self(flag)
    }

    pub fn triggered(&self) -> bool {
        self.0.load(Ordering::SeqCst)
    }
}
