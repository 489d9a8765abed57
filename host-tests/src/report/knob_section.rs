//! The knobs a user trades, each a small plot with its table: band rows
//! (RAM against setups and cycles), 16- or 32-bit depth (RAM against the
//! pixels the 16 bits lose), subpixel bits (coverage error against
//! cycles), perspective correction (error against cycles). Chip figures
//! from the firmware's `knobs` build and the profiles' measurements
//! ([`super::chips`]); the subpixel and perspective errors from the host
//! (the same arithmetic: the chips' CRCs equal the host's).

use maud::{html, Markup, PreEscaped};
use serde::{Deserialize, Serialize};

use fixshade::num::{FastSub, Profile, Q16};
use fixshade::target::{PixelFormat, Rgb888};

use super::Error;
use crate::builtin::load_builtin;
use crate::compare::ideal_view;
use crate::core_render::{CoreProfile, CoreScene, Renderer};
use crate::metrics::{compare, FrameView, Metrics};

use super::chip_section::{md, table, Table};
use super::chips::{KnobResult, Measurements};
use super::plot::{line_svg, Series};

/// The frame of built-in `scene` with profile `P` against its ideal frame.
fn vs_ideal<P: Profile<Real = Q16>>(scene: &str) -> Result<Metrics, Error> {
    let desc = load_builtin(scene)?;
    let cs = CoreScene::<Q16>::new(&desc).map_err(|e| Error::input(format!("{scene}: {e}")))?;
    let (w, h) = (desc.width, desc.height);
    let mut r = Renderer::<P, Rgb888>::new(&cs, w, h, 16);
    let (mut rgb, mut covered) = (Vec::new(), Vec::new());
    r.frame(&cs.scene(), |b| {
        rgb.extend(b.pixels().iter().map(|&p| {
            let c = <Rgb888 as PixelFormat>::decode(p);
            [c.r, c.g, c.b]
        }));
        covered.extend(b.depth().unwrap_or(&[]).iter().map(|&d| d != u16::MAX));
    })
    .map_err(|e| Error::input(format!("{scene}: {e}")))?;
    let ideal = super::sweep::ideal_frame(&desc)?;
    let irgb = ideal.to_rgb8();
    compare(
        &FrameView {
            width: w,
            height: h,
            rgb: &rgb,
            covered: &covered,
            object: None,
        },
        &ideal_view(&ideal, &irgb),
    )
    .map_err(|e| Error::input(format!("{scene}: {e}")))
}

/// The knob section (in `results.json` as `knobs`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct KnobSection {
    /// The scene of the knob sweeps.
    pub scene: String,
    /// Band rows.
    pub rows: Table,
    /// Depth bits.
    pub depth: Table,
    /// Subpixel bits.
    pub subpixel: Table,
    /// Perspective correction.
    pub perspective: Table,
    /// (title, SVG) per knob.
    #[serde(skip)]
    pub plots: Vec<(String, String)>,
}

fn m(x: u64) -> String {
    format!("{:.3} M", x as f64 / 1e6)
}

fn strings(v: &[&str]) -> Vec<String> {
    v.iter().map(|s| s.to_string()).collect()
}

