//! The operability figure of a campaign over a grid of sea states (issue 43; `beam-impact campaign
//! --figures DIR`): per heading, Hs against Tp, each cell coloured by its verdict (operable,
//! overloading, a sea the model refuses) and labelled with its overload probability, and the
//! limiting Hs per Tp as a line.

use std::path::{Path, PathBuf};

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::figures::{create_dir, draw_header, write_svg_png, Drawing, LegendEntry, Output, Pen};
use crate::error::{Error, Result};
use crate::studies::campaign::operability::{axes, cell_text, limits, TableCell};
use crate::studies::campaign::Options;

/// Operable cells.
pub const OPERABLE: RGBColor = RGBColor(166, 219, 160);
/// Cells whose overload probability is not shown below the target.
pub const OVERLOADING: RGBColor = RGBColor(244, 165, 130);
/// Sea states the model refuses (a breaking sea).
pub const REFUSED: RGBColor = RGBColor(200, 200, 200);
/// The limit line.
pub const LIMIT: RGBColor = RGBColor(20, 20, 20);

/// One heading's figure.
#[derive(Clone, Debug)]
pub struct OperabilityFigure {
    /// File stem (`operability-heading-180`).
    pub stem: String,
    /// Title.
    pub caption: String,
    /// Lines under the title.
    pub subtitle: Vec<String>,
    /// Each cell: Hs (m), Tp (s), its colour and text.
    pub cells: Vec<(f64, f64, RGBColor, String)>,
    /// The limiting Hs per Tp (m; None: none operable).
    pub limits: Vec<(f64, Option<f64>)>,
}

/// The figures of `cells`, one per heading.
pub fn operability_figures(cells: &[TableCell], options: &Options, note: &str) -> Vec<OperabilityFigure> {
    let (headings, _, _) = axes(cells);
    let all_limits = limits(cells);
    headings
        .iter()
        .map(|&heading| {
            let mine: Vec<&TableCell> = cells.iter().filter(|c| c.heading == heading).collect();
            OperabilityFigure {
                stem: format!("operability-heading-{heading}"),
                caption: format!("Operability: overload probability per loss of the support, heading {heading} deg"),
                subtitle: vec![
                    format!(
                        "green: {} below the target {}; red: not; grey: a sea the model refuses (breaking) or not run. The line: \
                         the largest Hs up to which every cell is green.",
                        if options.on_upper_bound {
                            format!("the {} % upper bound", 100.0 * options.confidence)
                        } else {
                            "the estimate".into()
                        },
                        crate::studies::campaign::summary::significant(options.target)
                    ),
                    note.to_string(),
                ],
                cells: mine
                    .iter()
                    .map(|c| {
                        let color = match &c.outcome {
                            Ok(s) if s.operable => OPERABLE,
                            Ok(_) => OVERLOADING,
                            Err(_) => REFUSED,
                        };
                        (c.significant_wave_height, c.peak_period, color, cell_text(&c.outcome, options.on_upper_bound))
                    })
                    .collect(),
                limits: all_limits
                    .iter()
                    .filter(|l| l.heading == heading)
                    .map(|l| (l.peak_period, l.significant_wave_height))
                    .collect(),
            }
        })
        .collect()
}

/// Half the spacing of sorted `values` (1 for a single value): a cell's half width.
fn half_step(values: &[f64]) -> f64 {
    let mut v: Vec<f64> = values.to_vec();
    v.sort_by(f64::total_cmp);
    v.dedup();
    v.windows(2).map(|w| w[1] - w[0]).fold(f64::INFINITY, f64::min).clamp(1e-3, 2.0) / 2.0
}

impl Drawing for OperabilityFigure {
    fn stem(&self) -> &str {
        &self.stem
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>, _output: Output) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        let err = |e: DrawingAreaErrorKind<DB::ErrorType>| Error::Other(format!("cannot draw {}: {e}", self.stem));
        let legend = [LegendEntry::Line("limiting Hs".into(), LIMIT, Pen::Wide)];
        let body = draw_header(root, &self.caption, &self.subtitle, &legend, Output::Svg, &self.stem)?;
        let hs: Vec<f64> = self.cells.iter().map(|c| c.0).collect();
        let tp: Vec<f64> = self.cells.iter().map(|c| c.1).collect();
        let (dh, dt) = (half_step(&hs), half_step(&tp));
        let range = |v: &[f64], d: f64| {
            let lo = v.iter().copied().fold(f64::INFINITY, f64::min) - d;
            let hi = v.iter().copied().fold(f64::NEG_INFINITY, f64::max) + d;
            lo.max(0.0)..hi
        };
        let mut chart = ChartBuilder::on(&body)
            .margin(20)
            .x_label_area_size(50)
            .y_label_area_size(70)
            .build_cartesian_2d(range(&tp, dt), range(&hs, dh))
            .map_err(err)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc("peak period Tp, s")
            .y_desc("significant wave height Hs, m")
            .label_style(("sans-serif", 16))
            .axis_desc_style(("sans-serif", 18))
            .draw()
            .map_err(err)?;
        chart
            .draw_series(self.cells.iter().map(|&(h, t, color, _)| {
                Rectangle::new([(t - dt * 0.96, h - dh * 0.96), (t + dt * 0.96, h + dh * 0.96)], color.filled())
            }))
            .map_err(err)?;
        let label = TextStyle::from(("sans-serif", 14).into_font()).pos(Pos::new(HPos::Center, VPos::Center));
        chart
            .draw_series(self.cells.iter().map(|(h, t, _, text)| Text::new(text.clone(), (*t, *h), label.clone())))
            .map_err(err)?;
        // The limit: a step line over each column's width at its limiting Hs (the cell's top edge).
        let mut line = Vec::new();
        for &(t, limit) in &self.limits {
            let top = limit.map_or(range(&hs, dh).start, |h| h + dh);
            line.push((t - dt, top));
            line.push((t + dt, top));
        }
        chart.draw_series(std::iter::once(PathElement::new(line, LIMIT.stroke_width(3)))).map_err(err)?;
        root.present().map_err(err)?;
        Ok(())
    }
}

/// Writes each figure as `<stem>.svg` and `<stem>.png` into `dir` (created if missing).
pub fn write_operability_figures(figures: &[OperabilityFigure], dir: &Path) -> Result<Vec<PathBuf>> {
    create_dir(dir)?;
    let mut written = Vec::new();
    for f in figures {
        written.extend(write_svg_png(f, dir)?);
    }
    Ok(written)
}
