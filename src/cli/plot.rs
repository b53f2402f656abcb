//! `--plot OUT.png`: joint coordinates (top panel) and energy and work (bottom panel) over time.

use std::path::Path;
use std::sync::OnceLock;

use plotters::prelude::*;

/// One plotted column.
pub struct Series {
    /// Variable name (legend).
    pub name: String,
    /// True for `system.energy`/`system.work` (bottom panel).
    pub energy: bool,
    /// (time, value) points.
    pub points: Vec<(f64, f64)>,
}

fn range(series: &[&Series]) -> ((f64, f64), (f64, f64)) {
    let mut t = (f64::INFINITY, f64::NEG_INFINITY);
    let mut y = (f64::INFINITY, f64::NEG_INFINITY);
    for (x, v) in series
        .iter()
        .flat_map(|s| s.points.iter())
        .filter(|(_, v)| v.is_finite())
    {
        t = (t.0.min(*x), t.1.max(*x));
        y = (y.0.min(*v), y.1.max(*v));
    }
    if !t.0.is_finite() {
        t = (0.0, 1.0);
    }
    if !y.0.is_finite() {
        y = (-1.0, 1.0);
    }
    let pad = ((y.1 - y.0) * 0.05).max(1e-9 * (1.0 + y.1.abs()));
    ((t.0, t.1.max(t.0 + 1e-9)), (y.0 - pad, y.1 + pad))
}

fn panel(
    area: &DrawingArea<BitMapBackend<'_>, plotters::coord::Shift>,
    title: &str,
    ylabel: &str,
    series: &[&Series],
) -> Result<(), Box<dyn std::error::Error>> {
    let ((t0, t1), (y0, y1)) = range(series);
    let mut chart = ChartBuilder::on(area)
        .caption(title, ("sans-serif", 22))
        .margin(12)
        .x_label_area_size(36)
        .y_label_area_size(70)
        .build_cartesian_2d(t0..t1, y0..y1)?;
    chart
        .configure_mesh()
        .x_desc("time (s)")
        .y_desc(ylabel)
        .draw()?;
    for (k, s) in series.iter().enumerate() {
        let color = Palette99::pick(k).to_rgba();
        chart
            .draw_series(LineSeries::new(
                s.points.iter().copied().filter(|(_, v)| v.is_finite()),
                color.stroke_width(2),
            ))?
            .label(s.name.clone())
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 18, y)], color.stroke_width(2))
            });
    }
    if !series.is_empty() {
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .draw()?;
    }
    Ok(())
}

/// Registers the embedded DejaVu Sans as the plots' "sans-serif" font, once per process: plots
/// need no fontconfig or installed font, on any platform.
fn register_font() -> Result<(), String> {
    static REGISTERED: OnceLock<Result<(), String>> = OnceLock::new();
    REGISTERED
        .get_or_init(|| {
            plotters::style::register_font("sans-serif", FontStyle::Normal, dejavu::sans::regular())
                .map_err(|_| "the embedded DejaVu Sans font is not a valid font".to_string())
        })
        .clone()
}

/// Draws the two panels into a PNG at `path`.
pub fn draw(path: &Path, model: &str, series: &[Series]) -> Result<(), Box<dyn std::error::Error>> {
    register_font()?;
    let root = BitMapBackend::new(path, (1100, 800)).into_drawing_area();
    root.fill(&WHITE)?;
    let (top, bottom) = root.split_vertically(400);
    let joints: Vec<&Series> = series.iter().filter(|s| !s.energy).collect();
    let energy: Vec<&Series> = series.iter().filter(|s| s.energy).collect();
    panel(
        &top,
        &format!("{model}: joint coordinates"),
        "rad or m",
        &joints,
    )?;
    panel(
        &bottom,
        &format!("{model}: energy and work"),
        "energy, work (J)",
        &energy,
    )?;
    root.present()?;
    Ok(())
}