impl KnobSection {
    /// Builds the section; `None` when the file has no knob figures.
    ///
    /// # Errors
    /// A scene the host renderers refuse (bad input).
    pub fn new(ms: &Measurements) -> Result<Option<Self>, Error> {
        let Some(scene) = ms.knobs.first().map(|k| k.scene.clone()) else {
            return Ok(None);
        };
        let find = |t: &str, rows: u32, depth: u32, sub: u32| -> Option<&KnobResult> {
            ms.knobs.iter().find(|k| {
                k.target == t && k.rows == rows && k.depth_bits == depth && k.subpixel_bits == sub
            })
        };
        let (m0, m4) = ("thumbv6m-none-eabi", "thumbv7em-none-eabihf");
        let mut rows_list: Vec<u32> = ms
            .knobs
            .iter()
            .filter(|k| k.depth_bits == 16 && k.subpixel_bits == 4)
            .map(|k| k.rows)
            .collect();
        rows_list.sort_unstable();
        rows_list.dedup();
        let cyc = |k: Option<&KnobResult>| k.map_or("–".into(), |k| m(k.frame_cycles()));

        // Band rows.
        let rows = Table {
            head: strings(&[
                "band rows",
                "band + depth RAM B",
                "triangle setups",
                "M0 est. cycles",
                "M4F instructions",
                "RAM with prepared frame and stack (M0) B",
            ]),
            rows: rows_list
                .iter()
                .filter_map(|&r| {
                    let k = find(m0, r, 16, 4)?;
                    Some(vec![
                        r.to_string(),
                        (k.band_bytes + k.depth_bytes).to_string(),
                        k.setups.to_string(),
                        cyc(Some(k)),
                        cyc(find(m4, r, 16, 4)),
                        k.ram.to_string(),
                    ])
                })
                .collect(),
        };
        let rows_pts: Vec<(f64, f64, String)> = rows_list
            .iter()
            .filter_map(|&r| {
                let k = find(m0, r, 16, 4)?;
                Some((
                    (k.band_bytes + k.depth_bytes) as f64 / 1024.0,
                    k.frame_cycles() as f64 / 1e6,
                    format!("{r} rows"),
                ))
            })
            .collect();

        // Depth bits.
        let depth = Table {
            head: strings(&[
                "depth bits",
                "depth band B (16 rows)",
                "M0 est. cycles",
                "M4F instructions",
                "pixels differing from the 32-bit frame",
            ]),
            rows: [16, 32]
                .iter()
                .filter_map(|&d| {
                    let k = find(m0, 16, d, 4)?;
                    Some(vec![
                        d.to_string(),
                        k.depth_bytes.to_string(),
                        cyc(Some(k)),
                        cyc(find(m4, 16, d, 4)),
                        if d == 16 {
                            ms.knob_depth32_vs_depth16_pixels.to_string()
                        } else {
                            "0".into()
                        },
                    ])
                })
                .collect(),
        };
        let depth_pts: Vec<(f64, f64, String)> = [16, 32]
            .iter()
            .filter_map(|&d| {
                let k = find(m0, 16, d, 4)?;
                Some((
                    k.depth_bytes as f64 / 1024.0,
                    k.frame_cycles() as f64 / 1e6,
                    format!("{d}-bit"),
                ))
            })
            .collect();

        // Subpixel bits: coverage against the ideal on the host.
        let subs: Vec<(u32, Metrics)> = vec![
            (2, vs_ideal::<FastSub<2>>(&scene)?),
            (3, vs_ideal::<FastSub<3>>(&scene)?),
            (4, vs_ideal::<FastSub<4>>(&scene)?),
            (6, vs_ideal::<FastSub<6>>(&scene)?),
            (8, vs_ideal::<FastSub<8>>(&scene)?),
        ];
        let subpixel = Table {
            head: strings(&[
                "subpixel bits",
                "coverage mismatches vs ideal",
                "mean error vs ideal",
                "M0 est. cycles",
                "M4F instructions",
            ]),
            rows: subs
                .iter()
                .map(|(b, mt)| {
                    vec![
                        b.to_string(),
                        mt.coverage_mismatch.to_string(),
                        format!("{:.4}", mt.mean_abs_error),
                        cyc(find(m0, 16, 16, *b)),
                        cyc(find(m4, 16, 16, *b)),
                    ]
                })
                .collect(),
        };
        let sub_pts: Vec<(f64, f64, String)> = subs
            .iter()
            .filter_map(|(b, mt)| {
                let k = find(m0, 16, 16, *b)?;
                Some((
                    k.frame_cycles() as f64 / 1e6,
                    mt.coverage_mismatch as f64,
                    format!("{b} bits"),
                ))
            })
            .collect();

        // Perspective correction: fast against fast-pc per firmware scene.
        let mut persp_rows = Vec::new();
        let mut series: Vec<Series> = vec![
            ("affine (fast)".into(), vec![]),
            ("perspective-correct (fast-pc)".into(), vec![]),
        ];
        for r in ms
            .results
            .iter()
            .filter(|r| r.target == m0 && r.profile == "fast" && r.mode.is_some())
        {
            let pc = ms
                .results
                .iter()
                .find(|x| x.target == m0 && x.profile == "fast-pc" && x.scene == r.scene);
            let Some(pc) = pc else { continue };
            let desc = load_builtin(&r.scene)?;
            let ideal = super::sweep::ideal_frame(&desc)?;
            let irgb = ideal.to_rgb8();
            let iview = ideal_view(&ideal, &irgb);
            let err = |p: CoreProfile| -> Result<f64, Error> {
                let f = super::sweep::rgb_frame(&desc, p)?;
                Ok(compare(&crate::compare::core_view(&f), &iview)
                    .map_err(|e| Error::input(format!("{}: {e}", r.scene)))?
                    .mean_abs_error)
            };
            let (ea, ep) = (err(CoreProfile::Fast)?, err(CoreProfile::FastPc)?);
            persp_rows.push(vec![
                r.scene.clone(),
                format!("{ea:.3}"),
                format!("{ep:.3}"),
                m(r.frame_cycles()),
                m(pc.frame_cycles()),
            ]);
            series[0]
                .1
                .push((r.frame_cycles() as f64 / 1e6, ea, r.scene.clone()));
            series[1]
                .1
                .push((pc.frame_cycles() as f64 / 1e6, ep, String::new()));
        }
        for s in &mut series {
            s.1.sort_by(|a, b| a.0.total_cmp(&b.0));
        }
        let perspective = Table {
            head: strings(&[
                "scene",
                "fast: mean error vs ideal",
                "fast-pc",
                "fast: M0 est. cycles",
                "fast-pc",
            ]),
            rows: persp_rows,
        };

        let plots = vec![
            (
                "Band rows".to_string(),
                line_svg(
                    &format!("band rows: RAM vs cycles ({scene}, M0)"),
                    "band + depth band, KiB",
                    "M est. M0 cycles / frame",
                    &[("fast, 16-bit depth".into(), rows_pts)],
                ),
            ),
            (
                "Depth bits".to_string(),
                line_svg(
                    &format!("depth bits: RAM vs cycles ({scene}, M0)"),
                    "depth band (16 rows), KiB",
                    "M est. M0 cycles / frame",
                    &[("fast, 16 rows".into(), depth_pts)],
                ),
            ),
            (
                "Subpixel bits".to_string(),
                line_svg(
                    &format!("subpixel bits: coverage vs cycles ({scene}, M0)"),
                    "M est. M0 cycles / frame",
                    "pixels covered unlike the ideal",
                    &[("fast".into(), sub_pts)],
                ),
            ),
            (
                "Perspective correction".to_string(),
                line_svg(
                    "perspective correction: error vs cycles (M0)",
                    "M est. M0 cycles / frame",
                    "mean error vs ideal (levels)",
                    &series,
                ),
            ),
        ];
        Ok(Some(Self {
            scene,
            rows,
            depth,
            subpixel,
            perspective,
            plots,
        }))
    }

