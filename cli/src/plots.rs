//! Plots, as PNG: the succession's species shares of basal area over the years and stem
//! density against mean stem diameter on log axes beside Reineke's self-thinning line; a
//! terrain's variogram on log axes with its fractal fit and scale range.

use std::io::Write;
use std::path::Path;

use plotters::coord::ranged1d::ValueFormatter;
use plotters::prelude::*;
use plotters::style::{FontStyle, register_font};
use sylva::base::file::AtomicFile;
use sylva::forest::succession::YearStats;
use sylva::terrain::analysis::FractalAnalysis;

use crate::Failure;

/// Whether plots are drawn by this build.
pub(crate) const DRAWN: bool = true;

/// The embedded font: DejaVu Sans cut down to ASCII (its licence is in `assets/`), so plots
/// draw their labels on any machine.
const FONT: &[u8] = include_bytes!("../assets/DejaVuSans-ascii.ttf");

/// Plot size, pixels.
const SIZE: (u32, u32) = (900, 560);

/// A colour per species, in order (the bundled five: oak, birch, spruce, pine, hazel).
const COLOURS: [RGBColor; 8] = [
    RGBColor(140, 90, 40),
    RGBColor(200, 170, 40),
    RGBColor(20, 90, 60),
    RGBColor(60, 150, 120),
    RGBColor(150, 60, 150),
    RGBColor(200, 60, 60),
    RGBColor(60, 60, 200),
    RGBColor(120, 120, 120),
];

fn font() -> Result<(), Failure> {
    register_font("sans-serif", FontStyle::Normal, FONT)
        .map_err(|_| Failure::job("the plots' embedded font could not be read"))
}

/// Draws the chart's grid with its axes named `x` and `y`.
fn axes<'a, X, Y>(
    chart: &mut ChartContext<'a, BitMapBackend<'a>, Cartesian2d<X, Y>>,
    x: &str,
    y: &str,
) -> Result<(), String>
where
    X: Ranged<ValueType: std::fmt::Debug> + ValueFormatter<<X as Ranged>::ValueType>,
    Y: Ranged<ValueType: std::fmt::Debug> + ValueFormatter<<Y as Ranged>::ValueType>,
{
    chart
        .configure_mesh()
        .x_desc(x)
        .y_desc(y)
        .label_style(("sans-serif", 16))
        .draw()
        .map_err(|e| e.to_string())
}

/// Draws the chart's legend, top right.
fn legend<'a, X: Ranged, Y: Ranged>(
    chart: &mut ChartContext<'a, BitMapBackend<'a>, Cartesian2d<X, Y>>,
) -> Result<(), String> {
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font(("sans-serif", 16))
        .draw()
        .map_err(|e| e.to_string())
}

/// Draws with `draw` on an RGB canvas and writes it to `path` as PNG, atomically.
fn write_png(
    path: &Path,
    draw: impl FnOnce(DrawingArea<BitMapBackend, plotters::coord::Shift>) -> Result<(), String>,
) -> Result<(), Failure> {
    font()?;
    let mut rgb = vec![255u8; (SIZE.0 * SIZE.1 * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, SIZE).into_drawing_area();
        draw(root).map_err(|e| Failure::job(format!("{}: {e}", path.display())))?;
    }
    let mut file = AtomicFile::create(path)?;
    {
        let mut encoder = png::Encoder::new(&mut file, SIZE.0, SIZE.1);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        let mut writer = encoder
            .write_header()
            .map_err(|e| Failure::job(format!("{}: {e}", path.display())))?;
        writer
            .write_image_data(&rgb)
            .map_err(|e| Failure::job(format!("{}: {e}", path.display())))?;
    }
    file.flush()
        .map_err(|e| Failure::job(format!("{}: {e}", path.display())))?;
    file.commit()?;
    Ok(())
}

