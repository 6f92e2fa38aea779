//! A vessel's motion RAOs (response amplitude operators) per frequency and wave heading, six
//! degrees of freedom, as complex numbers, parsed from our CSV or from VERES's `.re1` text.
//!
//! **Axes and signs** (docs/moving-supports.md): x forward from the motion reference point, y to
//! port, z up; surge, sway, heave along them (m per m of wave amplitude); roll, pitch, yaw the
//! right-handed rotations about them (rad per m here; deg per m in our CSV): roll positive
//! starboard down, pitch positive bow down, yaw positive bow to port.
//!
//! **Heading** beta, deg: the direction the waves travel, measured from the bow towards port:
//! 180 head seas (waves from ahead), 0 following seas, 90 beam seas from starboard (travelling
//! to port), 270 from port.
//!
//! **Phase**: H_j = |H_j| e^(i eps_j) means x_j(t) = |H_j| zeta_a cos(w t + eps_j) when the wave
//! elevation at the motion reference point is zeta_a cos(w t): eps_j is the response's phase lead.
//!
//! **Our CSV** (`#` comment lines and blank lines skipped): the header
//! `frequency,heading,surge,surge_phase,sway,sway_phase,heave,heave_phase,roll,roll_phase,pitch,pitch_phase,yaw,yaw_phase`
//! (any order), then one row per (frequency, heading) of a full grid in any order: frequency
//! rad/s, heading deg, amplitudes m/m (surge, sway, heave) and deg/m (roll, pitch, yaw), phases
//! deg.
//!
//! **VERES `.re1`** ("MOTION TRANSFER FUNCTIONS", ShipX; the layout as MSS's `read_veres_TF`
//! reads it): six header lines of text, then rho g; Lpp B T; LCG VCG; the counts of speeds,
//! headings, frequencies and degrees of freedom; then per speed a line (speed, sinkage, trim and
//! the motion reference point), per heading a line (deg), per frequency a line (rad/s) and one
//! line per degree of freedom: its number, real and imaginary part. VERES's axes are x aft, y to
//! starboard, z up, its rotations right-handed in rad/m, its heading h = 0 head seas measured in
//! its own axes, and x_j(t) = Re(H_j zeta_a e^(i w t)) (MSS converts with T = diag(-1, 1, -1, -1,
//! 1, -1) to its x forward, y starboard, z down axes). So ours are surge, sway, roll and pitch
//! negated, heave and yaw as they are, at beta = h + 180 deg. The tests
//! `sea_raos::veres_supply_vessel_*` prove it on MSS's supply vessel against a long wave's limits:
//! heave 1 at phase 0 in every heading; pitch the wave slope, i k cos(beta) (in head seas -90 deg:
//! the bow goes down a quarter period after the crest passes the reference point); surge and sway
//! the particles' excursion, -i cos(beta) and -i sin(beta); roll towards where beam waves travel.
//!
//! **Headings a file lacks**: a file whose headings all lie in 0..180 deg or all in 180..360 deg
//! (VERES writes 0..180 of its own, ours 180..360) is completed by port-starboard symmetry: the
//! response at 360 - beta is the one at beta with sway, roll and yaw negated. Between headings
//! the complex RAOs are interpolated linearly, with neighbours at most [`MAX_HEADING_GAP`] apart
//! (around the circle); between frequencies linearly, inside the file's range only (the sea's
//! components are kept inside it: `crate::model::sea::settings`).

use nalgebra::Complex;

/// Names of the six degrees of freedom, in order.
pub const DOF_NAMES: [&str; 6] = ["surge", "sway", "heave", "roll", "pitch", "yaw"];

/// The CSV's columns.
pub const CSV_COLUMNS: [&str; 14] = [
    "frequency",
    "heading",
    "surge",
    "surge_phase",
    "sway",
    "sway_phase",
    "heave",
    "heave_phase",
    "roll",
    "roll_phase",
    "pitch",
    "pitch_phase",
    "yaw",
    "yaw_phase",
];