    fn parts(&self) -> [(&str, &Table, &str); 4] {
        [
            ("Band rows", &self.rows, "Taller bands cost RAM (colour and depth band) and save per-band work (clearing, admitting and resuming the active triangles); each triangle is set up once unless more triangles are active at a band border than the pool holds; the frame is the same byte for byte."),
            ("Depth bits", &self.depth, "A 32-bit depth band doubles the depth RAM; the pixels column counts where the 16-bit frame differs from the 32-bit one (depth resolution lost: z-fighting), on the host."),
            ("Subpixel bits", &self.subpixel, "Finer snapping moves edges closer to the exact ones (coverage against the ideal, host) at about the same cost; the range is 1 to 8 bits."),
            ("Perspective correction", &self.perspective, "The -pc profiles interpolate colours and normals perspective-correctly (one division per pixel); errors against the ideal of the scene's own shading, host."),
        ]
    }

    /// The section's HTML.
    pub fn html(&self) -> Markup {
        html! {
            h2 id="knobs" { "Knobs: what each trades on the chips" }
            p.note { "Band rows, depth bits and subpixel bits on " (self.scene) " with the fast profile (the firmware's knobs build, under QEMU; est. M0 cycles, an estimate, and M4F instructions); perspective correction from the profiles' measurements. The knobs build takes the band height and depth format as parameters, so its frames cost a few per cent more than the default build's (compare the knob variants with each other)." }
            @for ((title, t, note), (_, svg)) in self.parts().iter().zip(&self.plots) {
                h3 { (title) }
                p.note { (note) }
                div.plots {
                    (PreEscaped(svg.find("<svg").map_or(svg.as_str(), |i| &svg[i..])))
                    (table(t))
                }
            }
        }
    }

    /// The section in Markdown.
    pub fn markdown(&self) -> String {
        let mut s = format!(
            "## Knobs: what each trades on the chips\n\nOn {} with the fast profile.\n",
            self.scene
        );
        for (title, t, note) in self.parts() {
            s += &format!("\n### {title}\n\n{note}\n\n{}", md(t));
        }
        s
    }
}