/// Each species' share of the stand's basal area by year, as lines.
pub(crate) fn species_shares(
    path: &Path,
    years: &[YearStats],
    names: &[String],
) -> Result<(), Failure> {
    write_png(path, |root| {
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let last = years.last().map_or(1, |y| y.year.max(1));
        let mut chart = ChartBuilder::on(&root)
            .caption("Species' shares of basal area", ("sans-serif", 26))
            .margin(16)
            .x_label_area_size(44)
            .y_label_area_size(60)
            .build_cartesian_2d(0u32..last, 0f32..100f32)
            .map_err(|e| e.to_string())?;
        axes(&mut chart, "year", "share of basal area (%)")?;
        for (k, name) in names.iter().enumerate() {
            let colour = COLOURS[k % COLOURS.len()];
            let points = years.iter().map(|y| {
                let share = if y.basal_area > 0.0 {
                    100.0 * y.species.get(k).map_or(0.0, |s| s.basal_area) / y.basal_area
                } else {
                    0.0
                };
                (y.year, share)
            });
            chart
                .draw_series(LineSeries::new(points, colour.stroke_width(3)))
                .map_err(|e| e.to_string())?
                .label(name.as_str())
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(3))
                });
        }
        legend(&mut chart)?;
        root.present().map_err(|e| e.to_string())
    })
}

/// Stems per hectare against quadratic mean diameter, both logarithmic, a point per year
/// shaded from early (light) to late (dark); the line of `slope` fitted over the thinning
/// years `phase` (red), and Reineke's line of slope -1.605 through the densest year for
/// comparison (black).
pub(crate) fn self_thinning(
    path: &Path,
    years: &[YearStats],
    phase: &[YearStats],
    slope: Option<f32>,
) -> Result<(), Failure> {
    let points: Vec<(f32, f32, u32)> = years
        .iter()
        .filter(|y| y.stems_per_ha > 0.0 && y.mean_diameter > 0.0)
        .map(|y| (y.mean_diameter, y.stems_per_ha, y.year))
        .collect();
    write_png(path, |root| {
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let (dmin, dmax) = points
            .iter()
            .fold((f32::MAX, f32::MIN), |(a, b), p| (a.min(p.0), b.max(p.0)));
        let (nmin, nmax) = points
            .iter()
            .fold((f32::MAX, f32::MIN), |(a, b), p| (a.min(p.1), b.max(p.1)));
        let (dmin, dmax) = if points.is_empty() {
            (1.0, 100.0)
        } else {
            (dmin * 0.8, dmax * 1.25)
        };
        let (nmin, nmax) = if points.is_empty() {
            (1.0, 10_000.0)
        } else {
            (nmin * 0.8, nmax * 1.25)
        };
        let caption = match slope {
            Some(s) => format!(
                "Self-thinning, years {} to {}: slope {s:.2} (Reineke -1.605)",
                phase.first().map_or(0, |y| y.year),
                phase.last().map_or(0, |y| y.year)
            ),
            None => "Self-thinning".to_string(),
        };
        let mut chart = ChartBuilder::on(&root)
            .caption(caption, ("sans-serif", 26))
            .margin(16)
            .x_label_area_size(44)
            .y_label_area_size(70)
            .build_cartesian_2d((dmin..dmax).log_scale(), (nmin..nmax).log_scale())
            .map_err(|e| e.to_string())?;
        axes(
            &mut chart,
            "quadratic mean diameter (cm)",
            "stems per hectare",
        )?;
        let last = points.last().map_or(1, |p| p.2.max(1)) as f32;
        chart
            .draw_series(points.iter().map(|&(d, n, year)| {
                let t = year as f32 / last;
                let shade = (200.0 * (1.0 - t)) as u8;
                Circle::new((d, n), 3, RGBColor(shade, shade, 255 - shade / 2).filled())
            }))
            .map_err(|e| e.to_string())?
            .label("a year of the stand (light early, dark late)")
            .legend(|(x, y)| Circle::new((x + 10, y), 4, BLUE.filled()));
        if let Some(&(d0, n0, _)) = points
            .iter()
            .max_by(|a, b| (a.1 * a.0.powf(1.605)).total_cmp(&(b.1 * b.0.powf(1.605))))
        {
            let line = [dmin, dmax].map(|d| (d, n0 * (d / d0).powf(-1.605)));
            chart
                .draw_series(LineSeries::new(line, BLACK.stroke_width(2)))
                .map_err(|e| e.to_string())?
                .label("Reineke: N ~ D^-1.605")
                .legend(|(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], BLACK.stroke_width(2))
                });
        }
        let fitted: Vec<(f32, f32)> = phase
            .iter()
            .filter(|y| y.stems_per_ha > 0.0 && y.mean_diameter > 0.0)
            .map(|y| (y.mean_diameter.ln(), y.stems_per_ha.ln()))
            .collect();
        if let (Some(s), false) = (slope, fitted.is_empty()) {
            let n = fitted.len() as f32;
            let (mx, my) = fitted
                .iter()
                .fold((0.0, 0.0), |(a, b), p| (a + p.0 / n, b + p.1 / n));
            let (lo, hi) = fitted
                .iter()
                .fold((f32::MAX, f32::MIN), |(a, b), p| (a.min(p.0), b.max(p.0)));
            let line = [lo, hi].map(|x| (x.exp(), (my + s * (x - mx)).exp()));
            chart
                .draw_series(LineSeries::new(line, RED.stroke_width(3)))
                .map_err(|e| e.to_string())?
                .label(format!("fitted over the thinning years: slope {s:.2}"))
                .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], RED.stroke_width(3)));
        }
        legend(&mut chart)?;
        root.present().map_err(|e| e.to_string())
    })
}