/// Most frequencies a table may have.
pub const MAX_FREQUENCIES: usize = 2000;
/// Most headings a table may have (every degree).
pub const MAX_HEADINGS: usize = 360;
/// Most data rows (CSV) or RAO lines (`.re1`) read: 200 000, a 550 x 360 grid.
pub const MAX_ROWS: usize = 200_000;
/// Largest frequency, rad/s (a 0.06 s wave: beyond any vessel's response).
pub const MAX_FREQUENCY: f64 = 100.0;
/// Largest translation RAO, m/m.
pub const MAX_TRANSLATION: f64 = 100.0;
/// Largest rotation RAO, rad/m (100 rad/m: 5730 deg per m of wave).
pub const MAX_ROTATION: f64 = 100.0;
/// Largest gap between two headings interpolated between, deg.
pub const MAX_HEADING_GAP: f64 = 45.0;

/// Where a table came from.
#[derive(Clone, Debug, PartialEq)]
pub enum RaoSource {
    /// Our CSV.
    Csv,
    /// A VERES `.re1` file: its ship's name, the speed used (m/s) and its motion reference point
    /// (x from Lpp/2, positive aft, and z above the baseline, m).
    Veres {
        /// The ship's name line.
        ship: String,
        /// The speed whose block was read, m/s (0).
        speed: f64,
        /// The motion reference point's x (VERES: from Lpp/2, aft), m.
        reference_x: f64,
        /// The motion reference point's z above the baseline, m.
        reference_z: f64,
    },
}

/// A vessel's RAO grid: frequencies x headings, six complex RAOs each (see the module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct RaoTable {
    /// Angular frequencies, rad/s, strictly ascending.
    pub frequencies: Vec<f64>,
    /// Headings, deg, strictly ascending in [0, 360).
    pub headings: Vec<f64>,
    /// Heading-major: `values[h * frequencies.len() + f]`, surge to yaw, translations m/m,
    /// rotations rad/m.
    pub values: Vec<[Complex<f64>; 6]>,
    /// Headings the file gave (the others were completed by symmetry).
    pub given_headings: usize,
    /// Where it came from.
    pub source: RaoSource,
}

/// A number's cell as an error quotes it.
fn quote(cell: &str) -> String {
    crate::model::motion_table::quote_cell(cell)
}

fn is_rotation(dof: usize) -> bool {
    dof >= 3
}

/// Checks one RAO's amplitude (in its file's unit: `scale` converts to m/m or rad/m).
fn check_amplitude(dof: usize, value: f64, unit: &str, scale: f64) -> Result<(), String> {
    let limit = if is_rotation(dof) { MAX_ROTATION } else { MAX_TRANSLATION };
    if value.is_finite() && value >= 0.0 && value * scale <= limit {
        return Ok(());
    }
    Err(format!("{} = {value} {unit} is not an amplitude from 0 to {} {unit}", DOF_NAMES[dof], limit / scale))
}

/// A heading in [0, 360) (-0 as 0).
fn normalise(heading: f64) -> f64 {
    let h = heading.rem_euclid(360.0);
    if h == 0.0 || h >= 360.0 {
        0.0
    } else {
        h
    }
}

/// One grid point as read: heading (deg, ours), frequency, the six RAOs, and where (for errors).
struct Point {
    heading: f64,
    frequency: f64,
    values: [Complex<f64>; 6],
    line: usize,
}

