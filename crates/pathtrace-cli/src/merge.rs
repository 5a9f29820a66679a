//! `pathtrace merge`: joins films rendered in sample ranges into the whole render's film. The
//! film sums are exact integers, so the merged image is bit for bit the one a single
//! `pathtrace render` of every sample writes, whatever the order of the parts. Films rendered
//! with feature buffers carry them, merged just as exactly, so `merge --aov`/`--denoise` write
//! what `render --aov`/`--denoise` of the whole would.

use crate::aov_output::FeatureOutputs;
use crate::args::MergeArgs;
use crate::destination::check_destination;
use crate::CliError;
use pathtrace::SampleRange;
use pathtrace_scene::film_file::{read_film, write_film};
use std::process::ExitCode;

/// `a..b, c..d`
fn list(ranges: &[SampleRange]) -> String {
    ranges.iter().map(|r| r.to_string()).collect::<Vec<_>>().join(", ")
}

pub fn run(a: MergeArgs) -> Result<ExitCode, CliError> {
    if a.output.is_none() && a.film_out.is_none() {
        return Err(CliError::usage("merge: nothing to write: give -o IMAGE and/or --film-out FILM"));
    }
    if a.features.wanted() && a.output.is_none() {
        return Err(CliError::usage("merge: --aov and --denoise write beside the image: give -o IMAGE"));
    }
    let feature_outputs = match &a.output {
        Some(path) => Some(FeatureOutputs::prepare(&a.features, path)?),
        None => None,
    };
    if let Some(path) = &a.film_out {
        check_destination(path, "--film-out")?;
    }
    let tone = a.tone.settings()?;
    let mut merged = None;
    for path in &a.parts {
        let part = read_film(path).map_err(|e| CliError::usage(e.to_string()))?;
        match &mut merged {
            None => merged = Some(part),
            Some(whole) => {
                whole.merge(&part).map_err(|e| CliError::usage(format!("{}: cannot merge: {e}", path.display())))?
            }
        }
    }
    let Some(whole) = merged else { return Err(CliError::usage("merge: no film given")) };
    if a.features.wanted() && whole.features.is_none() {
        return Err(CliError::usage(
            "merge: --aov and --denoise need the feature buffers, but the films have none: render the parts with --aov \
             or --denoise",
        ));
    }
    let missing = whole.missing();
    let (w, h) = (whole.film.width(), whole.film.height());
    if !missing.is_empty() {
        let message = format!(
            "samples {} of the {} spp render are missing (have {})",
            list(&missing),
            whole.spp,
            list(&whole.ranges)
        );
        if a.output.is_some() && !a.partial {
            return Err(CliError::usage(format!(
                "merge: {message}: render them with --sample-range, or pass --partial to write the image anyway"
            )));
        }
        eprintln!("warning: {message}");
    }
    let written = match &feature_outputs {
        Some(outputs) => Some(outputs.write(whole.film.image(), &tone, whole.features.as_ref())?),
        None => None,
    };
    if let Some(path) = &a.film_out {
        write_film(path, &whole).map_err(|e| CliError::runtime(e.to_string()))?;
    }
    if !a.quiet {
        let (also, denoised) = match (&written, &feature_outputs) {
            (Some(w), Some(o)) => (w.also_text(o.aovs()), w.denoised_text()),
            _ => (String::new(), String::new()),
        };
        let image = a.output.iter().map(|p| format!("{}{also}", p.display()));
        let outputs: Vec<String> = image.chain(a.film_out.iter().map(|p| p.display().to_string())).collect();
        eprintln!(
            "merged {} films — {w}×{h}, samples {} of {} spp — wrote {}{denoised}",
            a.parts.len(),
            list(&whole.ranges),
            whole.spp,
            outputs.join(" and ")
        );
    }
    Ok(ExitCode::SUCCESS)
}
