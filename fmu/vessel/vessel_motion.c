/* VesselMotion: the heave and pitch of a vessel in a regular wave as an FMI 2.0 co-simulation
 * FMU, driving the supports of BeamImpact (the bridge's hinge and the arrestor's clamp) in the
 * example: `beam-impact pack --ssp` builds it (gcc, or zig cc for each platform) and packs it with
 * VesselMotion.xml as its modelDescription.xml into GangwayOnVessel.ssp (docs/ssp.md);
 * tests/python/test_vessel.py builds it with gcc for its own master. docs/vessel.md describes it for users.
 *
 * Axes (right-handed, fixed to the vessel's mean position): x forward from the centre of
 * flotation (CF), y to port, z up. Heave z is up positive; pitch theta is the rotation about +y,
 * positive BOW DOWN, so a deck point at x moves vertically by z - x theta (small angles; the
 * points' horizontal motion is left out: BeamImpact's beams move vertically). Head seas: the wave
 * comes from ahead, travelling towards -x.
 *
 *   wave elevation at the CF  zeta(t)  = zeta_a cos(omega t + phase)
 *   heave                     z(t)     = |H_z| zeta_a cos(omega t + phase + eps_z)
 *   pitch                     theta(t) = |H_theta| k zeta_a cos(omega t + phase + eps_theta)
 *
 * omega = 2 pi / T, k = omega^2 / g (deep water). Linear, steady state: the response amplitude
 * operators (RAO) |H_z| (m/m), |H_theta| (per unit wave slope k zeta_a) and their phases are
 * parameters; velocities and accelerations are the exact derivatives of the cosines. In long
 * waves the vessel follows the surface, |H_z| -> 1, eps_z -> 0, |H_theta| -> 1, eps_theta -> -pi/2
 * (the surface slope at the CF is -k zeta_a sin(...), and pitch bow down follows minus the slope).
 *
 * The two supports (each a deck point; the parameter <point>.on_vessel false leaves it fixed, on a
 * platform):
 *   hinge: heave h = z - x_h theta (and its rates)
 *   clamp: heave c = z - x_c theta; rotation r = -d theta, d = clamp.direction = the cosine of the
 *          angle between the arrestor (from its clamp to its free end) and the vessel's forward
 *          axis, so r has the sign of the arrestor's slope dw/dx and raises its end for r > 0
 *          (BeamImpact's convention): an arrestor pointing aft (d = -1) rises at its end when the
 *          bow goes down. Roll, which an athwartships arrestor would follow, is zero in head seas.
 *
 * Inputs: the support reactions BeamImpact computes (its upper.hinge_reaction_force,
 * lower.clamp_reaction_force: the support's force on the beam, up positive; and
 * lower.clamp_reaction_moment: counter-clockwise positive with x from the clamp to the free end).
 * The structures load the vessel with the opposite: deck.force = -(R_h + R_c) (up positive) and,
 * about the CF, deck.pitch_moment = x_h R_h + x_c R_c + d M_c (bow down positive), each term only
 * for a support on the vessel. The motion stays prescribed: a gangway and its arrestor (about
 * 24 t) against a walk-to-work vessel's 5 900 t; deck.heave_acceleration = deck.force /
 * vessel.mass and deck.pitch_acceleration = deck.pitch_moment / vessel.pitch_inertia bound what
 * that neglects (the accelerations the loads would give the vessel alone, before added mass and
 * hydrostatics resist).
 *
 * The irregular sea (issue 42; docs/sea-states.md, docs/ssp.md): with sea.significant_wave_height
 * > 0 the nine support motions, the elevation, heave and pitch are instead those of a long-crested
 * irregular sea through the vessel's RAO table resources/raos.csv (our CSV), at the record's time
 * t + sea.time_shift, from x forward, y to port (hinge.y, clamp.y) of the motion reference point, the
 * clamp turning by -pitch cos psi + roll sin psi (psi = sea.arrestor_direction): the section "the
 * irregular sea" below. 0 (the default) keeps the regular wave.
 *
 * The outputs are algebraic in time and in the inputs; the FMU has no state, a step only
 * advances its time. The FMI 2 types come from fmi2_abi.h beside this file (written from the
 * standard: no header files of the standard are needed to build it). Every one of the 25 common and 9 co-simulation functions exists; the
 * unsupported ones log why and return fmi2Error. The logger is always called with "%s".
 */
#include <ctype.h>
#include <errno.h>
#include <locale.h>
#include <math.h>
#include <stdint.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi2_abi.h"

#define GUID "{9e4f2a61-3b7d-4c85-a0d2-6f1c8e3b5a94}"
#define PI 3.14159265358979323846

/* Value references: one numbering across the Real and the Boolean variables (VesselMotion.xml). */
enum {
    /* parameters */
    VR_WAVE_AMPLITUDE, VR_WAVE_PERIOD, VR_WAVE_PHASE, VR_GRAVITY,
    VR_HEAVE_RAO, VR_HEAVE_PHASE, VR_PITCH_RAO, VR_PITCH_PHASE,
    VR_HINGE_X, VR_CLAMP_X, VR_CLAMP_DIRECTION, VR_VESSEL_MASS, VR_VESSEL_PITCH_INERTIA,
    /* inputs */
    VR_HINGE_FORCE, VR_CLAMP_FORCE, VR_CLAMP_MOMENT,
    /* outputs */
    VR_WAVE_ELEVATION, VR_HEAVE, VR_PITCH,
    VR_HINGE_HEAVE, VR_HINGE_HEAVE_VELOCITY, VR_HINGE_HEAVE_ACCELERATION,
    VR_CLAMP_HEAVE, VR_CLAMP_HEAVE_VELOCITY, VR_CLAMP_HEAVE_ACCELERATION,
    VR_CLAMP_ROTATION, VR_CLAMP_ROTATION_VELOCITY, VR_CLAMP_ROTATION_ACCELERATION,
    VR_DECK_FORCE, VR_DECK_PITCH_MOMENT, VR_DECK_HEAVE_ACCELERATION, VR_DECK_PITCH_ACCELERATION,
    /* calculated parameter */
    VR_WAVE_LENGTH,
    /* the irregular sea's parameters (issue 42; sea.significant_wave_height 0: the regular wave) */
    VR_SEA_HS, VR_SEA_TP, VR_SEA_SPECTRUM, VR_SEA_GAMMA, VR_SEA_HEADING, VR_SEA_SEED, VR_SEA_COMPONENTS,
    VR_SEA_FREQUENCY_MIN, VR_SEA_FREQUENCY_MAX, VR_SEA_TIME_SHIFT, VR_HINGE_Y, VR_CLAMP_Y, VR_SEA_ARRESTOR,
    N_REAL,
    /* Boolean parameters */
    VR_HINGE_ON_VESSEL = N_REAL, VR_CLAMP_ON_VESSEL,
    N_VR
};

#define FIRST_INPUT VR_HINGE_FORCE
#define FIRST_OUTPUT VR_WAVE_ELEVATION
#define FIRST_SEA VR_SEA_HS
/* Whether vr is a parameter (settable before fmi2ExitInitializationMode), an input. */
#define IS_PARAMETER(vr) ((vr) < FIRST_INPUT || ((vr) >= FIRST_SEA && (vr) < N_REAL))
#define IS_INPUT(vr) ((vr) >= FIRST_INPUT && (vr) < FIRST_OUTPUT)
#define N_BOOLEAN (N_VR - N_REAL)

/* ---- the irregular sea (issue 42) ------------------------------------------------------------------
 * docs/sea-states.md's record, as src/model/sea/ makes it for `beam-impact sea` and a [sea] run, in
 * the same operations in the same order, so that the outputs equal that record's columns to
 * round-off (tests/python/test_vessel_sea.py: 1e-12 of each column):
 * - the RAO table from our CSV (resources/raos.csv; src/model/sea/raos.rs's parse_csv): amplitudes
 *   m/m and deg/m with phase leads in deg as complex numbers (rotations in rad/m), the rows sorted
 *   by heading then frequency, a one-sided file completed by port-starboard symmetry (sway, roll,
 *   yaw negated at 360 - heading), linear in the complex values between headings (neighbours at
 *   most 45 deg apart) and between frequencies;
 * - the spectrum (DNV-RP-C205 3.5.5: Pierson-Moskowitz, JONSWAP with gamma or DNV's rule);
 * - N equal bins over [w_min, w_max] (default 0.5 w_p to 5 w_p clipped to the file's frequencies),
 *   in bin i w_i = w_min + (i + u_i) dw, phi_i = 2 pi v_i, a_i = sqrt(2 S(w_i) dw), u_0, v_0, u_1,
 *   ... from splitmix64 seeded with the seed (u = (next >> 11) 2^-53);
 * - the deck points: a point rises by heave - x pitch + y roll, the clamp turns by
 *   -pitch cos psi + roll sin psi (psi the arrestor's direction from the bow towards port);
 * - at the record's time t + time_shift, x_j = sum Re(c_ij e^(i w_i t)) with c_ij = a_i e^(i phi_i)
 *   H_j(w_i) and its exact derivatives; the elevation sum a_i cos(w_i t + phi_i).
 * Memory is allocated once, when the parameters are fixed; a step evaluates the sums only. */