impl RaoTable {
    /// The grid from its points: sorted, complete (every heading with every frequency, each
    /// once), within the limits; then completed by symmetry where one-sided.
    fn from_points(mut points: Vec<Point>, source: RaoSource) -> Result<RaoTable, String> {
        if points.is_empty() {
            return Err("no RAO rows".into());
        }
        points.sort_by(|a, b| a.heading.total_cmp(&b.heading).then(a.frequency.total_cmp(&b.frequency)));
        for pair in points.windows(2) {
            if pair[0].heading == pair[1].heading && pair[0].frequency == pair[1].frequency {
                return Err(format!(
                    "heading {} deg, frequency {} rad/s is given twice (lines {} and {})",
                    pair[0].heading,
                    pair[0].frequency,
                    pair[0].line.min(pair[1].line),
                    pair[0].line.max(pair[1].line)
                ));
            }
        }
        let mut headings: Vec<f64> = points.iter().map(|p| p.heading).collect();
        headings.dedup();
        let mut frequencies: Vec<f64> = points.iter().map(|p| p.frequency).collect();
        frequencies.sort_by(f64::total_cmp);
        frequencies.dedup();
        if headings.len() > MAX_HEADINGS {
            return Err(format!("{} headings, more than {MAX_HEADINGS}", headings.len()));
        }
        if frequencies.len() > MAX_FREQUENCIES {
            return Err(format!("{} frequencies, more than {MAX_FREQUENCIES}", frequencies.len()));
        }
        if frequencies.len() < 2 {
            return Err(format!("{} frequency: at least 2 are needed to interpolate between", frequencies.len()));
        }
        let nf = frequencies.len();
        if points.len() != headings.len() * nf {
            // Name the first heading that lacks a frequency.
            for (k, heading) in headings.iter().enumerate() {
                let have: Vec<f64> = points.iter().filter(|p| p.heading == *heading).map(|p| p.frequency).collect();
                if let Some(missing) = frequencies.iter().find(|f| !have.contains(f)) {
                    return Err(format!(
                        "incomplete grid: heading {heading} deg has no row at frequency {missing} rad/s ({} of {} \
                         frequencies; every heading needs every frequency)",
                        have.len(),
                        nf
                    ));
                }
                debug_assert!(k < headings.len());
            }
            return Err(format!(
                "incomplete grid: {} rows for {} headings x {nf} frequencies",
                points.len(),
                headings.len()
            ));
        }
        let given_headings = headings.len();
        let mut values: Vec<[Complex<f64>; 6]> = points.iter().map(|p| p.values).collect();
        // Port-starboard symmetry for a one-sided file.
        let starboard_side = headings.iter().all(|h| *h <= 180.0);
        let port_side = headings.iter().all(|h| *h == 0.0 || *h >= 180.0);
        if starboard_side || port_side {
            let mut all: Vec<(f64, Vec<[Complex<f64>; 6]>)> =
                headings.iter().enumerate().map(|(k, h)| (*h, values[k * nf..(k + 1) * nf].to_vec())).collect();
            for (k, h) in headings.iter().enumerate() {
                let mirror = normalise(360.0 - h);
                if headings.contains(&mirror) {
                    continue;
                }
                let column = values[k * nf..(k + 1) * nf]
                    .iter()
                    .map(|v| {
                        let mut m = *v;
                        for dof in [1, 3, 5] {
                            m[dof] = -m[dof];
                        }
                        m
                    })
                    .collect();
                all.push((mirror, column));
            }
            all.sort_by(|a, b| a.0.total_cmp(&b.0));
            headings = all.iter().map(|a| a.0).collect();
            values = all.into_iter().flat_map(|a| a.1).collect();
        }
        Ok(RaoTable { frequencies, headings, values, given_headings, source })
    }

