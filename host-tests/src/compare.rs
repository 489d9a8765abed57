//! Comparing the core's frame with its float twin and the ideal reference.
//!
//! The float twin is the core itself with the `f64` profile (or `f64-pc`
//! for a perspective-correct profile): the same decisions with no
//! quantization, so `vs_float` isolates the fixed point's error.
//! `vs_ideal` compares with the independent exact renderer and measures
//! everything (subpixel snapping, affine interpolation, quantization).
//!
//! Frames are compared as 8-bit channels: the core renders in RGB888 here,
//! whatever the scene's display format. Packing into RGB565 afterwards
//! drops the low 3 (red, blue) or 2 (green) bits the same way for every
//! profile, and would turn a one-level difference that crosses a 5-bit
//! step into eight.

use crate::core_render::{render_core, CoreError, CoreFrame, CoreProfile};
use crate::ideal::{self, IdealFrame};
use crate::image::{diff_heatmap, write_png};
use crate::metrics::{compare, FrameView, Metrics};
use crate::output::write_atomically;
use crate::scene_file::SceneDesc;
use serde::Serialize;
use std::fmt;
use std::path::Path;

/// A frame and its two references, with the metrics.
#[derive(Clone, Debug)]
pub struct Comparison {
    /// The profile compared.
    pub profile: CoreProfile,
    /// The core with that profile.
    pub fixed: CoreFrame,
    /// The core with its float twin.
    pub float: CoreFrame,
    /// The ideal reference.
    pub ideal: IdealFrame,
    /// The metrics.
    pub metrics: MetricsPair,
}

/// `metrics.json`: the profile against its float twin and the ideal.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MetricsPair {
    /// Against the float twin (quantization alone).
    pub vs_float: Metrics,
    /// Against the ideal reference (everything).
    pub vs_ideal: Metrics,
}

/// Why a comparison failed.
#[derive(Debug)]
pub enum CompareError {
    /// The core refused the scene.
    Core(CoreError),
    /// The ideal reference refused the scene.
    Ideal(ideal::IdealError),
    /// Frames of different sizes (a bug).
    Metrics(crate::metrics::MetricsError),
}

impl fmt::Display for CompareError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Core(e) => write!(f, "{e}"),
            Self::Ideal(e) => write!(f, "ideal reference: {e}"),
            Self::Metrics(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for CompareError {}

/// A view of a core frame for the metrics.
pub fn core_view(f: &CoreFrame) -> FrameView<'_> {
    FrameView {
        width: f.width,
        height: f.height,
        rgb: &f.rgb,
        covered: &f.covered,
        object: None,
    }
}

/// A view of an ideal frame for the metrics, with `rgb` its
/// [`IdealFrame::to_rgb8`] (the caller keeps the pixels).
pub fn ideal_view<'a>(f: &'a IdealFrame, rgb: &'a [[u8; 3]]) -> FrameView<'a> {
    FrameView {
        width: f.width,
        height: f.height,
        rgb,
        covered: &f.covered,
        object: None,
    }
}

/// Renders `desc` with `profile`, its twin and the ideal reference, and
/// compares.
///
/// # Errors
/// [`CompareError`] when a renderer refuses the scene.
pub fn compare_scene(desc: &SceneDesc, profile: CoreProfile) -> Result<Comparison, CompareError> {
    let desc = &SceneDesc {
        pixel_format: crate::scene_file::PixelFormat::Rgb888,
        ..desc.clone()
    };
    let fixed = render_core(desc, Some(profile)).map_err(CompareError::Core)?;
    let float = render_core(desc, Some(profile.twin())).map_err(CompareError::Core)?;
    let ideal = ideal::render(&desc.to_ideal()).map_err(CompareError::Ideal)?;
    let metrics = metrics_of(&fixed, &float, &ideal)?;
    Ok(Comparison {
        profile,
        fixed,
        float,
        ideal,
        metrics,
    })
}

/// The metrics of `fixed` against `float` and `ideal`.
///
/// # Errors
/// [`CompareError::Metrics`] for frames of different sizes.
pub fn metrics_of(
    fixed: &CoreFrame,
    float: &CoreFrame,
    ideal: &IdealFrame,
) -> Result<MetricsPair, CompareError> {
    let irgb = ideal.to_rgb8();
    Ok(MetricsPair {
        vs_float: compare(&core_view(fixed), &core_view(float)).map_err(CompareError::Metrics)?,
        vs_ideal: compare(&core_view(fixed), &ideal_view(ideal, &irgb))
            .map_err(CompareError::Metrics)?,
    })
}

impl Comparison {
    /// The heat-map of the profile's frame against the ideal reference.
    pub fn diff_vs_ideal(&self) -> Vec<[u8; 3]> {
        let irgb = self.ideal.to_rgb8();
        diff_heatmap(&core_view(&self.fixed), &ideal_view(&self.ideal, &irgb)).unwrap_or_default()
    }

    /// The heat-map of the profile's frame against its float twin.
    pub fn diff_vs_float(&self) -> Vec<[u8; 3]> {
        diff_heatmap(&core_view(&self.fixed), &core_view(&self.float)).unwrap_or_default()
    }

    /// Writes `fixed.png`, `float.png`, `ideal.png`, `diff.png` (against
    /// the ideal reference), `diff_float.png` (against the twin) and
    /// `metrics.json` into `dir`, each atomically.
    ///
    /// # Errors
    /// The first I/O error.
    pub fn write(&self, dir: &Path) -> std::io::Result<()> {
        let (w, h) = (self.fixed.width, self.fixed.height);
        write_png(dir.join("fixed.png"), w, h, &self.fixed.rgb)?;
        write_png(dir.join("float.png"), w, h, &self.float.rgb)?;
        write_png(dir.join("ideal.png"), w, h, &self.ideal.to_rgb8())?;
        write_png(dir.join("diff.png"), w, h, &self.diff_vs_ideal())?;
        write_png(dir.join("diff_float.png"), w, h, &self.diff_vs_float())?;
        let json = serde_json::to_string_pretty(&self.metrics).map_err(std::io::Error::other)?;
        write_atomically(&dir.join("metrics.json"), |out| {
            out.write_all(json.as_bytes())
        })
    }
}
