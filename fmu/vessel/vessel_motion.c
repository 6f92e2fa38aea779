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
 * The outputs are algebraic in time and in the inputs; the FMU has no state, a step only
 * advances its time. The FMI 2 types come from fmi2_abi.h beside this file (written from the
 * standard: no header files of the standard are needed to build it). Every one of the 25 common and 9 co-simulation functions exists; the
 * unsupported ones log why and return fmi2Error. The logger is always called with "%s".
 */
#include <math.h>
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
    N_REAL,
    /* Boolean parameters */
    VR_HINGE_ON_VESSEL = N_REAL, VR_CLAMP_ON_VESSEL,
    N_VR
};

#define FIRST_INPUT VR_HINGE_FORCE
#define FIRST_OUTPUT VR_WAVE_ELEVATION
#define N_BOOLEAN (N_VR - N_REAL)

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
static double output(const Instance *s, fmi2ValueReference vr) {
    const double *p = s->values;
    double hinge = s->booleans[VR_HINGE_ON_VESSEL - N_REAL] ? 1.0 : 0.0;
    double clamp = s->booleans[VR_CLAMP_ON_VESSEL - N_REAL] ? 1.0 : 0.0;
    Motion m = motion(s, s->time);
    double deck_force = -(hinge * p[VR_HINGE_FORCE] + clamp * p[VR_CLAMP_FORCE]);
    double deck_moment = hinge * p[VR_HINGE_X] * p[VR_HINGE_FORCE] +
                         clamp * (p[VR_CLAMP_X] * p[VR_CLAMP_FORCE] + p[VR_CLAMP_DIRECTION] * p[VR_CLAMP_MOMENT]);
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
    for (i = 0; i < N_REAL; i++) s->values[i] = i < FIRST_OUTPUT ? START[i] : 0.0;
    memcpy(s->booleans, START_BOOLEAN, sizeof START_BOOLEAN);
}

FMI2_EXPORT fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID,
                              fmi2String fmuResourceLocation, const fmi2CallbackFunctions *functions,
                              fmi2Boolean visible, fmi2Boolean loggingOn) {
    Instance *s;
    Instance probe;
    (void)fmuResourceLocation;
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
    char why[160];
    if (s == NULL) return fmi2Error;
    if (s->phase != INITIALIZATION) return fail(s, "fmi2ExitInitializationMode", "not in initialization mode");
    if (!parameters_valid(s, why, sizeof why)) {
        s->phase = FAILED;
        return fail(s, "fmi2ExitInitializationMode", why);
    }
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
    char why[160];
    if (s->phase == INSTANTIATED || s->phase == FAILED)
        return fail(s, function, "not allowed before initialization mode or after an error");
    if (s->phase == INITIALIZATION && !parameters_valid(s, why, sizeof why)) return fail(s, function, why);
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
        if (r >= FIRST_OUTPUT) {
            snprintf(why, sizeof why, "value reference %u is not a Real input or parameter", r);
            return fail(s, "fmi2SetReal", why);
        }
        if (r < FIRST_INPUT && s->phase == STEP_COMPLETE) {
            snprintf(why, sizeof why, "parameter %u is fixed: set it before fmi2ExitInitializationMode", r);
            return fail(s, "fmi2SetReal", why);
        }
        if (!isfinite(value[i])) {
            snprintf(why, sizeof why, "value reference %u: value is not finite", r);
            return fail(s, "fmi2SetReal", why);
        }
    }
    for (i = 0; i < nvr; i++) s->values[vr[i]] = value[i];
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