    /// Parses our CSV (see the module docs). The error is one line naming the line and column.
    pub fn parse_csv(text: &str) -> Result<RaoTable, String> {
        let mut lines = text
            .lines()
            .enumerate()
            .map(|(i, l)| (i + 1, l.trim()))
            .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
        let (header_line, header) = lines.next().ok_or("no header line (frequency, heading and the six RAOs)")?;
        let names: Vec<&str> = header.split(',').map(|c| c.trim().trim_matches('"')).collect();
        if !names.contains(&"frequency") || !names.contains(&"heading") {
            // Not an RAO header: nothing of it is quoted (the file may be any file a scenario named).
            return Err(format!(
                "line {header_line} is not an RAO CSV header: it needs the columns {}",
                CSV_COLUMNS.join(",")
            ));
        }
        let mut slots = Vec::with_capacity(names.len());
        for name in &names {
            let Some(k) = CSV_COLUMNS.iter().position(|c| c == name) else {
                return Err(format!(
                    "line {header_line}: unknown column `{}` (expected {})",
                    quote(name),
                    CSV_COLUMNS.join(",")
                ));
            };
            if slots.contains(&k) {
                return Err(format!("line {header_line}: column `{name}` appears twice"));
            }
            slots.push(k);
        }
        if let Some(missing) = CSV_COLUMNS.iter().enumerate().find(|(k, _)| !slots.contains(k)) {
            return Err(format!("line {header_line}: no column `{}` (expected {})", missing.1, CSV_COLUMNS.join(",")));
        }
        let mut points = Vec::new();
        for (line, row) in lines {
            if points.len() >= MAX_ROWS {
                return Err(format!("more than {MAX_ROWS} rows (line {line})"));
            }
            let fields: Vec<&str> = row.split(',').map(str::trim).collect();
            if fields.len() != names.len() {
                return Err(format!("line {line}: {} fields, the header has {} columns", fields.len(), names.len()));
            }
            let mut v = [0.0; 14];
            for (c, field) in fields.iter().enumerate() {
                let value: f64 = field
                    .parse()
                    .map_err(|_| format!("line {line}: `{}` = `{}` is not a number", names[c], quote(field)))?;
                if !value.is_finite() {
                    return Err(format!("line {line}: `{}` = {value} is not finite", names[c]));
                }
                v[slots[c]] = value;
            }
            let (frequency, heading) = (v[0], v[1]);
            if !(frequency > 0.0 && frequency <= MAX_FREQUENCY) {
                return Err(format!("line {line}: frequency = {frequency} rad/s is not > 0 and <= {MAX_FREQUENCY}"));
            }
            if !(-360.0..=360.0).contains(&heading) {
                return Err(format!("line {line}: heading = {heading} deg is not between -360 and 360"));
            }
            let mut values = [Complex::new(0.0, 0.0); 6];
            for dof in 0..6 {
                let (amplitude, phase) = (v[2 + 2 * dof], v[3 + 2 * dof]);
                let (unit, scale) =
                    if is_rotation(dof) { ("deg/m", std::f64::consts::PI / 180.0) } else { ("m/m", 1.0) };
                check_amplitude(dof, amplitude, unit, scale).map_err(|e| format!("line {line}: {e}"))?;
                if phase.abs() > 3600.0 {
                    return Err(format!("line {line}: {}_phase = {phase} deg is beyond +-3600", DOF_NAMES[dof]));
                }
                let radians = phase.to_radians();
                values[dof] =
                    Complex::new(amplitude * scale * libm::cos(radians), amplitude * scale * libm::sin(radians));
            }
            points.push(Point { heading: normalise(heading), frequency, values, line });
        }
        RaoTable::from_points(points, RaoSource::Csv)
    }