#define SEA_MAX_FILE (32L << 20)    /* bytes of an RAO file read at most */
#define SEA_MAX_ROWS 200000         /* data rows (raos.rs MAX_ROWS) */
#define SEA_MAX_FREQUENCIES 2000
#define SEA_MAX_HEADINGS 360
#define SEA_MAX_FREQUENCY 100.0     /* rad/s */
#define SEA_MAX_AMPLITUDE 100.0     /* m/m, rad/m */
#define SEA_MAX_HEADING_GAP 45.0    /* deg */
#define SEA_MAX_COMPONENTS 100000
#define SEA_MIN_ENERGY_FRACTION 0.95
#define SEA_RAO_FILE "raos.csv"
#define N_CSV 14

static const char *const CSV_COLUMNS[N_CSV] = {
    "frequency", "heading", "surge", "surge_phase", "sway", "sway_phase", "heave", "heave_phase",
    "roll", "roll_phase", "pitch", "pitch_phase", "yaw", "yaw_phase"};
static const char *const DOF_NAMES[6] = {"surge", "sway", "heave", "roll", "pitch", "yaw"};

typedef struct { double re, im; } Cx;

static Cx cx(double re, double im) { Cx z; z.re = re; z.im = im; return z; }
static Cx cx_add(Cx a, Cx b) { return cx(a.re + b.re, a.im + b.im); }
static Cx cx_sub(Cx a, Cx b) { return cx(a.re - b.re, a.im - b.im); }
static Cx cx_scale(Cx a, double x) { return cx(a.re * x, a.im * x); }
static Cx cx_mul(Cx a, Cx b) { return cx(a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re); }
/* a + (b - a) t, as raos.rs interpolates */
static Cx cx_lerp(Cx a, Cx b, double t) { return cx_add(a, cx_scale(cx_sub(b, a), t)); }

/* One grid point as read (raos.rs's Point). */
typedef struct {
    double heading, frequency;
    Cx values[6];
    long line;
} RaoPoint;

/* The table: headings x frequencies, heading-major, six complex RAOs each (rad/m for rotations). */
typedef struct {
    int nf, nh;
    double *frequencies, *headings;
    Cx (*values)[6];
} RaoTable;

/* The outputs' coefficients per component: heave, pitch, hinge heave, clamp heave, clamp rotation. */
#define SEA_SUMS 5

typedef struct {
    int ready;               /* 1 once made for the current parameters */
    int n;                   /* components */
    double *w, *a, *phi;     /* frequencies rad/s, amplitudes m, phases rad */
    Cx (*c)[SEA_SUMS];       /* c_ij = a_i e^(i phi_i) H_j(w_i) */
    double lo, hi, gamma;    /* the range used, rad/s, and the spectrum's gamma (for the log) */
    int cached;              /* the sums at cache_time are in sums */
    double cache_time;
    double zeta, sums[SEA_SUMS][3];
} Sea;

static void sea_free(Sea *sea) {
    free(sea->w);
    free(sea->a);
    free(sea->phi);
    free(sea->c);
    memset(sea, 0, sizeof *sea);
}

static void table_free(RaoTable *t) {
    free(t->frequencies);
    free(t->headings);
    free(t->values);
    memset(t, 0, sizeof *t);
}

/* raos.rs's normalise: a heading in [0, 360) (-0 as 0), f64::rem_euclid. */
static double rem_euclid(double x, double m) {
    double r = fmod(x, m);
    return r < 0.0 ? r + fabs(m) : r;
}

static double normalise(double heading) {
    double h = rem_euclid(heading, 360.0);
    return (h == 0.0 || h >= 360.0) ? 0.0 : h;
}

/* A cell as a number, strictly: [+-]digits[.digits][e[+-]digits] (what Rust's f64 parse takes
 * of a CSV's cells, without "inf" and "NaN"), parsed with strtod under the C locale's point. */
static int parse_number(const char *cell, size_t len, double *out) {
    char buf[64];
    size_t i = 0, digits = 0;
    char *end;
    const char *point = localeconv()->decimal_point;
    if (len == 0 || len >= sizeof buf) return 0;
    if (cell[i] == '+' || cell[i] == '-') i++;
    while (i < len && isdigit((unsigned char)cell[i])) i++, digits++;
    if (i < len && cell[i] == '.') {
        i++;
        while (i < len && isdigit((unsigned char)cell[i])) i++, digits++;
    }
    if (digits == 0) return 0;
    if (i < len && (cell[i] == 'e' || cell[i] == 'E')) {
        size_t exp_digits = 0;
        i++;
        if (i < len && (cell[i] == '+' || cell[i] == '-')) i++;
        while (i < len && isdigit((unsigned char)cell[i])) i++, exp_digits++;
        if (exp_digits == 0) return 0;
    }
    if (i != len) return 0;
    memcpy(buf, cell, len);
    buf[len] = '\0';
    /* strtod reads the locale's decimal point: the host may have set one that is not '.'. */
    if (point != NULL && point[0] != '\0' && point[0] != '.' && point[1] == '\0') {
        for (i = 0; i < len; i++)
            if (buf[i] == '.') buf[i] = point[0];
    }
    errno = 0;
    *out = strtod(buf, &end);
    return end == buf + len;
}

/* Trims spaces, tabs and carriage returns (Rust's trim of a CSV field) from [*start, *end). */
static void trim(const char **start, const char **end) {
    while (*start < *end && isspace((unsigned char)**start)) (*start)++;
    while (*end > *start && isspace((unsigned char)(*end)[-1])) (*end)--;
}

static int compare_points(const void *x, const void *y) {
    const RaoPoint *a = (const RaoPoint *)x, *b = (const RaoPoint *)y;
    if (a->heading != b->heading) return a->heading < b->heading ? -1 : 1;
    if (a->frequency != b->frequency) return a->frequency < b->frequency ? -1 : 1;
    return a->line < b->line ? -1 : (a->line > b->line);
}

static int compare_doubles(const void *x, const void *y) {
    double a = *(const double *)x, b = *(const double *)y;
    return a < b ? -1 : (a > b);
}

/* Parses our RAO CSV text (NUL-terminated, len bytes) into t; on error writes one line into why and
 * returns 0. */
