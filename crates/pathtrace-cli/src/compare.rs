//! `pathtrace compare`: image metrics against a reference.

use crate::args::CompareArgs;
use crate::CliError;
use pathtrace::film::ToneMapSettings;
use pathtrace::metrics::{compare, difference_image};
use pathtrace_scene::image_io::{read_image, write_image};
use std::process::ExitCode;

pub fn run(a: CompareArgs) -> Result<ExitCode, CliError> {
    if let Some(diff) = &a.diff {
        crate::destination::check_image_destination(diff, "--diff")?;
    }
    let image = read_image(&a.image).map_err(|e| CliError::usage(e.to_string()))?;
    let reference = read_image(&a.reference).map_err(|e| CliError::usage(e.to_string()))?;
    let m = compare(&image, &reference).map_err(|e| {
        CliError::usage(format!("cannot compare {} with {}: {e}", a.image.display(), a.reference.display()))
    })?;
    let marked = match &a.diff {
        Some(path) => {
            let (diff, marked) =
                difference_image(&image, &reference, a.threshold).map_err(|e| CliError::usage(e.to_string()))?;
            write_image(path, &diff, &ToneMapSettings::default()).map_err(|e| CliError::runtime(e.to_string()))?;
            Some(marked)
        }
        None => None,
    };
    if a.json {
        let json = serde_json::json!({
            "mse": m.mse, "rmse": m.rmse, "relative_mse": m.relative_mse,
            "psnr_8bit_db": finite_or_null(m.psnr_8bit), "psnr_linear_db": finite_or_null(m.psnr_linear),
            "ssim": m.ssim, "changed_pixels": marked, "identical": m.mse == 0.0,
        });
        println!("{}", serde_json::to_string_pretty(&json).map_err(|e| CliError::runtime(e.to_string()))?);
    } else {
        println!("MSE            {:.6e}", m.mse);
        println!("RMSE           {:.6e}", m.rmse);
        println!("relative MSE   {:.6e}", m.relative_mse);
        println!("PSNR (8-bit)   {} dB", db(m.psnr_8bit));
        println!("PSNR (linear)  {} dB", db(m.psnr_linear));
        println!("SSIM           {:.4}", m.ssim);
        if let (Some(n), Some(path)) = (marked, &a.diff) {
            let total = image.pixels.len();
            println!(
                "changed pixels {n} of {total} ({:.2}%) > {} steps → {}",
                100.0 * n as f64 / total as f64,
                a.threshold,
                path.display()
            );
        }
    }
    Ok(ExitCode::SUCCESS)
}

/// A PSNR for people: infinite only for identical images (the metrics refuse NaN and infinite
/// pixels), undefined (NaN) for linear PSNR against a black reference.
fn db(v: f64) -> String {
    if v.is_finite() {
        format!("{v:.2}")
    } else if v == f64::INFINITY {
        "∞ (identical)".into()
    } else {
        "undefined (the reference is black)".into()
    }
}

fn finite_or_null(v: f64) -> Option<f64> {
    v.is_finite().then_some(v)
}