    /// Parses VERES's `.re1` motion transfer functions (see the module docs): the first speed
    /// block at speed 0 (a vessel holding station), converted to our axes, phases and headings.
    pub fn parse_re1(text: &str) -> Result<RaoTable, String> {
        let mut lines = text.lines().enumerate().map(|(i, l)| (i + 1, l));
        let first = lines.next().map(|l| l.1).unwrap_or("");
        if !first.contains("MOTION TRANSFER FUNCTIONS") {
            return Err("line 1 is not a VERES motion transfer function header (MOTION TRANSFER FUNCTIONS)".into());
        }
        let mut ship = String::new();
        for _ in 2..=6 {
            let (_, l) = lines.next().ok_or("the file ends inside its header (6 lines of text)")?;
            if let Some(name) = l.trim().strip_prefix("Ship name:") {
                ship = crate::error::bounded_line(name.trim());
            }
        }
        let mut numbers = |what: &str, count: usize| -> Result<(usize, Vec<f64>), String> {
            let (line, l) = lines.next().ok_or_else(|| format!("the file ends before its {what}"))?;
            let values: Vec<f64> = l
                .split_whitespace()
                .take(count + 1)
                .map(|t| t.parse::<f64>())
                .collect::<Result<_, _>>()
                .map_err(|_| format!("line {line}: {what}: not {count} numbers"))?;
            if values.len() != count || values.iter().any(|v| !v.is_finite()) {
                return Err(format!("line {line}: {what}: expected {count} finite numbers, got {}", values.len()));
            }
            Ok((line, values))
        };
        numbers("density and gravity", 2)?;
        numbers("main dimensions (Lpp, B, T)", 3)?;
        numbers("centre of gravity (LCG, VCG)", 2)?;
        let (line, counts) = numbers("counts of speeds, headings, frequencies and degrees of freedom", 4)?;
        let whole = |x: f64, min: f64, max: usize, what: &str| -> Result<usize, String> {
            if x.fract() == 0.0 && x >= min && x <= max as f64 {
                Ok(x as usize)
            } else {
                Err(format!("line {line}: {x} {what}, expected {min} to {max}"))
            }
        };
        let speeds = whole(counts[0], 1.0, 100, "speeds")?;
        let nhead = whole(counts[1], 1.0, 180, "headings")?;
        let nfreq = whole(counts[2], 2.0, MAX_FREQUENCIES, "frequencies")?;
        let ndof = whole(counts[3], 6.0, 6, "degrees of freedom")?;
        if nhead * nfreq * ndof > MAX_ROWS {
            return Err(format!(
                "line {line}: {nhead} headings x {nfreq} frequencies x {ndof}, more than {MAX_ROWS} RAO lines"
            ));
        }
        // VERES to ours: x aft -> forward, y starboard -> port, z up; rotations alike.
        let sign = [-1.0, -1.0, 1.0, -1.0, -1.0, 1.0];
        for _ in 0..speeds {
            let (speed_line, speed) = numbers("speed line (speed, sinkage, trim, motion point x and z)", 5)?;
            let at_rest = speed[0] == 0.0;
            let mut points = Vec::with_capacity(if at_rest { nhead * nfreq } else { 0 });
            let mut first_frequencies: Vec<f64> = Vec::new();
            for h in 0..nhead {
                let (hl, heading) = numbers("heading", 1)?;
                let heading = heading[0];
                if !(0.0..=360.0).contains(&heading) {
                    return Err(format!("line {hl}: heading {heading} deg is not between 0 and 360"));
                }
                let mut previous = 0.0;
                for f in 0..nfreq {
                    let (fl, frequency) = numbers("frequency", 1)?;
                    let frequency = frequency[0];
                    if !(frequency > previous && frequency <= MAX_FREQUENCY) {
                        return Err(format!(
                            "line {fl}: frequency {frequency} rad/s does not follow {previous} rad/s (frequencies must \
                             increase, up to {MAX_FREQUENCY})"
                        ));
                    }
                    if h == 0 {
                        first_frequencies.push(frequency);
                    } else if first_frequencies[f] != frequency {
                        return Err(format!(
                            "line {fl}: frequency {frequency} rad/s, where the first heading has {} rad/s (every heading \
                             needs the same frequencies)",
                            first_frequencies[f]
                        ));
                    }
                    previous = frequency;
                    let mut values = [Complex::new(0.0, 0.0); 6];
                    let mut seen = [false; 6];
                    for _ in 0..ndof {
                        let (dl, d) = numbers("degree of freedom, real and imaginary part", 3)?;
                        let dof = d[0];
                        if !(dof.fract() == 0.0 && (1.0..=6.0).contains(&dof)) || seen[dof as usize - 1] {
                            return Err(format!("line {dl}: degree of freedom {dof}, expected each of 1 to 6 once"));
                        }
                        let k = dof as usize - 1;
                        seen[k] = true;
                        let value = Complex::new(sign[k] * d[1], sign[k] * d[2]);
                        check_amplitude(k, value.norm(), if is_rotation(k) { "rad/m" } else { "m/m" }, 1.0)
                            .map_err(|e| format!("line {dl}: {e}"))?;
                        values[k] = value;
                    }
                    if at_rest {
                        let ours = normalise(heading + 180.0);
                        points.push(Point { heading: ours, frequency, values, line: fl });
                    }
                }
            }
            if at_rest {
                let source = RaoSource::Veres { ship, speed: 0.0, reference_x: speed[3], reference_z: speed[4] };
                return RaoTable::from_points(points, source).map_err(|e| format!("speed 0 (line {speed_line}): {e}"));
            }
        }
        Err(format!("no block at speed 0 among its {speeds} speed(s): the record is for a vessel holding station"))
    }

    /// Parses `text` as `.re1` when its first line says MOTION TRANSFER FUNCTIONS, else as our CSV.
    pub fn parse(text: &str) -> Result<RaoTable, String> {
        if text.lines().next().is_some_and(|l| l.contains("MOTION TRANSFER FUNCTIONS")) {
            RaoTable::parse_re1(text)
        } else {
            RaoTable::parse_csv(text)
        }
    }

