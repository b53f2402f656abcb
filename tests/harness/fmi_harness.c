/* fmi_harness: drives an unzipped triad FMU through the whole FMI 2.0 Co-Simulation sequence
 * by loading its binary the way an importer does (dlopen / LoadLibrary), and prints the
 * results for comparison between platforms (tests/platforms/run_harness.py):
 *
 *     fmi_harness LIBRARY FMU_DIR [STEPS]
 *
 * Sequence: error cases before instantiation (wrong GUID, NULL and foreign resource
 * locations), instantiate with the resource URI a tool of this system passes (on Windows the
 * drive-letter form file:///C:/dir/resources, and the plain path C:\dir\resources), a call in
 * the wrong state, set-up, initialisation, NULL arguments, a NaN input, STEPS fmi2DoStep of
 * 1/STEPS s with inputs set before each step and every output read after it, get/set and
 * serialise/deserialise of the state (a restored state must repeat the steps bit for bit),
 * fmi2Reset (the run repeats bit for bit), terminate, free.
 *
 * Printed on stdout: `out NAME VALUE` for every Real output after the last step (%.17g),
 * `ew MAX_DRIFT SCALE` (the largest change of system.energy - system.work over the run and
 * the largest |energy| or |work|), and `checks N passed, M failed`. Exit status 0 when every
 * check passed. Written for this project from the FMI 2.0.4 standard's function signatures.
 */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness_util.h"

/* FMI 2.0 types (fmi2TypesPlatform.h, "default" platform) */
typedef void *fmi2Component;
typedef void *fmi2FMUstate;
typedef unsigned int fmi2ValueReference;
typedef double fmi2Real;
typedef int fmi2Integer;
typedef int fmi2Boolean;
typedef const char *fmi2String;
typedef char fmi2Byte;
typedef int fmi2Status; /* OK 0, Warning 1, Discard 2, Error 3, Fatal 4 */
typedef void (*fmi2Logger)(void *, fmi2String, fmi2Status, fmi2String, fmi2String, ...);
typedef struct {
  fmi2Logger logger;
  void *(*allocateMemory)(size_t, size_t);
  void (*freeMemory)(void *);
  void (*stepFinished)(void *, fmi2Status);
  void *componentEnvironment;
} fmi2CallbackFunctions;

typedef const char *(*GetStr)(void);
typedef fmi2Component (*Instantiate)(fmi2String, int, fmi2String, fmi2String,
                                     const fmi2CallbackFunctions *, fmi2Boolean, fmi2Boolean);
typedef void (*FreeInstance)(fmi2Component);
typedef fmi2Status (*Setup)(fmi2Component, fmi2Boolean, fmi2Real, fmi2Real, fmi2Boolean,
                            fmi2Real);
typedef fmi2Status (*Comp)(fmi2Component);
typedef fmi2Status (*RealIO)(fmi2Component, const fmi2ValueReference *, size_t, fmi2Real *);
typedef fmi2Status (*RealSet)(fmi2Component, const fmi2ValueReference *, size_t,
                              const fmi2Real *);
typedef fmi2Status (*DoStep)(fmi2Component, fmi2Real, fmi2Real, fmi2Boolean);
typedef fmi2Status (*StateGet)(fmi2Component, fmi2FMUstate *);
typedef fmi2Status (*StateSet)(fmi2Component, fmi2FMUstate);
typedef fmi2Status (*StateSize)(fmi2Component, fmi2FMUstate, size_t *);
typedef fmi2Status (*StateSer)(fmi2Component, fmi2FMUstate, fmi2Byte *, size_t);
typedef fmi2Status (*StateDe)(fmi2Component, const fmi2Byte *, size_t, fmi2FMUstate *);
typedef fmi2Status (*RealStatus)(fmi2Component, int, fmi2Real *);

static struct {
  GetStr version, types;
  Instantiate instantiate;
  FreeInstance free_instance;
  Setup setup;
  Comp enter_init, exit_init, terminate, reset;
  RealIO get_real;
  RealSet set_real;
  DoStep do_step;
  StateGet get_state;
  StateSet set_state;
  StateGet free_state;
  StateSize state_size;
  StateSer serialize;
  StateDe deserialize;
  RealStatus real_status;
} api;

static int log_count;

static void logger(void *env, fmi2String inst, fmi2Status st, fmi2String cat, fmi2String msg,
                   ...) {
  va_list ap;
  (void)env;
  log_count++;
  fprintf(stderr, "[%s %d %s] ", inst ? inst : "?", st, cat ? cat : "?");
  va_start(ap, msg);
  vfprintf(stderr, msg, ap);
  va_end(ap);
  fputc('\n', stderr);
}

