//! SVG plots of error against cost (plotters), with the Pareto front.

use plotters::prelude::*;

use super::summary::Point;
use super::Mode;

/// Indices of the Pareto-optimal points of `(cost, error)` pairs, cheapest
/// first: no other point is at most as costly and at most as wrong while
/// better in one of the two. Points with a non-finite coordinate are never
/// on the front.
pub fn pareto_front(points: &[(f64, f64)]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..points.len())
        .filter(|&i| points[i].0.is_finite() && points[i].1.is_finite())
        .collect();
    order.sort_by(|&a, &b| {
        points[a]
            .0
            .total_cmp(&points[b].0)
            .then(points[a].1.total_cmp(&points[b].1))
    });
    let mut front = Vec::new();
    let mut best = f64::INFINITY;
    for i in order {
        if points[i].1 < best {
            best = points[i].1;
            front.push(i);
        }
    }
    front
}

fn mode_color(m: Mode) -> RGBColor {
    match m {
        Mode::Flat => RGBColor(140, 140, 140),
        Mode::Gouraud => RGBColor(31, 119, 180),
        Mode::Phong => RGBColor(230, 120, 20),
    }
}

/// One plot, log-log: `error` of every point against its cost, the Pareto
/// front joined by a line, ringed and labelled. Returns the SVG text (empty on a drawing
/// error, which only a bug could cause).
pub fn scatter_svg(
    title: &str,
    x_desc: &str,
    y_desc: &str,
    points: &[Point],
    error: impl Fn(&Point) -> f64,
) -> String {
    let xy: Vec<(f64, f64)> = points.iter().map(|p| (p.cost, error(p))).collect();
    let front = pareto_front(&xy);
    let mut svg = String::new();
    let drawn = draw(&mut svg, title, x_desc, y_desc, points, &xy, &front);
    if drawn.is_err() {
        return String::new();
    }
    svg
}

/// A tick label with the digits a power-of-ten scale needs.
fn tick(v: f64) -> String {
    let decimals = if v > 0.0 {
        (-v.log10().floor()).max(0.0) as usize
    } else {
        0
    };
    format!("{v:.decimals$}")
}

/// Errors below this are drawn at it (the log scale has no 0).
pub const ERROR_FLOOR: f64 = 1e-4;

fn draw(
    svg: &mut String,
    title: &str,
    x_desc: &str,
    y_desc: &str,
    points: &[Point],
    xy: &[(f64, f64)],
    front: &[usize],
) -> Result<(), Box<dyn std::error::Error>> {
    let shown: Vec<(f64, f64)> = xy.iter().map(|&(x, y)| (x, y.max(ERROR_FLOOR))).collect();
    let ok = |p: &(f64, f64)| p.0.is_finite() && p.1.is_finite() && p.0 > 0.0;
    let range = |f: fn(&(f64, f64)) -> f64| {
        let lo = shown
            .iter()
            .filter(|p| ok(p))
            .map(f)
            .fold(f64::INFINITY, f64::min);
        let hi = shown.iter().filter(|p| ok(p)).map(f).fold(0.0, f64::max);
        if lo.is_finite() && hi > 0.0 {
            (lo / 1.5, hi * 2.0)
        } else {
            (0.1, 10.0)
        }
    };
    let ((x0, x1), (y0, y1)) = (range(|p| p.0), range(|p| p.1));
    let root = SVGBackend::with_string(svg, (560, 380)).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 16))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(56)
        .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())?;
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .label_style(("sans-serif", 11))
        .light_line_style(RGBColor(245, 245, 245))
        .x_labels(10)
        .y_labels(10)
        .y_label_formatter(&|v| tick(*v))
        .x_label_formatter(&|v| tick(*v))
        .draw()?;
    chart.draw_series(LineSeries::new(
        front.iter().map(|&i| shown[i]),
        ShapeStyle::from(&BLACK).stroke_width(1),
    ))?;
    chart.draw_series(front.iter().map(|&i| {
        EmptyElement::at(shown[i])
            + Circle::new((0, 0), 7, ShapeStyle::from(&BLACK).stroke_width(1))
            + Text::new(points[i].label(), (8, -12), ("sans-serif", 10))
    }))?;
    for mode in Mode::ALL {
        let color = mode_color(mode);
        chart
            .draw_series(
                points
                    .iter()
                    .zip(&shown)
                    .filter(|(p, q)| p.mode == mode && ok(q))
                    .map(|(p, &q)| {
                        let style = if p.profile.is_fixed() {
                            color.filled()
                        } else {
                            ShapeStyle::from(&color).stroke_width(2)
                        };
                        Circle::new(q, 4, style)
                    }),
            )?
            .label(mode.title())
            .legend(move |(x, y)| Circle::new((x, y), 4, color.filled()));
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(RGBColor(200, 200, 200))
        .label_font(("sans-serif", 11))
        .position(SeriesLabelPosition::LowerRight)
        .draw()?;
    root.present()?;
    Ok(())
}

