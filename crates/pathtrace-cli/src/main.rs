//! `pathtrace`: render scenes, measure speed, watch renders live.

mod aov_output;
mod args;
mod bench;
mod bench_bvh;
mod bench_instances;
mod bvh_export;
mod bvh_meshes;
mod bvh_plots;
mod bvh_rays;
mod compare;
mod converge;
mod convert;
mod cpu_clock;
mod destination;
mod interrupt;
mod memory;
mod merge;
mod plot;
mod progress;
mod render;
mod scene_arg;
mod stats_json;
mod view;

use clap::Parser;
use std::process::ExitCode;

/// Exit code for bad arguments or bad input.
const EXIT_USAGE: u8 = 2;

fn main() -> ExitCode {
    let cli = match args::Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => return args::report_parse_error(e),
    };
    let result = match cli.command {
        args::Command::Render(a) => render::run(a),
        args::Command::Bench(a) => bench::run(a),
        args::Command::Compare(a) => compare::run(a),
        args::Command::Converge(a) => converge::run(a),
        args::Command::Convert(a) => convert::run(a),
        args::Command::View(a) => view::run(a),
        args::Command::Merge(a) => merge::run(a),
    };
    match result {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {}", pathtrace_scene::elide::elide_long_runs(&e.message));
            ExitCode::from(e.exit_code)
        }
    }
}

/// An error for the user: one line, and the exit code to leave with.
#[derive(Debug)]
pub struct CliError {
    pub message: String,
    pub exit_code: u8,
}

impl CliError {
    /// Bad input (arguments, scenes): exit code 2.
    pub fn usage(message: impl Into<String>) -> Self {
        Self { message: message.into(), exit_code: EXIT_USAGE }
    }

    /// Something failed while running (writing the image, starting threads): exit code 1.
    pub fn runtime(message: impl Into<String>) -> Self {
        Self { message: message.into(), exit_code: 1 }
    }
}

impl From<pathtrace::render::RenderError> for CliError {
    /// A render the scene or machine cannot do (a camera it cannot build, a film too large) is a
    /// bad request, exit 2; threads that fail to start are a runtime failure, exit 1.
    fn from(e: pathtrace::render::RenderError) -> Self {
        let bad_request = e.is_bad_request();
        let message = e.to_string();
        if bad_request {
            Self::usage(message)
        } else {
            Self::runtime(message)
        }
    }
}