#define MAXV 4096
static char names[MAXV][128];
static fmi2ValueReference in_vr[MAXV], out_vr[MAXV];
static int out_name[MAXV];
static size_t n_in, n_out;
static fmi2ValueReference vr_energy, vr_work;
static int have_energy, have_work;

static void parse_variables(const char *xml) {
  const char *p = xml;
  int i = 0;
  while ((p = strstr(p, "<ScalarVariable")) != NULL && i < MAXV) {
    const char *end = strstr(p, "</ScalarVariable>");
    char vr[32], caus[32] = "local";
    if (!end) break;
    if (strstr(p, "<Real") && strstr(p, "<Real") < end && attr(p, end, "name", names[i], 128) &&
        attr(p, end, "valueReference", vr, sizeof vr)) {
      fmi2ValueReference v = (fmi2ValueReference)strtoul(vr, NULL, 10);
      attr(p, strchr(p, '>'), "causality", caus, sizeof caus);
      if (!strcmp(caus, "input")) in_vr[n_in++] = v;
      if (!strcmp(caus, "output")) {
        out_name[n_out] = i;
        out_vr[n_out++] = v;
        if (!strcmp(names[i], "system.energy")) vr_energy = v, have_energy = 1;
        if (!strcmp(names[i], "system.work")) vr_work = v, have_work = 1;
      }
      i++;
    }
    p = end;
  }
}

/* the resource location a tool of this system passes */
static void resource_uri(const char *dir, char *uri, size_t cap, char *plain, size_t pcap) {
  char full[4096];
  const unsigned char *s;
  size_t n;
#ifdef _WIN32
  GetFullPathNameA(dir, sizeof full, full, NULL);
  snprintf(plain, pcap, "%s\\resources", full);
  n = (size_t)snprintf(uri, cap, "file:///");
#else
  if (!realpath(dir, full)) snprintf(full, sizeof full, "%s", dir);
  snprintf(plain, pcap, "%s/resources", full);
  n = (size_t)snprintf(uri, cap, "file://");
#endif
  for (s = (const unsigned char *)full; *s && n + 4 < cap; s++) {
    if (*s == '\\') {
      uri[n++] = '/';
    } else if ((*s >= 'a' && *s <= 'z') || (*s >= 'A' && *s <= 'Z') || (*s >= '0' && *s <= '9') ||
               strchr("-._~/:", *s)) {
      uri[n++] = (char)*s;
    } else {
      n += (size_t)snprintf(uri + n, cap - n, "%%%02X", *s);
    }
  }
  snprintf(uri + n, cap - n, "/resources/");
}

static double input_value(size_t step, size_t i) {
  return 0.2 * sin(0.05 * (double)step + (double)i) / (double)(1 + i % 3);
}

static fmi2Status run_steps(fmi2Component c, size_t from, size_t to, double h, double *trace,
                            double *ew_drift, double ew0, double *scale) {
  size_t k, j;
  double u[MAXV], y[MAXV];
  for (k = from; k < to; k++) {
    fmi2Status s;
    for (j = 0; j < n_in; j++) u[j] = input_value(k, j);
    if (n_in && api.set_real(c, in_vr, n_in, u) != 0) return 3;
    s = api.do_step(c, (double)k * h, h, 1);
    if (s != 0) return s;
    if (api.get_real(c, out_vr, n_out, y) != 0) return 3;
    if (trace) memcpy(trace + (k - from) * n_out, y, n_out * sizeof(double));
    if (ew_drift && have_energy && have_work) {
      double e = 0, w = 0, d;
      api.get_real(c, &vr_energy, 1, &e);
      api.get_real(c, &vr_work, 1, &w);
      d = fabs((e - w) - ew0);
      if (d > *ew_drift) *ew_drift = d;
      if (fabs(e) > *scale) *scale = fabs(e);
      if (fabs(w) > *scale) *scale = fabs(w);
    }
  }
  return 0;
}