/// A named series of labelled `(x, y)` points.
pub type Series = (String, Vec<(f64, f64, String)>);

/// A small linear plot of named series of `(x, y)` points joined by
/// lines, each point labelled by its series' `labels`. Returns the SVG
/// text (empty on a drawing error, which only a bug could cause).
pub fn line_svg(title: &str, x_desc: &str, y_desc: &str, series: &[Series]) -> String {
    let mut svg = String::new();
    if draw_lines(&mut svg, title, x_desc, y_desc, series).is_err() {
        return String::new();
    }
    svg
}

fn draw_lines(
    svg: &mut String,
    title: &str,
    x_desc: &str,
    y_desc: &str,
    series: &[Series],
) -> Result<(), Box<dyn std::error::Error>> {
    let all: Vec<(f64, f64)> = series
        .iter()
        .flat_map(|(_, p)| p.iter().map(|&(x, y, _)| (x, y)))
        .filter(|p| p.0.is_finite() && p.1.is_finite())
        .collect();
    let span = |f: fn(&(f64, f64)) -> f64| {
        let lo = all.iter().map(f).fold(f64::INFINITY, f64::min);
        let hi = all.iter().map(f).fold(f64::NEG_INFINITY, f64::max);
        if lo.is_finite() && hi.is_finite() {
            let pad = ((hi - lo) * 0.12).max(hi.abs() * 0.05).max(1e-9);
            (lo - pad, hi + pad)
        } else {
            (0.0, 1.0)
        }
    };
    let ((x0, x1), (y0, y1)) = (span(|p| p.0), span(|p| p.1));
    let root = SVGBackend::with_string(svg, (420, 300)).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 14))
        .margin(10)
        .x_label_area_size(36)
        .y_label_area_size(60)
        .build_cartesian_2d(x0..x1, y0..y1)?;
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .label_style(("sans-serif", 10))
        .light_line_style(RGBColor(245, 245, 245))
        .draw()?;
    let colors = [
        RGBColor(31, 119, 180),
        RGBColor(230, 120, 20),
        RGBColor(44, 160, 44),
        RGBColor(140, 140, 140),
    ];
    for (i, (name, pts)) in series.iter().enumerate() {
        let color = colors[i % colors.len()];
        chart
            .draw_series(LineSeries::new(
                pts.iter().map(|&(x, y, _)| (x, y)),
                ShapeStyle::from(&color).stroke_width(2),
            ))?
            .label(name.as_str())
            .legend(move |(x, y)| Circle::new((x, y), 4, color.filled()));
        chart.draw_series(pts.iter().map(|(x, y, label)| {
            EmptyElement::at((*x, *y))
                + Circle::new((0, 0), 3, color.filled())
                + Text::new(label.clone(), (5, -12), ("sans-serif", 9))
        }))?;
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(RGBColor(200, 200, 200))
        .label_font(("sans-serif", 10))
        .position(SeriesLabelPosition::UpperRight)
        .draw()?;
    root.present()?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn front_keeps_only_undominated_points() {
        let pts = [
            (1.0, 5.0), // 0: cheapest
            (2.0, 5.0), // 1: dominated by 0
            (2.0, 3.0), // 2
            (3.0, 4.0), // 3: dominated by 2
            (4.0, 1.0), // 4
            (5.0, 1.0), // 5: dominated by 4
            (f64::NAN, 0.0),
        ];
        assert_eq!(pareto_front(&pts), [0, 2, 4]);
        assert!(pareto_front(&[]).is_empty());
    }
}
