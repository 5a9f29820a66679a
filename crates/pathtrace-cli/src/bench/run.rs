//! One timed render of a suite scene: throughput, ray counts, and the error against the
//! reference after every progressive wave (the convergence curve that gives the time to a
//! target relative MSE).

use crate::CliError;
use pathtrace::film::{Film, Image};
use pathtrace::metrics::relative_mse;
use pathtrace::{Progress, RenderSession, RenderSettings, Scene};
use std::sync::Arc;
use std::time::Duration;

/// How often the session is polled for a finished wave. Short against a wave (≥ 16 k samples)
/// and cheap: a poll reads a few atomics.
const POLL: Duration = Duration::from_millis(2);

/// What one run measured.
pub struct Run {
    pub progress: Progress,
    pub film: Film,
    /// (seconds since the start, relative MSE against the reference) after each wave.
    pub curve: Vec<(f64, f64)>,
}

/// Renders once. With a reference, the image is snapshotted whenever a wave completes and its
/// relative MSE recorded at the time the snapshot was taken (so the time is never early).
pub fn render_run(scene: Arc<Scene>, settings: RenderSettings, reference: Option<&Image>) -> Result<Run, CliError> {
    let session = RenderSession::start(scene, settings)?;
    let mut curve = Vec::new();
    let mut seen_spp = 0;
    while !session.is_finished() {
        std::thread::sleep(POLL);
        let Some(reference) = reference else { continue };
        let spp = session.progress().spp_done;
        if spp != seen_spp {
            seen_spp = spp;
            let image = session.snapshot();
            let t = session.progress().elapsed.as_secs_f64();
            if let Ok(e) = relative_mse(&image, reference) {
                curve.push((t, e));
            }
        }
    }
    let outcome = session.wait();
    if let Some(reference) = reference {
        if let Ok(e) = relative_mse(&outcome.film.image(), reference) {
            curve.push((outcome.progress.elapsed.as_secs_f64(), e));
        }
    }
    Ok(Run { progress: outcome.progress, film: outcome.film, curve })
}

/// The time at which a convergence curve first reaches `target`, interpolated linearly in
/// log(time)–log(error) between the two waves around the crossing (Monte Carlo error falls as a
/// power of time, a straight line there). `None` if it never gets there; the first point's time
/// if it starts below the target.
pub fn time_to_reach(curve: &[(f64, f64)], target: f64) -> Option<f64> {
    let i = curve.iter().position(|&(_, e)| e <= target)?;
    if i == 0 {
        return Some(curve[0].0);
    }
    let ((t0, e0), (t1, e1)) = (curve[i - 1], curve[i]);
    if t0 <= 0.0 || e1 <= 0.0 || e0 <= e1 {
        return Some(t1);
    }
    let f = (e0.ln() - target.ln()) / (e0.ln() - e1.ln());
    Some((t0.ln() + f * (t1.ln() - t0.ln())).exp())
}

/// Median of a non-empty list (mean of the middle two for even lengths); NaN for none.
pub fn median(mut v: Vec<f64>) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crossing_interpolates_on_a_power_law() {
        // e = 1/t: reaches 0.01 at t = 100 exactly, between the points at 50 and 200.
        let curve = [(10.0, 0.1), (50.0, 0.02), (200.0, 0.005)];
        let t = time_to_reach(&curve, 0.01).unwrap();
        assert!((t - 100.0).abs() < 1e-9, "{t}");
        assert_eq!(time_to_reach(&curve, 1e-4), None);
        assert_eq!(time_to_reach(&curve, 0.5), Some(10.0));
    }

    #[test]
    fn medians() {
        assert_eq!(median(vec![3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(vec![4.0, 1.0, 2.0, 3.0]), 2.5);
        assert!(median(vec![]).is_nan());
    }
}