static int parse_csv(const char *text, size_t len, RaoTable *t, char *why, size_t n) {
    const char *p = text, *stop = text + len;
    long line = 0;
    int slots[N_CSV], columns = 0, have_header = 0;
    size_t count = 0, capacity = 0, k, h, f;
    RaoPoint *points = NULL;
    double *freqs = NULL;
    int ok = 0;
    memset(t, 0, sizeof *t);
    while (p < stop) {
        const char *eol = memchr(p, '\n', (size_t)(stop - p));
        const char *ls = p, *le = eol ? eol : stop;
        p = eol ? eol + 1 : stop;
        line++;
        trim(&ls, &le);
        if (ls == le || *ls == '#') continue;
        if (!have_header) {
            const char *c = ls;
            int seen_frequency = 0, seen_heading = 0, i;
            /* the header's names */
            while (c <= le) {
                const char *ce = memchr(c, ',', (size_t)(le - c));
                const char *cs = c, *cend = ce ? ce : le;
                int slot = -1;
                c = ce ? ce + 1 : le + 1;
                trim(&cs, &cend);
                while (cs < cend && *cs == '"') cs++;
                while (cend > cs && cend[-1] == '"') cend--;
                for (i = 0; i < N_CSV; i++)
                    if (strlen(CSV_COLUMNS[i]) == (size_t)(cend - cs) && memcmp(CSV_COLUMNS[i], cs, (size_t)(cend - cs)) == 0)
                        slot = i;
                if (slot == 0) seen_frequency = 1;
                if (slot == 1) seen_heading = 1;
                if (columns >= N_CSV) {
                    columns++;
                    break;
                }
                slots[columns++] = slot;
            }
            if (!seen_frequency || !seen_heading) {
                snprintf(why, n, "line %ld is not an RAO CSV header: it needs the columns frequency,heading and the six RAOs with their phases", line);
                goto done;
            }
            if (columns > N_CSV) {
                snprintf(why, n, "line %ld: more than %d columns (expected frequency,heading and the six RAOs with their phases)", line, N_CSV);
                goto done;
            }
            for (i = 0; i < columns; i++) {
                int j;
                if (slots[i] < 0) {
                    snprintf(why, n, "line %ld: column %d is not one of frequency,heading,surge,surge_phase,...,yaw,yaw_phase", line, i + 1);
                    goto done;
                }
                for (j = 0; j < i; j++)
                    if (slots[j] == slots[i]) {
                        snprintf(why, n, "line %ld: column `%s` appears twice", line, CSV_COLUMNS[slots[i]]);
                        goto done;
                    }
            }
            if (columns != N_CSV) {
                snprintf(why, n, "line %ld: %d columns, expected the 14 of frequency,heading,surge,surge_phase,...,yaw,yaw_phase", line, columns);
                goto done;
            }
            have_header = 1;
            continue;
        }
        {
            double v[N_CSV];
            const char *c = ls;
            int fields = 0, dof;
            RaoPoint *point;
            if (count >= SEA_MAX_ROWS) {
                snprintf(why, n, "more than %d rows (line %ld)", SEA_MAX_ROWS, line);
                goto done;
            }
            while (c <= le) {
                const char *ce = memchr(c, ',', (size_t)(le - c));
                const char *cs = c, *cend = ce ? ce : le;
                double value;
                c = ce ? ce + 1 : le + 1;
                if (fields >= N_CSV) {
                    fields++;
                    break;
                }
                trim(&cs, &cend);
                if (!parse_number(cs, (size_t)(cend - cs), &value)) {
                    snprintf(why, n, "line %ld: `%s` is not a number", line, CSV_COLUMNS[slots[fields]]);
                    goto done;
                }
                if (!isfinite(value)) {
                    snprintf(why, n, "line %ld: `%s` = %g is not finite", line, CSV_COLUMNS[slots[fields]], value);
                    goto done;
                }
                v[slots[fields++]] = value;
            }
            if (fields != N_CSV) {
                snprintf(why, n, "line %ld: %s%d fields, the header has %d columns", line, fields > N_CSV ? "more than " : "",
                         fields > N_CSV ? N_CSV : fields, N_CSV);
                goto done;
            }
            if (!(v[0] > 0.0 && v[0] <= SEA_MAX_FREQUENCY)) {
                snprintf(why, n, "line %ld: frequency = %g rad/s is not > 0 and <= %g", line, v[0], SEA_MAX_FREQUENCY);
                goto done;
            }
            if (!(v[1] >= -360.0 && v[1] <= 360.0)) {
                snprintf(why, n, "line %ld: heading = %g deg is not between -360 and 360", line, v[1]);
                goto done;
            }
            if (count == capacity) {
                size_t grown = capacity ? 2 * capacity : 512;
                RaoPoint *more = (RaoPoint *)realloc(points, grown * sizeof *points);
                if (more == NULL) {
                    snprintf(why, n, "out of memory at line %ld", line);
                    goto done;
                }
                points = more;
                capacity = grown;
            }
            point = &points[count];
            for (dof = 0; dof < 6; dof++) {
                double amplitude = v[2 + 2 * dof], phase = v[3 + 2 * dof];
                int rotation = dof >= 3;
                double scale = rotation ? PI / 180.0 : 1.0;
                double radians;
                if (!(amplitude >= 0.0 && amplitude * scale <= SEA_MAX_AMPLITUDE)) {
                    snprintf(why, n, "line %ld: %s = %g %s is not an amplitude from 0 to %g %s", line, DOF_NAMES[dof], amplitude,
                             rotation ? "deg/m" : "m/m", SEA_MAX_AMPLITUDE / scale, rotation ? "deg/m" : "m/m");
                    goto done;
                }
                if (fabs(phase) > 3600.0) {
                    snprintf(why, n, "line %ld: %s_phase = %g deg is beyond +-3600", line, DOF_NAMES[dof], phase);
                    goto done;
                }
                radians = phase * (PI / 180.0);
                point->values[dof] = cx(amplitude * scale * cos(radians), amplitude * scale * sin(radians));
            }
            point->heading = normalise(v[1]);
            point->frequency = v[0];
            point->line = line;
            count++;
        }
    }
    if (!have_header) {
        snprintf(why, n, "no header line (frequency, heading and the six RAOs)");
        goto done;
    }
    if (count == 0) {
        snprintf(why, n, "no RAO rows");
        goto done;
    }
    qsort(points, count, sizeof *points, compare_points);
    for (k = 1; k < count; k++)
        if (points[k].heading == points[k - 1].heading && points[k].frequency == points[k - 1].frequency) {
            snprintf(why, n, "heading %g deg, frequency %g rad/s is given twice (lines %ld and %ld)", points[k].heading,
                     points[k].frequency, points[k - 1].line < points[k].line ? points[k - 1].line : points[k].line,
                     points[k - 1].line < points[k].line ? points[k].line : points[k - 1].line);
            goto done;
        }
    /* the headings (sorted with the points) and the frequencies */
    freqs = (double *)malloc(count * sizeof *freqs);
    if (freqs == NULL) {
        snprintf(why, n, "out of memory");
        goto done;
    }
    for (k = 0; k < count; k++) freqs[k] = points[k].frequency;
    qsort(freqs, count, sizeof *freqs, compare_doubles);
    for (k = 0, f = 0; k < count; k++)
        if (f == 0 || freqs[k] != freqs[f - 1]) freqs[f++] = freqs[k];
    for (k = 0, h = 0; k < count; k++)
        if (k == 0 || points[k].heading != points[k - 1].heading) h++;
    if (h > SEA_MAX_HEADINGS) {
        snprintf(why, n, "%lu headings, more than %d", (unsigned long)h, SEA_MAX_HEADINGS);
        goto done;
    }
    if (f > SEA_MAX_FREQUENCIES) {
        snprintf(why, n, "%lu frequencies, more than %d", (unsigned long)f, SEA_MAX_FREQUENCIES);
        goto done;
    }
    if (f < 2) {
        snprintf(why, n, "%lu frequency: at least 2 are needed to interpolate between", (unsigned long)f);
        goto done;
    }
    if (count != h * f) {
        snprintf(why, n, "incomplete grid: %lu rows for %lu headings x %lu frequencies (every heading needs every frequency)",
                 (unsigned long)count, (unsigned long)h, (unsigned long)f);
        goto done;
    }
    {
        /* port-starboard symmetry for a one-sided file (raos.rs from_points) */
        int starboard = 1, port = 1;
        size_t given = h, total = h, i, j, m;
        double *headings = (double *)malloc(2 * given * sizeof *headings);
        int *source = (int *)malloc(2 * given * sizeof *source); /* given column, negative: mirrored (-1 - k) */
        size_t *order = NULL;
        if (headings == NULL || source == NULL) {
            free(headings);
            free(source);
            snprintf(why, n, "out of memory");
            goto done;
        }
        for (i = 0; i < given; i++) {
            headings[i] = points[i * f].heading;
            source[i] = (int)i;
            if (!(headings[i] <= 180.0)) starboard = 0;
            if (!(headings[i] == 0.0 || headings[i] >= 180.0)) port = 0;
        }
        if (starboard || port) {
            for (i = 0; i < given; i++) {
                double mirror = normalise(360.0 - headings[i]);
                int present = 0;
                for (j = 0; j < given; j++)
                    if (headings[j] == mirror) present = 1;
                if (present) continue;
                headings[total] = mirror;
                source[total] = -1 - (int)i;
                total++;
            }
        }
        /* sort the columns by heading (insertion sort: at most 720, and stable as Rust's sort_by) */
        order = (size_t *)malloc(total * sizeof *order);
        t->frequencies = (double *)malloc(f * sizeof *t->frequencies);
        t->headings = (double *)malloc(total * sizeof *t->headings);
        t->values = (Cx(*)[6])malloc(total * f * sizeof *t->values);
        if (order == NULL || t->frequencies == NULL || t->headings == NULL || t->values == NULL) {
            free(headings);
            free(source);
            free(order);
            snprintf(why, n, "out of memory");
            goto done;
        }
        for (i = 0; i < total; i++) {
            size_t at = i;
            while (at > 0 && headings[order[at - 1]] > headings[i]) {
                order[at] = order[at - 1];
                at--;
            }
            order[at] = i;
        }
        memcpy(t->frequencies, freqs, f * sizeof *freqs);
        for (i = 0; i < total; i++) {
            int src = source[order[i]];
            size_t column = (size_t)(src >= 0 ? src : -1 - src);
            t->headings[i] = headings[order[i]];
            for (j = 0; j < f; j++) {
                for (m = 0; m < 6; m++) {
                    Cx value = points[column * f + j].values[m];
                    if (src < 0 && (m == 1 || m == 3 || m == 5)) value = cx(-value.re, -value.im);
                    t->values[i * f + j][m] = value;
                }
            }
        }
        t->nf = (int)f;
        t->nh = (int)total;
        free(headings);
        free(source);
        free(order);
    }
    ok = 1;
done:
    free(points);
    free(freqs);
    if (!ok) table_free(t);
    return ok;
}

/* The RAOs at every frequency for heading beta (raos.rs at_heading) into column (nf entries). */
static int at_heading(const RaoTable *t, double beta, Cx (*column)[6], char *why, size_t n) {
    int k, above = 0, lo, hi, j, m;
    double gap, x;
    beta = normalise(beta);
    for (k = 0; k < t->nh; k++)
        if (t->headings[k] == beta) {
            memcpy(column, &t->values[(size_t)k * t->nf], (size_t)t->nf * sizeof *column);
            return 1;
        }
    if (t->nh == 1) {
        snprintf(why, n, "the RAO file has heading %g deg only, not %g deg", t->headings[0], beta);
        return 0;
    }
    while (above < t->nh && t->headings[above] < beta) above++;
    lo = (above + t->nh - 1) % t->nh;
    hi = above % t->nh;
    gap = rem_euclid(t->headings[hi] - t->headings[lo], 360.0);
    if (gap > SEA_MAX_HEADING_GAP) {
        snprintf(why, n, "heading %g deg falls between the RAO file's headings %g and %g deg, %g deg apart (at most %g deg are interpolated across)",
                 beta, t->headings[lo], t->headings[hi], gap, SEA_MAX_HEADING_GAP);
        return 0;
    }
    x = rem_euclid(beta - t->headings[lo], 360.0) / gap;
    for (j = 0; j < t->nf; j++)
        for (m = 0; m < 6; m++)
            column[j][m] = cx_lerp(t->values[(size_t)lo * t->nf + j][m], t->values[(size_t)hi * t->nf + j][m], x);
    return 1;
}

/* The RAOs of column at frequency w (raos.rs at_frequency); 0 outside the table's range. */
static int at_frequency(const RaoTable *t, Cx (*column)[6], double w, Cx six[6]) {
    int k = 0, m;
    double x;
    if (!(w >= t->frequencies[0] && w <= t->frequencies[t->nf - 1])) return 0;
    while (k < t->nf && t->frequencies[k] <= w) k++;
    if (k < 1) k = 1;
    if (k > t->nf - 1) k = t->nf - 1;
    x = (w - t->frequencies[k - 1]) / (t->frequencies[k] - t->frequencies[k - 1]);
    for (m = 0; m < 6; m++) six[m] = cx_lerp(column[k - 1][m], column[k][m], x);
    return 1;
}

