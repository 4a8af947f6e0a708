//! Pareto plots with plotters (pure Rust: bitmap backend, ab_glyph text
//! with the committed DejaVu Sans, so no system font is needed).

use super::Table;
use plotters::prelude::*;
use plotters::style::{FontStyle, register_font};
use std::path::Path;
use std::sync::OnceLock;

/// DejaVu Sans (free license: `host-sim/assets/DejaVuSans-LICENSE.txt`).
const FONT: &[u8] = include_bytes!("../../assets/DejaVuSans.ttf");

/// Plot size in pixels (kept small for the repository).
pub const SIZE: (u32, u32) = (640, 400);

fn font_ready() -> Result<(), String> {
    static DONE: OnceLock<Result<(), String>> = OnceLock::new();
    DONE.get_or_init(|| {
        register_font("sans-serif", FontStyle::Normal, FONT)
            .map_err(|_| "the bundled DejaVu Sans font did not load".to_owned())
    })
    .clone()
}

const PALETTE: [RGBColor; 6] = [
    RGBColor(0, 92, 175),
    RGBColor(214, 96, 0),
    RGBColor(0, 140, 70),
    RGBColor(170, 30, 120),
    RGBColor(120, 90, 30),
    RGBColor(90, 90, 90),
];

/// The series a row belongs to: its representation, before any comma.
fn series(repr: &str) -> &str {
    repr.split(',').next().unwrap_or(repr)
}

/// Writes the error-against-time plot of `t` to `file`.
///
/// # Errors
/// A message when drawing or writing fails.
pub fn pareto(file: &Path, t: &Table) -> Result<(), String> {
    font_ready()?;
    let pts: Vec<(f64, f64, &str)> = t
        .rows
        .iter()
        .filter_map(|r| {
            r.err.map(|e| {
                let y = if t.plot_mean { e.mean } else { e.max };
                (r.time.median.max(1e-3), y, r.repr.as_str())
            })
        })
        .collect();
    let err = |e: &dyn std::fmt::Display| format!("plot {}: {e}", file.display());
    let positive: Vec<f64> = pts
        .iter()
        .map(|p| p.1)
        .filter(|&e| e > 0.0 && e.is_finite())
        .collect();
    let ymin_data = positive.iter().copied().fold(f64::INFINITY, f64::min);
    let ymax_data = positive.iter().copied().fold(0.0f64, f64::max);
    let (ymin, ymax) = if positive.is_empty() {
        (1e-3, 1.0)
    } else {
        (ymin_data / 10.0, ymax_data * 4.0)
    };
    let xs = pts.iter().map(|p| p.0);
    let xmin = xs.clone().fold(f64::INFINITY, f64::min) / 2.0;
    let xmax = xs.fold(0.0f64, f64::max) * 2.0;
    let (xmin, xmax) = if xmin.is_finite() && xmax > xmin {
        (xmin, xmax)
    } else {
        (0.1, 10.0)
    };
    // Zero error sits on the bottom edge; infinite on the top.
    let y_of = |e: f64| {
        if e <= 0.0 {
            ymin
        } else if !e.is_finite() {
            ymax
        } else {
            e
        }
    };

    // Drawn into memory and written by the simulator's own PNG encoder
    // (plotters' file encoder would pull in the `image` crate).
    let mut rgb = vec![0u8; SIZE.0 as usize * SIZE.1 as usize * 3];
    let root = BitMapBackend::with_buffer(&mut rgb, SIZE).into_drawing_area();
    root.fill(&WHITE).map_err(|e| err(&e))?;
    let mut chart = ChartBuilder::on(&root)
        .caption(t.title, ("sans-serif", 17))
        .margin(12)
        .x_label_area_size(38)
        .y_label_area_size(64)
        .build_cartesian_2d((xmin..xmax).log_scale(), (ymin..ymax).log_scale())
        .map_err(|e| err(&e))?;
    chart
        .configure_mesh()
        .x_desc("host ns/op (median)")
        .y_desc(format!(
            "{} error ({})",
            if t.plot_mean { "mean" } else { "max" },
            t.unit_short
        ))
        .x_label_formatter(&|v| {
            // Label 1, 2 and 5 of each decade only.
            let lead = v / 10f64.powf(v.log10().floor());
            if [1.0, 2.0, 5.0].iter().any(|d| (lead - d).abs() < 1e-6) {
                format!("{v}")
            } else {
                String::new()
            }
        })
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .label_style(("sans-serif", 12))
        .light_line_style(WHITE.mix(0.0))
        .draw()
        .map_err(|e| err(&e))?;

    // Pareto front: sorted by time, keep rows with a smaller error than
    // every faster row.
    let mut sorted = pts.clone();
    sorted.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    let mut front = Vec::new();
    let mut best = f64::INFINITY;
    for p in &sorted {
        if p.1 < best {
            best = p.1;
            front.push((p.0, y_of(p.1)));
        }
    }
    chart
        .draw_series(LineSeries::new(
            front,
            RGBColor(170, 170, 170).stroke_width(2),
        ))
        .map_err(|e| err(&e))?;

    let mut names: Vec<&str> = Vec::new();
    for p in &pts {
        if !names.contains(&series(p.2)) {
            names.push(series(p.2));
        }
    }
    // Labels: greedy placement around each point, avoiding the labels
    // and points already drawn (pixel rectangles; ~6.2 px per character
    // at 11 px).
    let mut taken: Vec<(i32, i32, i32, i32)> = pts
        .iter()
        .map(|p| {
            let (x, y) = chart.backend_coord(&(p.0, y_of(p.1)));
            (x - 4, y - 4, x + 4, y + 4)
        })
        .collect();
    let overlaps = |a: &(i32, i32, i32, i32), b: &(i32, i32, i32, i32)| {
        a.0 < b.2 && b.0 < a.2 && a.1 < b.3 && b.1 < a.3
    };
    for p in &pts {
        let idx = names.iter().position(|n| *n == series(p.2)).unwrap_or(0);
        let color = PALETTE[idx % PALETTE.len()];
        let label = if p.1 == 0.0 {
            format!("{} (0)", p.2)
        } else {
            p.2.to_owned()
        };
        let w = (label.chars().count() as f64 * 6.2) as i32;
        let h = 12;
        let (px, py) = chart.backend_coord(&(p.0, y_of(p.1)));
        let candidates = [
            (6, -14),
            (6, 2),
            (-w - 6, -14),
            (-w - 6, 2),
            (6, -28),
            (6, 16),
            (-w - 6, -28),
            (-w - 6, 16),
            (-w / 2, -30),
            (-w / 2, 18),
            (6, -42),
            (6, 30),
            (-w - 6, -42),
            (-w - 6, 30),
        ];
        let mut chosen = candidates[0];
        for c in candidates {
            let r = (px + c.0, py + c.1, px + c.0 + w, py + c.1 + h);
            if !taken.iter().any(|t| overlaps(t, &r)) {
                chosen = c;
                break;
            }
        }
        taken.push((
            px + chosen.0,
            py + chosen.1,
            px + chosen.0 + w,
            py + chosen.1 + h,
        ));
        chart
            .draw_series(std::iter::once(
                EmptyElement::at((p.0, y_of(p.1)))
                    + Circle::new((0, 0), 4, color.filled())
                    + Text::new(label, chosen, ("sans-serif", 11).into_font().color(&color)),
            ))
            .map_err(|e| err(&e))?;
    }
    root.present().map_err(|e| err(&e))?;
    drop(chart);
    drop(root);
    crate::image::write_rgb8_png(file, SIZE.0 as u16, SIZE.1 as u16, &rgb)
}
