//! `beam-impact sea`: a scenario's sea record as a motion file (issue 42): the wave elevation and
//! the supports' motion on the record's grid, every value in Rust's shortest round-trip form, so
//! that `run --motion` reads back the very rows a `[sea]` run follows.

use std::io::Write;
use std::path::Path;

use beam_impact::model::motion_table::WAVE_ELEVATION;
use beam_impact::model::sea::settings::{MAX_RECORD_ROWS, MAX_RECORD_TIME, MAX_RECORD_WORK, SAMPLE_INTERVAL_RANGE};
use beam_impact::model::support_motion::{check_motion_value, MOTION_NAMES};
use beam_impact::record::output::{check_distinct, shown, OutputFile};
use beam_impact::{Error, Result};

use super::common::{emit, io, scenario_with_settings};

pub fn sea(file: &Path, set: &[String], duration: f64, out: &Path, sample_interval: Option<f64>) -> Result<()> {
    let scenario = scenario_with_settings(Some(file), set)?;
    let sea = scenario.sea.as_ref().ok_or_else(|| {
        Error::Other(format!("{}: no [sea] section (the sea state and the vessel's RAO file)", shown(file)))
    })?;
    if !(duration.is_finite() && duration > 0.0 && duration <= MAX_RECORD_TIME) {
        return Err(Error::invalid("--duration", format!("> 0 s, at most {MAX_RECORD_TIME:e} s"), duration));
    }
    let dt = sample_interval.unwrap_or(sea.sample_interval);
    let (lo, hi) = SAMPLE_INTERVAL_RANGE;
    if !(lo..=hi).contains(&dt) {
        return Err(Error::invalid("--sample-interval", format!("between {lo:e} and {hi} s"), dt));
    }
    let (first, last) = beam_impact::model::sea::SeaRecord::grid(0.0, duration, dt);
    let rows = (last - first + 1) as u64;
    if rows > MAX_RECORD_ROWS || rows.saturating_mul(u64::from(sea.components)) > MAX_RECORD_WORK {
        return Err(Error::Other(format!(
            "--duration {duration} s every {dt} s is {rows} rows of {} components, more than {MAX_RECORD_ROWS} rows or \
             {MAX_RECORD_WORK:e} component evaluations: raise --sample-interval",
            sea.components
        )));
    }
    // The RAO file and the scenario are inputs: never written over.
    check_distinct(&[("the scenario file", file), ("the RAO file", Path::new(&sea.raos)), ("--out", out)])?;
    let record = sea.record()?;
    let mut output = OutputFile::create(out, true, "cannot create sea record")?;
    let mut text = String::with_capacity(1 << 16);
    text.push_str(&format!("time,{WAVE_ELEVATION}"));
    for name in MOTION_NAMES {
        text.push(',');
        text.push_str(name);
    }
    text.push('\n');
    let (mut sum, mut squares) = (0.0, 0.0);
    // In blocks of rows: the supports' motion as a run's table computes it (the same bits).
    const BLOCK: i64 = 4096;
    for start in (first..=last).step_by(BLOCK as usize) {
        let end = (start + BLOCK - 1).min(last);
        for (k, motion) in (start..=end).zip(record.motions(start, end, dt)) {
            let t = k as f64 * dt;
            let zeta = record.elevation(t);
            sum += zeta;
            squares += zeta * zeta;
            text.push_str(&format!("{t:?},{zeta:?}"));
            for (n, value) in motion.values().iter().enumerate() {
                check_motion_value(n, *value).map_err(|e| {
                    Error::Other(format!(
                        "sea: at the record's time {t} s {e}: the sea drives the supports beyond the model's range"
                    ))
                })?;
                text.push_str(&format!(",{value:?}"));
            }
            text.push('\n');
            if text.len() > 1 << 20 {
                output.file().write_all(text.as_bytes()).map_err(|e| io("cannot write sea record", out, e))?;
                text.clear();
            }
        }
    }
    output.file().write_all(text.as_bytes()).map_err(|e| io("cannot write sea record", out, e))?;
    output.commit()?;
    let n = rows as f64;
    let measured = 4.0 * (squares / n - (sum / n) * (sum / n)).max(0.0).sqrt();
    let spectrum = sea.spectrum();
    let (lo, hi) = sea.frequency_range(sea.rao_table.as_deref());
    emit(&format!(
        "beam-impact: sea record written to {}: {rows} rows, the record's time 0 to {} s every {dt} s\n\
         sea state: Hs {} m, Tp {} s, {} (gamma {:.3}), heading {} deg, seed {}, {} components over {lo:.4} to {hi:.4} \
         rad/s\n\
         the record's 4 sqrt(m0) of the elevation: {measured:.4} m (over its {} s)\n\
         RAO file: {} (SHA-256 {})\n",
        shown(out),
        last as f64 * dt,
        sea.significant_wave_height,
        sea.peak_period,
        sea.spectrum.name(),
        spectrum.gamma,
        sea.heading,
        sea.seed,
        sea.components,
        last as f64 * dt,
        shown(Path::new(&sea.raos)),
        sea.rao_sha256
    ))
}