/* ---- spectrum and components (spectrum.rs, components.rs) ---- */

static double dnv_gamma(double hs, double tp) {
    double p = tp / sqrt(hs);
    if (p <= 3.6) return 5.0;
    if (p < 5.0) return exp(5.75 - 1.15 * p);
    return 1.0;
}

typedef struct { double hs, tp, gamma; } Spectrum;

static double density(const Spectrum *s, double w) {
    double wp, r, r4, pm, sigma, x;
    if (w <= 0.0) return 0.0;
    wp = 2.0 * PI / s->tp;
    r = wp / w;
    r4 = r * r * r * r;
    pm = 5.0 / 16.0 * s->hs * s->hs * r4 / w * exp(-1.25 * r4);
    if (s->gamma == 1.0) return pm;
    sigma = w <= wp ? 0.07 : 0.09;
    x = (w - wp) / (sigma * wp);
    return (1.0 - 0.287 * log(s->gamma)) * pm * pow(s->gamma, exp(-0.5 * x * x));
}

/* m0 between lo and hi by composite Simpson's rule on 20 000 intervals (spectrum.rs moment_between, n = 0). */
static double m0_between(const Spectrum *s, double lo, double hi) {
    const int intervals = 20000;
    double h = (hi - lo) / intervals, sum;
    int k;
    sum = density(s, lo) + density(s, hi);
    for (k = 1; k < intervals; k++) sum += (k % 2 == 1 ? 4.0 : 2.0) * density(s, lo + h * k);
    return sum * h / 3.0;
}

/* m0 over 0 < w < infinity: Simpson's up to 30 w_p and the w^-5 tail in closed form (spectrum.rs moment). */
static double m0(const Spectrum *s) {
    double wp = 2.0 * PI / s->tp, top = 30.0 * wp;
    double factor = s->gamma == 1.0 ? 1.0 : 1.0 - 0.287 * log(s->gamma);
    double c = 5.0 / 16.0 * s->hs * s->hs * pow(wp, 4.0) * factor;
    return m0_between(s, 0.0, top) + c * pow(top, -4.0) / 4.0;
}

/* splitmix64 (components.rs SplitMix64) */
static uint64_t splitmix64(uint64_t *state) {
    uint64_t z;
    *state += UINT64_C(0x9E3779B97F4A7C15);
    z = *state;
    z = (z ^ (z >> 30)) * UINT64_C(0xBF58476D1CE4E5B9);
    z = (z ^ (z >> 27)) * UINT64_C(0x94D049BB133111EB);
    return z ^ (z >> 31);
}

static double uniform(uint64_t *state) { return (double)(splitmix64(state) >> 11) * (1.0 / 9007199254740992.0); }

/* ---- the record ---- */

/* What the irregular sea's parameters break (settings.rs validation_errors, those the FMU has),
 * into why; 1 when valid. p: the instance's values; on: the supports' on_vessel flags. */
static int sea_parameters_valid(const double *p, const fmi2Boolean *on, char *why, size_t n) {
    double hs = p[VR_SEA_HS], tp = p[VR_SEA_TP], gamma = p[VR_SEA_GAMMA];
    double steepness, limit;
    if (!(hs > 0.0 && hs <= 20.0)) return snprintf(why, n, "sea.significant_wave_height (m) must be in (0, 20] for the irregular sea (0: the regular wave), got %g", hs), 0;
    if (!(tp >= 2.0 && tp <= 30.0)) return snprintf(why, n, "sea.peak_period (s) must be in [2, 30], got %g", tp), 0;
    if (!(p[VR_SEA_SPECTRUM] == 0.0 || p[VR_SEA_SPECTRUM] == 1.0))
        return snprintf(why, n, "sea.spectrum must be 0 (JONSWAP) or 1 (Pierson-Moskowitz), got %g", p[VR_SEA_SPECTRUM]), 0;
    if (gamma != 0.0) {
        if (!(gamma >= 1.0 && gamma <= 7.0))
            return snprintf(why, n, "sea.peak_enhancement must be in [1, 7] (0: DNV's rule), got %g", gamma), 0;
        if (p[VR_SEA_SPECTRUM] != 0.0)
            return snprintf(why, n, "sea.peak_enhancement must be 0 with sea.spectrum = 1 (gamma is JONSWAP's), got %g", gamma), 0;
    }
    /* DNV-RP-C205 3.5.11: a sea steeper than this breaks */
    steepness = 2.0 * PI * hs / (9.81 * tp * tp);
    limit = tp <= 8.0 ? 1.0 / 15.0 : tp >= 15.0 ? 1.0 / 25.0 : 1.0 / 15.0 + (tp - 8.0) / 7.0 * (1.0 / 25.0 - 1.0 / 15.0);
    if (steepness > limit)
        return snprintf(why, n, "sea.significant_wave_height = %g m with sea.peak_period = %g s is steeper than a sea can be: 2 pi Hs / (g Tp^2) = %.4f > %.4f (DNV-RP-C205 3.5.11)", hs, tp, steepness, limit), 0;
    if (!(p[VR_SEA_HEADING] >= 0.0 && p[VR_SEA_HEADING] <= 360.0))
        return snprintf(why, n, "sea.heading (deg) must be in [0, 360], got %g", p[VR_SEA_HEADING]), 0;
    if (!(p[VR_SEA_SEED] >= 0.0 && p[VR_SEA_SEED] <= 9007199254740992.0 && floor(p[VR_SEA_SEED]) == p[VR_SEA_SEED]))
        return snprintf(why, n, "sea.seed must be a whole number from 0 to 2^53, got %.17g", p[VR_SEA_SEED]), 0;
    if (!(p[VR_SEA_COMPONENTS] >= 1.0 && p[VR_SEA_COMPONENTS] <= SEA_MAX_COMPONENTS && floor(p[VR_SEA_COMPONENTS]) == p[VR_SEA_COMPONENTS]))
        return snprintf(why, n, "sea.components must be a whole number from 1 to %d, got %g", SEA_MAX_COMPONENTS, p[VR_SEA_COMPONENTS]), 0;
    if (!(p[VR_SEA_FREQUENCY_MIN] >= 0.0 && p[VR_SEA_FREQUENCY_MIN] <= SEA_MAX_FREQUENCY))
        return snprintf(why, n, "sea.frequency_min (rad/s) must be in (0, 100] (0: the default), got %g", p[VR_SEA_FREQUENCY_MIN]), 0;
    if (!(p[VR_SEA_FREQUENCY_MAX] >= 0.0 && p[VR_SEA_FREQUENCY_MAX] <= SEA_MAX_FREQUENCY))
        return snprintf(why, n, "sea.frequency_max (rad/s) must be in (0, 100] (0: the default), got %g", p[VR_SEA_FREQUENCY_MAX]), 0;
    if (p[VR_SEA_FREQUENCY_MIN] > 0.0 && p[VR_SEA_FREQUENCY_MAX] > 0.0 && !(p[VR_SEA_FREQUENCY_MIN] < p[VR_SEA_FREQUENCY_MAX]))
        return snprintf(why, n, "sea.frequency_max must be > sea.frequency_min = %g rad/s, got %g", p[VR_SEA_FREQUENCY_MIN], p[VR_SEA_FREQUENCY_MAX]), 0;
    if (!(p[VR_SEA_TIME_SHIFT] >= 0.0 && p[VR_SEA_TIME_SHIFT] <= 1e6))
        return snprintf(why, n, "sea.time_shift (s) must be in [0, 1e6], got %g", p[VR_SEA_TIME_SHIFT]), 0;
    if (!(fabs(p[VR_HINGE_X]) <= 500.0 && fabs(p[VR_HINGE_Y]) <= 500.0 && fabs(p[VR_CLAMP_X]) <= 500.0 && fabs(p[VR_CLAMP_Y]) <= 500.0))
        return snprintf(why, n, "hinge.x, hinge.y, clamp.x and clamp.y must be within 500 m of the motion reference point in the irregular sea, got %g, %g, %g, %g",
                        p[VR_HINGE_X], p[VR_HINGE_Y], p[VR_CLAMP_X], p[VR_CLAMP_Y]), 0;
    if (!on[0] && !on[1]) return snprintf(why, n, "hinge.on_vessel and clamp.on_vessel are both false: no support is on the vessel"), 0;
    if (!(p[VR_SEA_ARRESTOR] >= 0.0 && p[VR_SEA_ARRESTOR] <= 360.0))
        return snprintf(why, n, "sea.arrestor_direction (deg) must be in [0, 360], got %g", p[VR_SEA_ARRESTOR]), 0;
    return 1;
}

/* Reads resources/raos.csv (at most SEA_MAX_FILE bytes, a regular file) into a NUL-terminated
 * buffer; why gets one line on failure. */