    /// The lowest and highest frequency, rad/s.
    pub fn frequency_range(&self) -> (f64, f64) {
        (self.frequencies[0], self.frequencies[self.frequencies.len() - 1])
    }

    /// The RAOs at every frequency for heading `beta` (deg): the file's own column, or the linear
    /// interpolation between its two neighbours around the circle (at most [`MAX_HEADING_GAP`]
    /// apart; a table of one heading is used at that heading only).
    pub fn at_heading(&self, beta: f64) -> Result<Vec<[Complex<f64>; 6]>, String> {
        let beta = normalise(beta);
        let nf = self.frequencies.len();
        let column = |k: usize| &self.values[k * nf..(k + 1) * nf];
        if let Some(k) = self.headings.iter().position(|h| *h == beta) {
            return Ok(column(k).to_vec());
        }
        let n = self.headings.len();
        if n == 1 {
            return Err(format!("the RAO file has heading {} deg only, not {beta} deg", self.headings[0]));
        }
        // The neighbours: the last heading below beta and the next above (wrapping round 360).
        let above = self.headings.partition_point(|h| *h < beta);
        let (lo, hi) = ((above + n - 1) % n, above % n);
        let (h_lo, h_hi) = (self.headings[lo], self.headings[hi]);
        let gap = (h_hi - h_lo).rem_euclid(360.0);
        if gap > MAX_HEADING_GAP {
            return Err(format!(
                "heading {beta} deg falls between the RAO file's headings {h_lo} and {h_hi} deg, {gap} deg apart (at most \
                 {MAX_HEADING_GAP} deg are interpolated across)"
            ));
        }
        let t = (beta - h_lo).rem_euclid(360.0) / gap;
        Ok(column(lo).iter().zip(column(hi)).map(|(a, b)| std::array::from_fn(|j| a[j] + (b[j] - a[j]) * t)).collect())
    }

    /// The RAOs of `column` (from [`Self::at_heading`]) at frequency `w`, linear between the
    /// neighbouring frequencies; `None` outside the table's range.
    pub fn at_frequency(&self, column: &[[Complex<f64>; 6]], w: f64) -> Option<[Complex<f64>; 6]> {
        let (lo, hi) = self.frequency_range();
        if !(w >= lo && w <= hi) {
            return None;
        }
        let k = self.frequencies.partition_point(|f| *f <= w).clamp(1, self.frequencies.len() - 1);
        let (f0, f1) = (self.frequencies[k - 1], self.frequencies[k]);
        let t = (w - f0) / (f1 - f0);
        let (a, b) = (column[k - 1], column[k]);
        Some(std::array::from_fn(|j| a[j] + (b[j] - a[j]) * t))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const HEADER: &str =
        "frequency,heading,surge,surge_phase,sway,sway_phase,heave,heave_phase,roll,roll_phase,pitch,pitch_phase,yaw,yaw_phase";

    #[test]
    fn a_one_sided_csv_is_mirrored_with_sway_roll_and_yaw_negated() {
        let mut text = format!("{HEADER}\n");
        for heading in [90.0, 120.0] {
            for w in [0.5, 1.0] {
                text += &format!("{w},{heading},0.1,0,0.2,10,1,0,2,30,1,-90,0.5,45\n");
            }
        }
        let t = RaoTable::parse_csv(&text).unwrap();
        assert_eq!(t.headings, vec![90.0, 120.0, 240.0, 270.0]);
        assert_eq!(t.given_headings, 2);
        let a = t.at_heading(90.0).unwrap();
        let b = t.at_heading(270.0).unwrap();
        for dof in 0..6 {
            let s = if [1, 3, 5].contains(&dof) { -1.0 } else { 1.0 };
            assert_eq!(b[0][dof], a[0][dof] * s);
        }
        // Roll 2 deg/m at 30 deg: rad/m.
        assert!((a[0][3].norm() - 2f64.to_radians()).abs() < 1e-15);
        assert!((a[0][3].arg() - 30f64.to_radians()).abs() < 1e-12);
    }
}