/// The variogram on log axes: half the mean squared height difference against lag, along x,
/// along z (light) and both (dark), the fitted line over the scale range (red, its ends
/// marked), with H in the caption.
pub(crate) fn variogram(
    path: &Path,
    analysis: &FractalAnalysis,
    name: &str,
) -> Result<(), Failure> {
    let v = &analysis.variogram;
    let fit = &analysis.variogram_fit;
    write_png(path, |root| {
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let positive = v
            .iter()
            .flat_map(|p| [p[1], p[2], p[3]])
            .filter(|g| *g > 0.0);
        let (gmin, gmax) = positive.fold((f64::MAX, f64::MIN), |(a, b), g| (a.min(g), b.max(g)));
        let (gmin, gmax) = if gmin < gmax {
            (gmin * 0.7, gmax * 1.4)
        } else {
            (1e-3, 1.0)
        };
        let (lmin, lmax) = (
            v.first().map_or(1.0, |p| p[0]) * 0.8,
            v.last().map_or(10.0, |p| p[0]) * 1.25,
        );
        let caption = format!(
            "{name}: H = {:.2} (D = {:.2}) from {:.0} to {:.0} m",
            fit.hurst, analysis.dimension, fit.scale_range[0], fit.scale_range[1]
        );
        let mut chart = ChartBuilder::on(&root)
            .caption(caption, ("sans-serif", 24))
            .margin(16)
            .x_label_area_size(44)
            .y_label_area_size(80)
            .build_cartesian_2d((lmin..lmax).log_scale(), (gmin..gmax).log_scale())
            .map_err(|e| e.to_string())?;
        axes(&mut chart, "lag (m)", "semivariance (m^2)")?;
        for (column, label, colour) in [
            (1, "along x", RGBColor(150, 180, 230)),
            (2, "along z", RGBColor(150, 210, 160)),
            (3, "both", RGBColor(20, 40, 120)),
        ] {
            chart
                .draw_series(
                    v.iter()
                        .filter(|p| p[column] > 0.0)
                        .map(|p| Circle::new((p[0], p[column]), 4, colour.filled())),
                )
                .map_err(|e| e.to_string())?
                .label(label)
                .legend(move |(x, y)| Circle::new((x + 10, y), 4, colour.filled()));
        }
        let [slope, intercept] = fit.line;
        let [a, b] = fit.scale_range;
        let line = [a, b].map(|l| (l, (slope * l.ln() + intercept).exp()));
        chart
            .draw_series(LineSeries::new(line, RED.stroke_width(3)))
            .map_err(|e| e.to_string())?
            .label(format!("fit: slope 2H = {slope:.2}"))
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], RED.stroke_width(3)));
        for end in [a, b] {
            chart
                .draw_series(LineSeries::new(
                    [(end, gmin), (end, gmax)],
                    RGBColor(160, 160, 160).stroke_width(1),
                ))
                .map_err(|e| e.to_string())?;
        }
        legend(&mut chart)?;
        root.present().map_err(|e| e.to_string())
    })
}