static char *read_rao_file(const char *resources, size_t *len, char *why, size_t n) {
    char path[4096];
    FILE *file;
    char *text;
    size_t got = 0;
    if (resources == NULL) return snprintf(why, n, "no resource location (fmuResourceLocation) to read " SEA_RAO_FILE " from"), NULL;
    if ((size_t)snprintf(path, sizeof path, "%s/" SEA_RAO_FILE, resources) >= sizeof path)
        return snprintf(why, n, "the resource location is longer than %lu bytes", (unsigned long)sizeof path), NULL;
    file = fopen(path, "rb");
    if (file == NULL) return snprintf(why, n, "cannot open " SEA_RAO_FILE " in the FMU's resources: %s", strerror(errno)), NULL;
    text = (char *)malloc((size_t)SEA_MAX_FILE + 1);
    if (text == NULL) {
        fclose(file);
        return snprintf(why, n, "out of memory for " SEA_RAO_FILE), NULL;
    }
    /* Bounded while reading: a FIFO, a device or a growing file stops at the limit (a folder
     * fails to read). */
    while (got <= (size_t)SEA_MAX_FILE) {
        size_t r = fread(text + got, 1, (size_t)SEA_MAX_FILE + 1 - got, file);
        if (r == 0) break;
        got += r;
    }
    if (ferror(file)) {
        snprintf(why, n, "cannot read " SEA_RAO_FILE " in the FMU's resources (not a regular file?)");
        fclose(file);
        free(text);
        return NULL;
    }
    fclose(file);
    if (got > (size_t)SEA_MAX_FILE) {
        free(text);
        return snprintf(why, n, SEA_RAO_FILE " is larger than %ld bytes: not an RAO table", SEA_MAX_FILE), NULL;
    }
    if (memchr(text, '\0', got) != NULL) {
        free(text);
        return snprintf(why, n, SEA_RAO_FILE " holds a NUL byte: not a text RAO table"), NULL;
    }
    text[got] = '\0';
    *len = got;
    return text;
}

/* The support coordinates and the vessel's heave and pitch from the six complex motions (deck_motion.rs). */
static void sums_of(const double *p, const fmi2Boolean *on, const Cx six[6], Cx out[SEA_SUMS]) {
    double psi = p[VR_SEA_ARRESTOR] * (PI / 180.0);
    Cx zero = cx(0.0, 0.0);
    out[0] = six[2];
    out[1] = six[4];
    out[2] = on[0] ? cx_add(cx_sub(six[2], cx_scale(six[4], p[VR_HINGE_X])), cx_scale(six[3], p[VR_HINGE_Y])) : zero;
    out[3] = on[1] ? cx_add(cx_sub(six[2], cx_scale(six[4], p[VR_CLAMP_X])), cx_scale(six[3], p[VR_CLAMP_Y])) : zero;
    out[4] = on[1] ? cx_add(cx_scale(cx(-six[4].re, -six[4].im), cos(psi)), cx_scale(six[3], sin(psi))) : zero;
}

/* Makes the record for the parameters p from the RAO file under resources; 1, or 0 with why. */
static int sea_make(Sea *sea, const double *p, const fmi2Boolean *on, const char *resources, char *why, size_t n) {
    RaoTable table;
    Spectrum spectrum;
    char *text;
    size_t len = 0;
    double wp, lo, hi, flo, fhi, dw, fraction;
    int i, count, ok = 0;
    uint64_t state;
    Cx(*column)[6] = NULL;
    char detail[400];
    sea_free(sea);
    if (!sea_parameters_valid(p, on, why, n)) return 0;
    /* whole numbers in range now (converting them before the check could overflow) */
    count = (int)p[VR_SEA_COMPONENTS];
    state = (uint64_t)p[VR_SEA_SEED];
    text = read_rao_file(resources, &len, why, n);
    if (text == NULL) return 0;
    if (!parse_csv(text, len, &table, detail, sizeof detail)) {
        free(text);
        return snprintf(why, n, "resources/" SEA_RAO_FILE ": %s", detail), 0;
    }
    free(text);
    spectrum.hs = p[VR_SEA_HS];
    spectrum.tp = p[VR_SEA_TP];
    spectrum.gamma = p[VR_SEA_SPECTRUM] == 1.0 ? 1.0 : p[VR_SEA_GAMMA] != 0.0 ? p[VR_SEA_GAMMA] : dnv_gamma(spectrum.hs, spectrum.tp);
    /* settings.rs frequency_range: as given, else 0.5 w_p to 5 w_p within the file's frequencies */
    wp = 2.0 * PI / p[VR_SEA_TP];
    flo = table.frequencies[0];
    fhi = table.frequencies[table.nf - 1];
    lo = p[VR_SEA_FREQUENCY_MIN] != 0.0 ? p[VR_SEA_FREQUENCY_MIN] : fmax(0.5 * wp, flo);
    hi = p[VR_SEA_FREQUENCY_MAX] != 0.0 ? p[VR_SEA_FREQUENCY_MAX] : fmin(5.0 * wp, fhi);
    if (!(lo >= flo && lo <= fhi) || !(hi >= flo && hi <= fhi)) {
        snprintf(why, n, "sea.frequency_min/max: the components' range %g to %g rad/s is not within the RAO file's frequencies, %g to %g rad/s", lo, hi, flo, fhi);
        goto done;
    }
    if (lo >= hi) {
        snprintf(why, n, "the components' range %g to %g rad/s is empty (the RAO file's frequencies %g to %g rad/s and the spectrum's 0.5 to 5 w_p)", lo, hi, flo, fhi);
        goto done;
    }
    fraction = m0_between(&spectrum, lo, hi) / m0(&spectrum);
    if (fraction < SEA_MIN_ENERGY_FRACTION) {
        snprintf(why, n, "the components' range %g to %g rad/s holds %.1f %% of the spectrum's variance, less than 95 %%: widen sea.frequency_min/max or give RAOs over a wider range than %g to %g rad/s",
                 lo, hi, 100.0 * fraction, flo, fhi);
        goto done;
    }
    column = (Cx(*)[6])malloc((size_t)table.nf * sizeof *column);
    sea->w = (double *)malloc((size_t)count * sizeof *sea->w);
    sea->a = (double *)malloc((size_t)count * sizeof *sea->a);
    sea->phi = (double *)malloc((size_t)count * sizeof *sea->phi);
    sea->c = (Cx(*)[SEA_SUMS])malloc((size_t)count * sizeof *sea->c);
    if (column == NULL || sea->w == NULL || sea->a == NULL || sea->phi == NULL || sea->c == NULL) {
        snprintf(why, n, "out of memory for %d components", count);
        goto done;
    }
    if (!at_heading(&table, p[VR_SEA_HEADING], column, detail, sizeof detail)) {
        snprintf(why, n, "sea.heading = %g deg: %s", p[VR_SEA_HEADING], detail);
        goto done;
    }
    dw = (hi - lo) / count;
    for (i = 0; i < count; i++) {
        double u = uniform(&state), v = uniform(&state);
        double w = lo + (i + u) * dw;
        Cx six[6], out[SEA_SUMS], wave;
        int j;
        sea->w[i] = w;
        sea->a[i] = sqrt(2.0 * density(&spectrum, w) * dw);
        sea->phi[i] = 2.0 * PI * v;
        if (!at_frequency(&table, column, w, six)) {
            snprintf(why, n, "wave component at %g rad/s is outside the RAO file's frequencies (%g to %g rad/s)", w, flo, fhi);
            goto done;
        }
        wave = cx(sea->a[i] * cos(sea->phi[i]), sea->a[i] * sin(sea->phi[i]));
        sums_of(p, on, six, out);
        for (j = 0; j < SEA_SUMS; j++) sea->c[i][j] = cx_mul(wave, out[j]);
    }
    sea->n = count;
    sea->lo = lo;
    sea->hi = hi;
    sea->gamma = spectrum.gamma;
    sea->ready = 1;
    ok = 1;
done:
    free(column);
    table_free(&table);
    if (!ok) sea_free(sea);
    return ok;
}

/* The sums at the record's time t (record.rs motion, components.rs elevation), cached per time. */
static void sea_evaluate(Sea *sea, double t) {
    int i, j;
    if (sea->cached && sea->cache_time == t) return;
    memset(sea->sums, 0, sizeof sea->sums);
    sea->zeta = 0.0;
    for (i = 0; i < sea->n; i++) {
        double w = sea->w[i], s = sin(w * t), co = cos(w * t);
        sea->zeta += sea->a[i] * cos(w * t + sea->phi[i]);
        for (j = 0; j < SEA_SUMS; j++) {
            Cx c = sea->c[i][j];
            double re = c.re * co - c.im * s;
            double rate = -(c.re * s + c.im * co);
            sea->sums[j][0] += re;
            sea->sums[j][1] += w * rate;
            sea->sums[j][2] -= w * w * re;
        }
    }
    sea->cache_time = t;
    sea->cached = 1;
}


typedef enum { INSTANTIATED, INITIALIZATION, STEP_COMPLETE, TERMINATED, FAILED } Phase;

typedef struct {
    char *name;
    fmi2CallbackLogger logger;
    fmi2ComponentEnvironment env;
    fmi2Boolean logging_on;
    Phase phase;
    fmi2Real time;
    fmi2Real values[N_REAL];      /* parameters and inputs; outputs are computed when read */
    fmi2Boolean booleans[N_BOOLEAN];
    char *resources;              /* the resource folder's path (from fmuResourceLocation), or NULL */
    Sea sea;                      /* the irregular sea's record, made once the parameters are fixed */
} Instance;

/* Defaults (docs/vessel.md): a regular wave of 2 m height and 9 s period (wave length 126 m) in
 * head seas, a walk-to-work vessel of about 90 m (displacement 5 900 t, pitch radius of gyration
 * 0.25 L = 22.5 m), illustrative RAOs of the size a strip-theory calculation gives for such a hull
 * at zero speed and wave length / ship length 1.4; the hinge 10 m aft of the CF, the clamp 15 m
 * forward of it with the arrestor pointing aft, so its end (x = 3 m) is under the bridge's contact
 * point 13 m forward of the hinge. */