int main(int argc, char **argv) {
  char path[4096], guid[128] = "", model[256] = "", uri[8192], plain[8192];
  char *xml;
  lib_t lib;
  fmi2CallbackFunctions cb = {logger, NULL, NULL, NULL, NULL};
  fmi2Component c, bad;
  size_t steps = argc > 3 ? (size_t)strtoul(argv[3], NULL, 10) : 1000, j;
  double h = 1.0 / (double)steps, ew0 = 0, drift = 0, scale = 0, e = 0, w = 0, nan = NAN, t;
  double *trace, *again, *start, first[MAXV], y[MAXV];
  fmi2FMUstate st = NULL, st2 = NULL;
  size_t size = 0, mid = steps / 2, span = steps / 10 ? steps / 10 : 1;
  fmi2Byte *buf;

  if (argc < 3) {
    fprintf(stderr, "usage: fmi_harness LIBRARY FMU_DIR [STEPS]\n");
    return 2;
  }
  snprintf(path, sizeof path, "%s/modelDescription.xml", argv[2]);
  xml = read_file(path);
  if (!xml || !attr(xml, NULL, "guid", guid, sizeof guid) ||
      !attr(xml, NULL, "modelIdentifier", model, sizeof model)) {
    fprintf(stderr, "%s: no modelDescription.xml with guid and modelIdentifier\n", path);
    return 2;
  }
  parse_variables(xml);
  lib = lib_open(argv[1]);
  if (!lib) {
    printf("FAIL cannot load %s: %s\n", argv[1], lib_error());
    return 2;
  }
  api.version = (GetStr)sym(lib, "fmi2GetVersion");
  api.types = (GetStr)sym(lib, "fmi2GetTypesPlatform");
  api.instantiate = (Instantiate)sym(lib, "fmi2Instantiate");
  api.free_instance = (FreeInstance)sym(lib, "fmi2FreeInstance");
  api.setup = (Setup)sym(lib, "fmi2SetupExperiment");
  api.enter_init = (Comp)sym(lib, "fmi2EnterInitializationMode");
  api.exit_init = (Comp)sym(lib, "fmi2ExitInitializationMode");
  api.terminate = (Comp)sym(lib, "fmi2Terminate");
  api.reset = (Comp)sym(lib, "fmi2Reset");
  api.get_real = (RealIO)sym(lib, "fmi2GetReal");
  api.set_real = (RealSet)sym(lib, "fmi2SetReal");
  api.do_step = (DoStep)sym(lib, "fmi2DoStep");
  api.get_state = (StateGet)sym(lib, "fmi2GetFMUstate");
  api.set_state = (StateSet)sym(lib, "fmi2SetFMUstate");
  api.free_state = (StateGet)sym(lib, "fmi2FreeFMUstate");
  api.state_size = (StateSize)sym(lib, "fmi2SerializedFMUstateSize");
  api.serialize = (StateSer)sym(lib, "fmi2SerializeFMUstate");
  api.deserialize = (StateDe)sym(lib, "fmi2DeSerializeFMUstate");
  api.real_status = (RealStatus)sym(lib, "fmi2GetRealStatus");
  check(!strcmp(api.version(), "2.0"), "fmi2GetVersion is 2.0");
  check(!strcmp(api.types(), "default"), "fmi2GetTypesPlatform is default");
  resource_uri(argv[2], uri, sizeof uri, plain, sizeof plain);
  fprintf(stderr, "resource location: %s\n", uri);

  /* refused instantiations */
  bad = api.instantiate("bad", 1, "{not-the-guid}", uri, &cb, 0, 0);
  check(bad == NULL, "a wrong GUID is refused");
  bad = api.instantiate("bad", 1, guid, NULL, &cb, 0, 0);
  check(bad == NULL, "a NULL resource location is refused");
  bad = api.instantiate("bad", 1, guid, "http://example.invalid/resources", &cb, 0, 0);
  check(bad == NULL, "an http: resource location is refused");

  /* the plain path some tools pass */
  c = api.instantiate("plain", 1, guid, plain, &cb, 0, 0);
  check(c != NULL, "instantiate with a plain path");
  if (c) api.free_instance(c);

  c = api.instantiate(model, 1, guid, uri, &cb, 0, 0);
  if (!c) {
    printf("FAIL instantiate with %s\n", uri);
    return 1;
  }
  check(api.do_step(c, 0, h, 1) == 3, "fmi2DoStep before initialisation is an error");
  check(api.setup(c, 0, 0, 0, 0, 0) == 0, "fmi2SetupExperiment");
  check(api.enter_init(c) == 0, "fmi2EnterInitializationMode");
  check(api.exit_init(c) == 0, "fmi2ExitInitializationMode");
  check(api.get_real(c, NULL, 1, y) == 3, "fmi2GetReal with NULL references is an error");
  check(api.get_real(c, out_vr, 1, NULL) == 3, "fmi2GetReal with a NULL buffer is an error");
  check(api.do_step(NULL, 0, h, 1) == 3, "fmi2DoStep(NULL) is an error");
  check(api.get_state(c, NULL) == 3, "fmi2GetFMUstate(NULL) is an error");
  if (n_in) check(api.set_real(c, in_vr, 1, &nan) == 3, "a NaN input is refused");
  check(api.get_real(c, out_vr, n_out, first) == 0, "outputs at the start");
  if (have_energy && have_work) {
    api.get_real(c, &vr_energy, 1, &e);
    api.get_real(c, &vr_work, 1, &w);
    ew0 = e - w;
    scale = fmax(fabs(e), fabs(w));
  }

  /* the run, with a detour at the middle: get, step, set back, step again */
  trace = malloc(span * n_out * sizeof(double));
  again = malloc(span * n_out * sizeof(double));
  start = malloc(span * n_out * sizeof(double));
  check(run_steps(c, 0, span, h, start, &drift, ew0, &scale) == 0, "first steps");
  check(run_steps(c, span, mid, h, NULL, &drift, ew0, &scale) == 0, "steps to the middle");
  check(api.get_state(c, &st) == 0, "fmi2GetFMUstate");
  check(run_steps(c, mid, mid + span, h, trace, NULL, 0, NULL) == 0, "steps after the state");
  check(api.set_state(c, st) == 0, "fmi2SetFMUstate");
  check(run_steps(c, mid, mid + span, h, again, NULL, 0, NULL) == 0, "steps again");
  check(!memcmp(trace, again, span * n_out * sizeof(double)),
        "a restored state repeats the steps bit for bit");
  check(api.state_size(c, st, &size) == 0 && size > 0, "fmi2SerializedFMUstateSize");
  buf = malloc(size);
  check(api.serialize(c, st, buf, size) == 0, "fmi2SerializeFMUstate");
  check(api.free_state(c, &st) == 0 && st == NULL, "fmi2FreeFMUstate");
  check(api.deserialize(c, buf, size / 2, &st2) == 3, "a truncated state is refused");
  buf[size / 2] ^= 0x5a;
  check(api.deserialize(c, buf, size, &st2) == 3, "a corrupted state is refused");
  buf[size / 2] ^= 0x5a;
  check(api.deserialize(c, buf, size, &st2) == 0, "fmi2DeSerializeFMUstate");
  check(api.set_state(c, st2) == 0, "fmi2SetFMUstate of the deserialised state");
  check(api.free_state(c, &st2) == 0, "fmi2FreeFMUstate of the deserialised state");
  memset(again, 0, span * n_out * sizeof(double));
  check(run_steps(c, mid, mid + span, h, again, NULL, 0, NULL) == 0, "steps after deserialising");
  check(!memcmp(trace, again, span * n_out * sizeof(double)),
        "a deserialised state repeats the steps bit for bit");
  check(run_steps(c, mid + span, steps, h, NULL, &drift, ew0, &scale) == 0, "steps to the end");
  check(api.real_status(c, 2, &t) == 0 && t == (double)(steps - 1) * h + h,
        "fmi2LastSuccessfulTime is the end");
  check(api.get_real(c, out_vr, n_out, y) == 0, "outputs at the end");
  for (j = 0; j < n_out; j++) printf("out %s %.17g\n", names[out_name[j]], y[j]);
  printf("ew %.17g %.17g\n", drift, scale);

  /* reset: the same run again */
  check(api.reset(c) == 0, "fmi2Reset");
  check(api.do_step(c, 0, h, 1) == 3, "fmi2DoStep after reset is an error");
  check(api.setup(c, 0, 0, 0, 0, 0) == 0 && api.enter_init(c) == 0 && api.exit_init(c) == 0,
        "initialised after reset");
  check(api.get_real(c, out_vr, n_out, y) == 0 && !memcmp(y, first, n_out * sizeof(double)),
        "after reset the outputs are the initial ones");
  check(run_steps(c, 0, span, h, trace, NULL, 0, NULL) == 0, "steps after reset");
  check(!memcmp(trace, start, span * n_out * sizeof(double)),
        "after reset the run repeats bit for bit");
  check(api.terminate(c) == 0, "fmi2Terminate");
  check(api.do_step(c, 0, h, 1) == 3, "fmi2DoStep after terminate is an error");
  api.free_instance(c);
  lib_close(lib);
  free(trace);
  free(again);
  free(start);
  free(buf);
  free(xml);
  printf("checks %d passed, %d failed\n", passed, failed);
  return failed ? 1 : 0;
}
