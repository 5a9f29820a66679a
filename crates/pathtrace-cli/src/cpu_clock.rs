//! A clock for single-thread benchmarks on a shared machine: the calling thread's CPU time
//! (user + system, from `/proc/thread-self/stat`, Linux), which does not advance while other
//! processes hold the core. Resolution is one clock tick (10 ms), so time at least a second.

use std::time::Instant;

/// How single-thread work is timed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Clock {
    Wall,
    ThreadCpu,
}

/// Clock ticks per second of `/proc` times (`sysconf(_SC_CLK_TCK)`, 100 on Linux).
const TICKS_PER_SECOND: f64 = 100.0;

/// CPU seconds used by the calling thread, if the platform reports it.
pub fn thread_cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/thread-self/stat").ok()?;
    // Fields after the parenthesised command name: state is field 3, utime 14, stime 15.
    let rest = &stat[stat.rfind(')')? + 1..];
    let fields: Vec<&str> = rest.split_whitespace().collect();
    let utime: f64 = fields.get(11)?.parse().ok()?;
    let stime: f64 = fields.get(12)?.parse().ok()?;
    Some((utime + stime) / TICKS_PER_SECOND)
}

impl Clock {
    /// Runs `f` and returns its result and the seconds it took on this clock (wall time if
    /// the CPU clock is unavailable).
    pub fn time<T>(self, f: impl FnOnce() -> T) -> (T, f64) {
        let cpu0 = if self == Clock::ThreadCpu { thread_cpu_seconds() } else { None };
        let start = Instant::now();
        let out = f();
        let wall = start.elapsed().as_secs_f64();
        let seconds = match (cpu0, thread_cpu_seconds()) {
            (Some(a), Some(b)) if self == Clock::ThreadCpu => b - a,
            _ => wall,
        };
        (out, seconds.max(1e-9))
    }
}

impl Clock {
    /// Calls `f` until at least `min_seconds` have passed on this clock (at least once), so
    /// the CPU clock's 10 ms ticks stay a small error; returns the last result and the mean
    /// seconds per call.
    pub fn time_repeated<T>(self, min_seconds: f64, mut f: impl FnMut() -> T) -> (T, f64) {
        let ((out, calls), seconds) = self.time(|| {
            let start = Instant::now();
            let cpu0 = thread_cpu_seconds();
            let mut calls = 1;
            let mut out = f();
            let elapsed = |start: &Instant| match (self, cpu0, thread_cpu_seconds()) {
                (Clock::ThreadCpu, Some(a), Some(b)) => b - a,
                _ => start.elapsed().as_secs_f64(),
            };
            while elapsed(&start) < min_seconds {
                out = f();
                calls += 1;
            }
            (out, calls)
        });
        (out, seconds / calls as f64)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cpu_time_advances_with_work() {
        if thread_cpu_seconds().is_none() {
            eprintln!("note: no /proc/thread-self/stat here; skipping");
            return;
        }
        let (sum, seconds) = Clock::ThreadCpu.time(|| {
            let start = Instant::now();
            let mut x = 0u64;
            while start.elapsed().as_secs_f64() < 0.3 {
                x = x.wrapping_mul(6364136223846793005).wrapping_add(1);
            }
            x
        });
        std::hint::black_box(sum);
        assert!(seconds > 0.05 && seconds < 1.0, "{seconds}");
    }
}