static const fmi2Real START[N_REAL] = {
    1.0, 9.0, 0.0, 9.81,         /* wave.amplitude, wave.period, wave.phase, gravity */
    0.9, -0.3, 0.8, -1.9,        /* heave.rao, heave.phase, pitch.rao, pitch.phase */
    -10.0, 15.0, -1.0, 5.9e6, 3.0e9, /* hinge.x, clamp.x, clamp.direction, vessel.mass, vessel.pitch_inertia */
    0.0, 0.0, 0.0,               /* hinge_force, clamp_force, clamp_moment */
    /* outputs and the calculated parameter: not stored */
    0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
    /* the irregular sea (examples/vessel-sea.toml's): Hs 0 = the regular wave above; Tp 8 s, JONSWAP with
     * DNV's gamma, head seas, seed 1, 1000 components over the default range, no time shift, the
     * supports on the centreline, the arrestor pointing aft */
    0.0, 8.0, 0.0, 0.0, 180.0, 1.0, 1000.0, 0.0, 0.0, 0.0, 0.0, 0.0, 180.0,
};
static const fmi2Boolean START_BOOLEAN[N_BOOLEAN] = {fmi2True, fmi2True};

static void log_message(const Instance *s, fmi2Status status, const char *category, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));

static void log_message(const Instance *s, fmi2Status status, const char *category, const char *fmt, ...) {
    char message[512];
    va_list args;
    if (s == NULL || s->logger == NULL) return;
    /* Errors and warnings always reach the importer; anything else only with debug logging on. */
    if (status == fmi2OK && !s->logging_on) return;
    va_start(args, fmt);
    vsnprintf(message, sizeof message, fmt, args);
    va_end(args);
    s->logger(s->env, s->name, status, category, "%s", message);
}

static fmi2Status fail(Instance *s, const char *function, const char *why) {
    log_message(s, fmi2Error, "logStatusError", "%s: %s", function, why);
    return fmi2Error;
}

static fmi2Status unsupported(fmi2Component c, const char *function) {
    if (c == NULL) return fmi2Error;
    return fail((Instance *)c, function, "not supported by this FMU");
}

/* Writes why the parameters are invalid into why (size n) and returns 0, or returns 1. */
static int parameters_valid(const Instance *s, char *why, size_t n) {
    static const struct {
        int vr;
        const char *name;
        double low; /* the value must be > low (or >= low when closed) */
        int closed;
        double high; /* and <= high */
    } rules[] = {
        {VR_WAVE_AMPLITUDE, "wave.amplitude (m)", 0.0, 1, 1e3},
        {VR_WAVE_PERIOD, "wave.period (s)", 0.0, 0, 1e4},
        {VR_WAVE_PHASE, "wave.phase (rad)", -1e6, 1, 1e6},
        {VR_GRAVITY, "gravity (m/s2)", 0.0, 0, 100.0},
        {VR_HEAVE_RAO, "heave.rao (m/m)", 0.0, 1, 100.0},
        {VR_HEAVE_PHASE, "heave.phase (rad)", -1e6, 1, 1e6},
        {VR_PITCH_RAO, "pitch.rao (1)", 0.0, 1, 100.0},
        {VR_PITCH_PHASE, "pitch.phase (rad)", -1e6, 1, 1e6},
        {VR_HINGE_X, "hinge.x (m)", -1e4, 1, 1e4},
        {VR_CLAMP_X, "clamp.x (m)", -1e4, 1, 1e4},
        {VR_CLAMP_DIRECTION, "clamp.direction (1)", -1.0, 1, 1.0},
        {VR_VESSEL_MASS, "vessel.mass (kg)", 0.0, 0, 1e12},
        {VR_VESSEL_PITCH_INERTIA, "vessel.pitch_inertia (kg m2)", 0.0, 0, 1e18},
    };
    size_t i;
    for (i = 0; i < sizeof rules / sizeof rules[0]; i++) {
        double v = s->values[rules[i].vr];
        int above = rules[i].closed ? v >= rules[i].low : v > rules[i].low;
        if (!(above && v <= rules[i].high)) {
            snprintf(why, n, "%s must be in %c%g, %g], got %g", rules[i].name, rules[i].closed ? '[' : '(',
                     rules[i].low, rules[i].high, v);
            return 0;
        }
    }
    return 1;
}

/* The vessel's heave (m) and pitch (rad) and their first two rates at time t. */
typedef struct {
    double zeta, z[3], theta[3];
} Motion;

static double wave_frequency(const Instance *s) { return 2.0 * PI / s->values[VR_WAVE_PERIOD]; }

static double wave_number(const Instance *s) {
    double omega = wave_frequency(s);
    return omega * omega / s->values[VR_GRAVITY];
}

/* a cos(psi) and its exact first and second time derivatives, psi = omega t + phase. */
static void harmonic(double a, double omega, double psi, double out[3]) {
    out[0] = a * cos(psi);
    out[1] = -a * omega * sin(psi);
    out[2] = -a * omega * omega * cos(psi);
}

static Motion motion(const Instance *s, double t) {
    const double *p = s->values;
    double omega = wave_frequency(s);
    double psi = omega * t + p[VR_WAVE_PHASE];
    Motion m;
    m.zeta = p[VR_WAVE_AMPLITUDE] * cos(psi);
    harmonic(p[VR_HEAVE_RAO] * p[VR_WAVE_AMPLITUDE], omega, psi + p[VR_HEAVE_PHASE], m.z);
    harmonic(p[VR_PITCH_RAO] * wave_number(s) * p[VR_WAVE_AMPLITUDE], omega, psi + p[VR_PITCH_PHASE], m.theta);
    return m;
}

/* The value of output (or calculated parameter) vr at the instance's time. */
static int irregular(const Instance *s) { return s->values[VR_SEA_HS] != 0.0; }

/* The irregular sea's outputs (the motion at the record's time t + sea.time_shift). */
static double sea_output(Instance *s, fmi2ValueReference vr) {
    Sea *sea = &s->sea;
    sea_evaluate(sea, s->time + s->values[VR_SEA_TIME_SHIFT]);
    switch (vr) {
    case VR_WAVE_ELEVATION: return sea->zeta;
    case VR_HEAVE: return sea->sums[0][0];
    case VR_PITCH: return sea->sums[1][0];
    case VR_HINGE_HEAVE:
    case VR_HINGE_HEAVE_VELOCITY:
    case VR_HINGE_HEAVE_ACCELERATION: return sea->sums[2][vr - VR_HINGE_HEAVE];
    case VR_CLAMP_HEAVE:
    case VR_CLAMP_HEAVE_VELOCITY:
    case VR_CLAMP_HEAVE_ACCELERATION: return sea->sums[3][vr - VR_CLAMP_HEAVE];
    default: return sea->sums[4][vr - VR_CLAMP_ROTATION];
    }
}

static double output(Instance *s, fmi2ValueReference vr) {
    const double *p = s->values;
    double hinge = s->booleans[VR_HINGE_ON_VESSEL - N_REAL] ? 1.0 : 0.0;
    double clamp = s->booleans[VR_CLAMP_ON_VESSEL - N_REAL] ? 1.0 : 0.0;
    /* the arrestor's cosine with the forward axis: clamp.direction, or in the irregular sea cos psi */
    double direction = irregular(s) ? cos(p[VR_SEA_ARRESTOR] * (PI / 180.0)) : p[VR_CLAMP_DIRECTION];
    double deck_force = -(hinge * p[VR_HINGE_FORCE] + clamp * p[VR_CLAMP_FORCE]);
    double deck_moment = hinge * p[VR_HINGE_X] * p[VR_HINGE_FORCE] +
                         clamp * (p[VR_CLAMP_X] * p[VR_CLAMP_FORCE] + direction * p[VR_CLAMP_MOMENT]);
    Motion m;
    if (vr >= VR_WAVE_ELEVATION && vr <= VR_CLAMP_ROTATION_ACCELERATION && irregular(s) && s->sea.ready)
        return sea_output(s, vr);
    m = motion(s, s->time);
    switch (vr) {
    case VR_WAVE_ELEVATION: return m.zeta;
    case VR_HEAVE: return m.z[0];
    case VR_PITCH: return m.theta[0];
    case VR_HINGE_HEAVE:
    case VR_HINGE_HEAVE_VELOCITY:
    case VR_HINGE_HEAVE_ACCELERATION: {
        int k = (int)(vr - VR_HINGE_HEAVE);
        return hinge * (m.z[k] - p[VR_HINGE_X] * m.theta[k]);
    }
    case VR_CLAMP_HEAVE:
    case VR_CLAMP_HEAVE_VELOCITY:
    case VR_CLAMP_HEAVE_ACCELERATION: {
        int k = (int)(vr - VR_CLAMP_HEAVE);
        return clamp * (m.z[k] - p[VR_CLAMP_X] * m.theta[k]);
    }
    case VR_CLAMP_ROTATION:
    case VR_CLAMP_ROTATION_VELOCITY:
    case VR_CLAMP_ROTATION_ACCELERATION:
        return clamp * -p[VR_CLAMP_DIRECTION] * m.theta[vr - VR_CLAMP_ROTATION];
    case VR_DECK_FORCE: return deck_force;
    case VR_DECK_PITCH_MOMENT: return deck_moment;
    case VR_DECK_HEAVE_ACCELERATION: return deck_force / p[VR_VESSEL_MASS];
    case VR_DECK_PITCH_ACCELERATION: return deck_moment / p[VR_VESSEL_PITCH_INERTIA];
    case VR_WAVE_LENGTH: return 2.0 * PI / wave_number(s);
    default: return p[vr];
    }
}

/* Whether the parameters are valid and, in the irregular sea, its record made (once per set of
 * parameters: reading the RAO file and drawing the components is the only allocation). */
static int prepared(Instance *s, char *why, size_t n) {
    if (!parameters_valid(s, why, n)) return 0;
    if (irregular(s) && !s->sea.ready)
        return sea_make(&s->sea, s->values, s->booleans, s->resources, why, n);
    return 1;
}

/* The resource folder's path from fmuResourceLocation (a file URI: file:///path, file:/path or
 * file://localhost/path, percent-encoded; file:///C:/path on Windows), or NULL. */
static char *resource_path(const char *uri) {
    const char *p;
    char *path, *out;
    size_t len;
    if (uri == NULL || strncmp(uri, "file:", 5) != 0) return NULL;
    p = uri + 5;
    if (strncmp(p, "//localhost/", 12) == 0) p += 11;
    else if (strncmp(p, "///", 3) == 0) p += 2;
    else if (strncmp(p, "//", 2) == 0) return NULL; /* a remote host */
#if defined(_WIN32)
    if (p[0] == '/' && isalpha((unsigned char)p[1]) && p[2] == ':') p++;
#endif
    len = strlen(p);
    if (len == 0 || len > 4000) return NULL;
    path = out = (char *)malloc(len + 1);
    if (path == NULL) return NULL;
    while (*p) {
        if (p[0] == '%' && isxdigit((unsigned char)p[1]) && isxdigit((unsigned char)p[2])) {
            char hex[3] = {p[1], p[2], '\0'};
            *out++ = (char)strtol(hex, NULL, 16);
            p += 3;
        } else {
            *out++ = *p++;
        }
    }
    *out = '\0';
    while (out > path + 1 && out[-1] == '/') *--out = '\0';
    return path;
}

/* ---- inquire version numbers, logging -------------------------------------------------------- */

FMI2_EXPORT const char *fmi2GetTypesPlatform(void) { return fmi2TypesPlatform; }

FMI2_EXPORT const char *fmi2GetVersion(void) { return fmi2Version; }

FMI2_EXPORT fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean loggingOn, size_t nCategories,
                               const fmi2String categories[]) {
    Instance *s = (Instance *)c;
    if (s == NULL) return fmi2Error;
    if (nCategories > 0 && categories == NULL) return fail(s, "fmi2SetDebugLogging", "categories is NULL");
    s->logging_on = loggingOn;
    return fmi2OK;
}

/* ---- creation and destruction ---------------------------------------------------------------- */

static void set_defaults(Instance *s) {
    size_t i;
    for (i = 0; i < N_REAL; i++) s->values[i] = IS_PARAMETER(i) || IS_INPUT(i) ? START[i] : 0.0;
    sea_free(&s->sea);
    memcpy(s->booleans, START_BOOLEAN, sizeof START_BOOLEAN);
}

FMI2_EXPORT fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID,
                              fmi2String fmuResourceLocation, const fmi2CallbackFunctions *functions,
                              fmi2Boolean visible, fmi2Boolean loggingOn) {
    Instance *s;
    Instance probe;
    (void)visible;
    memset(&probe, 0, sizeof probe);
    probe.name = (char *)(instanceName ? instanceName : "VesselMotion");
    probe.logger = functions ? functions->logger : NULL;
    probe.env = functions ? functions->componentEnvironment : NULL;
    if (instanceName == NULL || instanceName[0] == '\0') {
        fail(&probe, "fmi2Instantiate", "missing instance name");
        return NULL;
    }
    if (fmuType != fmi2CoSimulation) {
        fail(&probe, "fmi2Instantiate", "only co-simulation (fmi2CoSimulation) is supported");
        return NULL;
    }
    if (fmuGUID == NULL || strcmp(fmuGUID, GUID) != 0) {
        fail(&probe, "fmi2Instantiate", "GUID does not match this binary's " GUID);
        return NULL;
    }
    /* canNotUseMemoryManagementFunctions="true": plain calloc, the callbacks may be NULL. */
    s = (Instance *)calloc(1, sizeof *s);
    if (s == NULL || (s->name = (char *)malloc(strlen(instanceName) + 1)) == NULL) {
        free(s);
        fail(&probe, "fmi2Instantiate", "out of memory");
        return NULL;
    }
    strcpy(s->name, instanceName);
    s->resources = resource_path(fmuResourceLocation);
    s->logger = probe.logger;
    s->env = probe.env;
    s->logging_on = loggingOn;
    s->phase = INSTANTIATED;
    s->time = 0.0;
    set_defaults(s);
    log_message(s, fmi2OK, "logAll", "instantiated (wave %g m amplitude, %g s period by default)",
                START[VR_WAVE_AMPLITUDE], START[VR_WAVE_PERIOD]);
    return s;
}

FMI2_EXPORT void fmi2FreeInstance(fmi2Component c) {
    Instance *s = (Instance *)c;
    if (s == NULL) return;
    sea_free(&s->sea);
    free(s->resources);
    free(s->name);
    free(s);
}

/* ---- initialization, termination, reset ------------------------------------------------------ */

FMI2_EXPORT fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean toleranceDefined, fmi2Real tolerance,
                               fmi2Real startTime, fmi2Boolean stopTimeDefined, fmi2Real stopTime) {
    Instance *s = (Instance *)c;
    (void)toleranceDefined;
    (void)tolerance;
    if (s == NULL) return fmi2Error;
    if (s->phase != INSTANTIATED) return fail(s, "fmi2SetupExperiment", "only allowed after fmi2Instantiate");
    if (!isfinite(startTime)) return fail(s, "fmi2SetupExperiment", "startTime is not finite");
    if (stopTimeDefined && !(stopTime >= startTime))
        return fail(s, "fmi2SetupExperiment", "stopTime is before startTime");
    s->time = startTime;
    return fmi2OK;
}

FMI2_EXPORT fmi2Status fmi2EnterInitializationMode(fmi2Component c) {
    Instance *s = (Instance *)c;
    if (s == NULL) return fmi2Error;
    if (s->phase != INSTANTIATED) return fail(s, "fmi2EnterInitializationMode", "only allowed after fmi2Instantiate");
    s->phase = INITIALIZATION;
    return fmi2OK;
}

FMI2_EXPORT fmi2Status fmi2ExitInitializationMode(fmi2Component c) {
    Instance *s = (Instance *)c;
    char why[512];
    if (s == NULL) return fmi2Error;
    if (s->phase != INITIALIZATION) return fail(s, "fmi2ExitInitializationMode", "not in initialization mode");
    if (!prepared(s, why, sizeof why)) {
        s->phase = FAILED;
        return fail(s, "fmi2ExitInitializationMode", why);
    }
    if (irregular(s))
        log_message(s, fmi2OK, "logAll", "irregular sea: Hs %g m, Tp %g s, gamma %.3f, heading %g deg, seed %.17g, %d components over %.4f to %.4f rad/s",
                    s->values[VR_SEA_HS], s->values[VR_SEA_TP], s->sea.gamma, s->values[VR_SEA_HEADING], s->values[VR_SEA_SEED],
                    s->sea.n, s->sea.lo, s->sea.hi);
    else
        log_message(s, fmi2OK, "logAll", "wave length %g m, pitch amplitude %g rad", output(s, VR_WAVE_LENGTH),
                    s->values[VR_PITCH_RAO] * wave_number(s) * s->values[VR_WAVE_AMPLITUDE]);
    s->phase = STEP_COMPLETE;
    return fmi2OK;
}

FMI2_EXPORT fmi2Status fmi2Terminate(fmi2Component c) {
    Instance *s = (Instance *)c;
    if (s == NULL) return fmi2Error;
    if (s->phase != STEP_COMPLETE) return fail(s, "fmi2Terminate", "only allowed after initialization");
    s->phase = TERMINATED;
    return fmi2OK;
}

FMI2_EXPORT fmi2Status fmi2Reset(fmi2Component c) {
    Instance *s = (Instance *)c;
    if (s == NULL) return fmi2Error;
    s->phase = INSTANTIATED;
    s->time = 0.0;
    set_defaults(s);
    return fmi2OK;
}

/* ---- getting and setting values -------------------------------------------------------------- */

/* Whether values may be read now; in initialization mode the parameters must be valid (the
 * outputs at the start time depend on them). */
static fmi2Status readable(Instance *s, const char *function) {
    char why[512];
    if (s->phase == INSTANTIATED || s->phase == FAILED)
        return fail(s, function, "not allowed before initialization mode or after an error");
    if (s->phase == INITIALIZATION && !prepared(s, why, sizeof why)) return fail(s, function, why);
    return fmi2OK;
}

FMI2_EXPORT fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Real value[]) {
    Instance *s = (Instance *)c;
    size_t i;
    if (s == NULL) return fmi2Error;
    if (nvr == 0) return fmi2OK;
    if (vr == NULL || value == NULL) return fail(s, "fmi2GetReal", "vr or value is NULL");
    if (readable(s, "fmi2GetReal") != fmi2OK) return fmi2Error;
    for (i = 0; i < nvr; i++) {
        if (vr[i] >= N_REAL) {
            char why[80];
            snprintf(why, sizeof why, "unknown Real value reference %u", vr[i]);
            return fail(s, "fmi2GetReal", why);
        }
        value[i] = output(s, vr[i]);
    }
    return fmi2OK;
}

FMI2_EXPORT fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Real value[]) {
    Instance *s = (Instance *)c;
    size_t i;
    char why[120];
    if (s == NULL) return fmi2Error;
    if (nvr == 0) return fmi2OK;
    if (vr == NULL || value == NULL) return fail(s, "fmi2SetReal", "vr or value is NULL");
    if (s->phase == TERMINATED || s->phase == FAILED) return fail(s, "fmi2SetReal", "not allowed after termination or an error");
    for (i = 0; i < nvr; i++) {
        fmi2ValueReference r = vr[i];
        if (!IS_PARAMETER(r) && !IS_INPUT(r)) {
            snprintf(why, sizeof why, "value reference %u is not a Real input or parameter", r);
            return fail(s, "fmi2SetReal", why);
        }
        if (IS_PARAMETER(r) && s->phase == STEP_COMPLETE) {
            snprintf(why, sizeof why, "parameter %u is fixed: set it before fmi2ExitInitializationMode", r);
            return fail(s, "fmi2SetReal", why);
        }
        if (!isfinite(value[i])) {
            snprintf(why, sizeof why, "value reference %u: value is not finite", r);
            return fail(s, "fmi2SetReal", why);
        }
    }
    for (i = 0; i < nvr; i++) {
        /* a parameter changed: the irregular sea's record is made again when next needed */
        if (IS_PARAMETER(vr[i]) && s->values[vr[i]] != value[i]) sea_free(&s->sea);
        s->values[vr[i]] = value[i];
    }
    return fmi2OK;
}

FMI2_EXPORT fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Boolean value[]) {
    Instance *s = (Instance *)c;
    size_t i;
    if (s == NULL) return fmi2Error;
    if (nvr == 0) return fmi2OK;
    if (vr == NULL || value == NULL) return fail(s, "fmi2GetBoolean", "vr or value is NULL");
    if (readable(s, "fmi2GetBoolean") != fmi2OK) return fmi2Error;
    for (i = 0; i < nvr; i++) {
        if (vr[i] < N_REAL || vr[i] >= N_VR) {
            char why[80];
            snprintf(why, sizeof why, "unknown Boolean value reference %u", vr[i]);
            return fail(s, "fmi2GetBoolean", why);
        }
        value[i] = s->booleans[vr[i] - N_REAL];
    }
    return fmi2OK;
}

FMI2_EXPORT fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Boolean value[]) {
    Instance *s = (Instance *)c;
    size_t i;
    char why[120];
    if (s == NULL) return fmi2Error;
    if (nvr == 0) return fmi2OK;
    if (vr == NULL || value == NULL) return fail(s, "fmi2SetBoolean", "vr or value is NULL");
    if (s->phase != INSTANTIATED && s->phase != INITIALIZATION)
        return fail(s, "fmi2SetBoolean", "the Boolean parameters are fixed: set them before fmi2ExitInitializationMode");
    for (i = 0; i < nvr; i++) {
        if (vr[i] < N_REAL || vr[i] >= N_VR) {
            snprintf(why, sizeof why, "unknown Boolean value reference %u", vr[i]);
            return fail(s, "fmi2SetBoolean", why);
        }
    }
    sea_free(&s->sea);
    for (i = 0; i < nvr; i++) s->booleans[vr[i] - N_REAL] = value[i] ? fmi2True : fmi2False;
    return fmi2OK;
}

/* No Integer or String variables: empty requests succeed, anything else is an error. */
FMI2_EXPORT fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Integer value[]) {
    (void)vr;
    (void)value;
    if (c == NULL) return fmi2Error;
    return nvr == 0 ? fmi2OK : fail((Instance *)c, "fmi2GetInteger", "this FMU has no Integer variables");
}

FMI2_EXPORT fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2String value[]) {
    (void)vr;
    (void)value;
    if (c == NULL) return fmi2Error;
    return nvr == 0 ? fmi2OK : fail((Instance *)c, "fmi2GetString", "this FMU has no String variables");
}

FMI2_EXPORT fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Integer value[]) {
    (void)vr;
    (void)value;
    if (c == NULL) return fmi2Error;
    return nvr == 0 ? fmi2OK : fail((Instance *)c, "fmi2SetInteger", "this FMU has no Integer variables");
}

FMI2_EXPORT fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2String value[]) {
    (void)vr;
    (void)value;
    if (c == NULL) return fmi2Error;
    return nvr == 0 ? fmi2OK : fail((Instance *)c, "fmi2SetString", "this FMU has no String variables");
}

/* ---- FMU state, directional derivatives: not supported (canGetAndSetFMUstate="false") ---------- */

FMI2_EXPORT fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate *FMUstate) {
    (void)FMUstate;
    return unsupported(c, "fmi2GetFMUstate");
}

FMI2_EXPORT fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate FMUstate) {
    (void)FMUstate;
    return unsupported(c, "fmi2SetFMUstate");
}

FMI2_EXPORT fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate *FMUstate) {
    if (c == NULL) return fmi2Error;
    /* Freeing a null state is ignored (FMI 2.0.4); no state can ever be handed out. */
    if (FMUstate == NULL || *FMUstate == NULL) return fmi2OK;
    return unsupported(c, "fmi2FreeFMUstate");
}

FMI2_EXPORT fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate FMUstate, size_t *size) {
    (void)FMUstate;
    (void)size;
    return unsupported(c, "fmi2SerializedFMUstateSize");
}

FMI2_EXPORT fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate FMUstate, fmi2Byte serializedState[], size_t size) {
    (void)FMUstate;
    (void)serializedState;
    (void)size;
    return unsupported(c, "fmi2SerializeFMUstate");
}

FMI2_EXPORT fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte serializedState[], size_t size,
                                   fmi2FMUstate *FMUstate) {
    (void)serializedState;
    (void)size;
    (void)FMUstate;
    return unsupported(c, "fmi2DeSerializeFMUstate");
}

FMI2_EXPORT fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference vUnknown_ref[], size_t nUnknown,
                                        const fmi2ValueReference vKnown_ref[], size_t nKnown,
                                        const fmi2Real dvKnown[], fmi2Real dvUnknown[]) {
    (void)vUnknown_ref;
    (void)nUnknown;
    (void)vKnown_ref;
    (void)nKnown;
    (void)dvKnown;
    (void)dvUnknown;
    return unsupported(c, "fmi2GetDirectionalDerivative");
}

/* ---- co-simulation ----------------------------------------------------------------------------- */

FMI2_EXPORT fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                       const fmi2Integer order[], const fmi2Real value[]) {
    (void)vr;
    (void)nvr;
    (void)order;
    (void)value;
    return unsupported(c, "fmi2SetRealInputDerivatives (canInterpolateInputs=\"false\")");
}

FMI2_EXPORT fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                        const fmi2Integer order[], fmi2Real value[]) {
    (void)vr;
    (void)nvr;
    (void)order;
    (void)value;
    return unsupported(c, "fmi2GetRealOutputDerivatives (maxOutputDerivativeOrder=\"0\")");
}

FMI2_EXPORT fmi2Status fmi2DoStep(fmi2Component c, fmi2Real currentCommunicationPoint, fmi2Real communicationStepSize,
                      fmi2Boolean noSetFMUStatePriorToCurrentPoint) {
    Instance *s = (Instance *)c;
    char why[160];
    (void)noSetFMUStatePriorToCurrentPoint;
    if (s == NULL) return fmi2Error;
    if (s->phase != STEP_COMPLETE) return fail(s, "fmi2DoStep", "only allowed after fmi2ExitInitializationMode");
    if (!(communicationStepSize > 0.0) || !isfinite(communicationStepSize)) {
        snprintf(why, sizeof why, "communicationStepSize must be > 0 s, got %g", communicationStepSize);
        return fail(s, "fmi2DoStep", why);
    }
    /* Importers accumulate t + h in floating point: accept a communication point within a
     * relative 1e-9 of the instance's time. */
    if (fabs(currentCommunicationPoint - s->time) > 1e-9 * fmax(1.0, fabs(s->time))) {
        snprintf(why, sizeof why, "currentCommunicationPoint %.17g s is not the instance's time %.17g s",
                 currentCommunicationPoint, s->time);
        return fail(s, "fmi2DoStep", why);
    }
    /* No state: the motion is a function of time, the deck loads follow the inputs. */
    s->time = currentCommunicationPoint + communicationStepSize;
    return fmi2OK;
}

FMI2_EXPORT fmi2Status fmi2CancelStep(fmi2Component c) {
    return unsupported(c, "fmi2CancelStep (fmi2DoStep never returns fmi2Pending)");
}

FMI2_EXPORT fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind kind, fmi2Status *value) {
    (void)kind;
    (void)value;
    return unsupported(c, "fmi2GetStatus (fmi2DoStep never returns fmi2Pending)");
}

FMI2_EXPORT fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind kind, fmi2Real *value) {
    Instance *s = (Instance *)c;
    if (s == NULL) return fmi2Error;
    if (kind != fmi2LastSuccessfulTime || value == NULL) return unsupported(c, "fmi2GetRealStatus (only fmi2LastSuccessfulTime)");
    *value = s->time;
    return fmi2OK;
}

FMI2_EXPORT fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind kind, fmi2Integer *value) {
    (void)kind;
    (void)value;
    return unsupported(c, "fmi2GetIntegerStatus");
}

FMI2_EXPORT fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind kind, fmi2Boolean *value) {
    Instance *s = (Instance *)c;
    if (s == NULL) return fmi2Error;
    if (kind != fmi2Terminated || value == NULL) return unsupported(c, "fmi2GetBooleanStatus (only fmi2Terminated)");
    *value = fmi2False; /* the FMU never asks to end the simulation */
    return fmi2OK;
}

FMI2_EXPORT fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind kind, fmi2String *value) {
    (void)kind;
    (void)value;
    return unsupported(c, "fmi2GetStringStatus");
}
