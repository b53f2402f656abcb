/* fmi3_harness: drives an unzipped triad FMI 3.0 FMU through the Co-Simulation sequence by
 * loading its binary the way an importer does (dlopen / LoadLibrary), and prints the results
 * for comparison with the FMI 2 harness on the same platform (tests/platforms/run_harness.py):
 *
 *     fmi3_harness LIBRARY FMU_DIR [STEPS]
 *
 * Sequence: a wrong instantiation token and a NULL resource path refused, instantiate with the
 * resource path (a path, with its trailing separator), a step before initialisation refused,
 * initialisation, NULL arguments and a wrong nValues refused, a NaN input refused, STEPS
 * fmi3DoStep of 1/STEPS s with the FMI 2 harness's inputs (the same scalars in the same order:
 * arrays are row-major) set before each step and every Float64 output read after it,
 * get/set and serialise/deserialise of the state (repeating the steps bit for bit), fmi3Reset
 * (the run repeats bit for bit), terminate, free.
 *
 * Printed on stdout: `out NAME#K VALUE` for element K (0-based, row-major) of every Float64
 * output after the last step (%.17g), and `checks N passed, M failed`. Exit status 0 when every
 * check passed. Written for this project from the FMI 3.0 standard's function signatures.
 */
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness_util.h"

#ifdef _WIN32
#define SEP "\\"
#else
#define SEP "/"
#endif

/* FMI 3.0 types (fmi3PlatformTypes.h) */
typedef void *fmi3Instance;
typedef void *fmi3FMUState;
typedef unsigned int fmi3ValueReference;
typedef double fmi3Float64;
typedef bool fmi3Boolean;
typedef unsigned char fmi3Byte;
typedef const char *fmi3String;
typedef int fmi3Status; /* OK 0, Warning 1, Discard 2, Error 3, Fatal 4 */
typedef void (*fmi3LogMessageCallback)(void *, fmi3Status, fmi3String, fmi3String);

typedef const char *(*GetStr)(void);
typedef fmi3Instance (*Instantiate)(fmi3String, fmi3String, fmi3String, fmi3Boolean, fmi3Boolean,
                                    fmi3Boolean, fmi3Boolean, const fmi3ValueReference *, size_t,
                                    void *, fmi3LogMessageCallback, void *);
typedef void (*FreeInstance)(fmi3Instance);
typedef fmi3Status (*EnterInit)(fmi3Instance, fmi3Boolean, fmi3Float64, fmi3Float64, fmi3Boolean,
                                fmi3Float64);
typedef fmi3Status (*Inst)(fmi3Instance);
typedef fmi3Status (*GetF64)(fmi3Instance, const fmi3ValueReference *, size_t, fmi3Float64 *,
                             size_t);
typedef fmi3Status (*SetF64)(fmi3Instance, const fmi3ValueReference *, size_t,
                             const fmi3Float64 *, size_t);
typedef fmi3Status (*DoStep)(fmi3Instance, fmi3Float64, fmi3Float64, fmi3Boolean, fmi3Boolean *,
                             fmi3Boolean *, fmi3Boolean *, fmi3Float64 *);
typedef fmi3Status (*StateGet)(fmi3Instance, fmi3FMUState *);
typedef fmi3Status (*StateSet)(fmi3Instance, fmi3FMUState);
typedef fmi3Status (*StateSize)(fmi3Instance, fmi3FMUState, size_t *);
typedef fmi3Status (*StateSer)(fmi3Instance, fmi3FMUState, fmi3Byte *, size_t);
typedef fmi3Status (*StateDe)(fmi3Instance, const fmi3Byte *, size_t, fmi3FMUState *);

static struct {
  GetStr version;
  Instantiate instantiate;
  FreeInstance free_instance;
  EnterInit enter_init;
  Inst exit_init, terminate, reset;
  GetF64 get;
  SetF64 set;
  DoStep do_step;
  StateGet get_state;
  StateSet set_state;
  StateGet free_state;
  StateSize state_size;
  StateSer serialize;
  StateDe deserialize;
} api;

static void logger(void *env, fmi3Status st, fmi3String cat, fmi3String msg) {
  (void)env;
  fprintf(stderr, "[%d %s] %s\n", st, cat ? cat : "?", msg ? msg : "");
}

#define MAXV 4096
static char names[MAXV][128];
static size_t sizes[MAXV];
static fmi3ValueReference in_vr[MAXV], out_vr[MAXV];
static int out_var[MAXV], in_var[MAXV];
static size_t n_in, n_out, n_in_values, n_out_values;

/* every <Float64> variable but `time`: name, value reference, causality, size (the product of
 * its <Dimension start>s) */
static void parse_variables(const char *xml) {
  const char *p = strstr(xml, "<ModelVariables>");
  const char *stop = p ? strstr(p, "</ModelVariables>") : NULL;
  int i = 0;
  while (p && (p = strstr(p + 1, "<Float64 ")) != NULL && p < stop && i < MAXV) {
    const char *tag_end = strchr(p, '>');
    char vr[32], caus[32] = "local", dim[32];
    size_t size = 1;
    if (!tag_end) break;
    if (tag_end[-1] != '/') {
      const char *close = strstr(p, "</Float64>");
      const char *d = p;
      while ((d = strstr(d + 1, "<Dimension ")) != NULL && close && d < close) {
        if (attr(d, strchr(d, '>'), "start", dim, sizeof dim)) size *= strtoul(dim, NULL, 10);
      }
    }
    if (!attr(p, tag_end, "name", names[i], 128) || !attr(p, tag_end, "valueReference", vr, sizeof vr))
      continue;
    attr(p, tag_end, "causality", caus, sizeof caus);
    sizes[i] = size;
    if (!strcmp(caus, "input")) {
      in_var[n_in] = i;
      in_vr[n_in++] = (fmi3ValueReference)strtoul(vr, NULL, 10);
      n_in_values += size;
    }
    if (!strcmp(caus, "output")) {
      out_var[n_out] = i;
      out_vr[n_out++] = (fmi3ValueReference)strtoul(vr, NULL, 10);
      n_out_values += size;
    }
    i++;
  }
}

/* the FMI 2 harness's inputs: element j of the flattened inputs at step `step` */
static double input_value(size_t step, size_t i) {
  return 0.2 * sin(0.05 * (double)step + (double)i) / (double)(1 + i % 3);
}

static fmi3Status do_step(fmi3Instance c, double t, double h) {
  fmi3Boolean ev = 0, term = 0, early = 0;
  fmi3Float64 last = 0;
  fmi3Status s = api.do_step(c, t, h, 1, &ev, &term, &early, &last);
  if (s == 0 && (ev || term || early || last != t + h)) return 3;
  return s;
}

static fmi3Status run_steps(fmi3Instance c, size_t from, size_t to, double h, double *trace) {
  size_t k, j;
  double u[MAXV], y[MAXV];
  for (k = from; k < to; k++) {
    fmi3Status s;
    for (j = 0; j < n_in_values; j++) u[j] = input_value(k, j);
    if (n_in && api.set(c, in_vr, n_in, u, n_in_values) != 0) return 3;
    s = do_step(c, (double)k * h, h);
    if (s != 0) return s;
    if (api.get(c, out_vr, n_out, y, n_out_values) != 0) return 3;
    if (trace) memcpy(trace + (k - from) * n_out_values, y, n_out_values * sizeof(double));
  }
  return 0;
}

int main(int argc, char **argv) {
  char path[4096], token[128] = "", res[8192];
  char *xml;
  lib_t lib;
  fmi3Instance c, bad;
  size_t steps = argc > 3 ? (size_t)strtoul(argv[3], NULL, 10) : 1000, j, k, e;
  double h = 1.0 / (double)steps, nan = NAN, y[MAXV], first[MAXV];
  double *trace, *again, *start;
  fmi3FMUState st = NULL, st2 = NULL;
  size_t size = 0, mid = steps / 2, span = steps / 10 ? steps / 10 : 1;
  fmi3Byte *buf;

  if (argc < 3) {
    fprintf(stderr, "usage: fmi3_harness LIBRARY FMU_DIR [STEPS]\n");
    return 2;
  }
  snprintf(path, sizeof path, "%s/modelDescription.xml", argv[2]);
  xml = read_file(path);
  if (!xml || !attr(xml, NULL, "instantiationToken", token, sizeof token)) {
    fprintf(stderr, "%s: no FMI 3 modelDescription.xml with an instantiationToken\n", path);
    return 2;
  }
  parse_variables(xml);
  lib = lib_open(argv[1]);
  if (!lib) {
    printf("FAIL cannot load %s: %s\n", argv[1], lib_error());
    return 2;
  }
  api.version = (GetStr)sym(lib, "fmi3GetVersion");
  api.instantiate = (Instantiate)sym(lib, "fmi3InstantiateCoSimulation");
  api.free_instance = (FreeInstance)sym(lib, "fmi3FreeInstance");
  api.enter_init = (EnterInit)sym(lib, "fmi3EnterInitializationMode");
  api.exit_init = (Inst)sym(lib, "fmi3ExitInitializationMode");
  api.terminate = (Inst)sym(lib, "fmi3Terminate");
  api.reset = (Inst)sym(lib, "fmi3Reset");
  api.get = (GetF64)sym(lib, "fmi3GetFloat64");
  api.set = (SetF64)sym(lib, "fmi3SetFloat64");
  api.do_step = (DoStep)sym(lib, "fmi3DoStep");
  api.get_state = (StateGet)sym(lib, "fmi3GetFMUState");
  api.set_state = (StateSet)sym(lib, "fmi3SetFMUState");
  api.free_state = (StateGet)sym(lib, "fmi3FreeFMUState");
  api.state_size = (StateSize)sym(lib, "fmi3SerializedFMUStateSize");
  api.serialize = (StateSer)sym(lib, "fmi3SerializeFMUState");
  api.deserialize = (StateDe)sym(lib, "fmi3DeserializeFMUState");
  check(!strcmp(api.version(), "3.0"), "fmi3GetVersion is 3.0");
#ifdef _WIN32
  GetFullPathNameA(argv[2], sizeof path, path, NULL);
#else
  if (!realpath(argv[2], path)) snprintf(path, sizeof path, "%s", argv[2]);
#endif
  snprintf(res, sizeof res, "%s" SEP "resources" SEP, path);
  fprintf(stderr, "resource path: %s\n", res);

  bad = api.instantiate("bad", "{not-the-token}", res, 0, 0, 0, 0, NULL, 0, NULL, logger, NULL);
  check(bad == NULL, "a wrong instantiation token is refused");
  bad = api.instantiate("bad", token, NULL, 0, 0, 0, 0, NULL, 0, NULL, logger, NULL);
  check(bad == NULL, "a NULL resource path is refused");
  c = api.instantiate("harness", token, res, 0, 0, 0, 0, NULL, 0, NULL, logger, NULL);
  if (!c) {
    printf("FAIL instantiate with %s\n", res);
    return 1;
  }
  check(do_step(c, 0, h) == 3, "fmi3DoStep before initialisation is an error");
  check(api.enter_init(c, 0, 0, 0, 0, 0) == 0, "fmi3EnterInitializationMode");
  check(api.exit_init(c) == 0, "fmi3ExitInitializationMode");
  check(api.get(c, NULL, 1, y, 1) == 3, "fmi3GetFloat64 with NULL references is an error");
  check(api.get(c, out_vr, n_out, y, n_out_values + 1) == 3, "a wrong nValues is an error");
  check(api.get_state(c, NULL) == 3, "fmi3GetFMUState(NULL) is an error");
  if (n_in) {
    double u[MAXV];
    for (j = 0; j < sizes[in_var[0]] && j < MAXV; j++) u[j] = nan;
    check(api.set(c, in_vr, 1, u, sizes[in_var[0]]) == 3, "a NaN input is refused");
  }
  check(api.get(c, out_vr, n_out, first, n_out_values) == 0, "outputs at the start");

  trace = malloc(span * n_out_values * sizeof(double));
  again = malloc(span * n_out_values * sizeof(double));
  start = malloc(span * n_out_values * sizeof(double));
  check(run_steps(c, 0, span, h, start) == 0, "first steps");
  check(run_steps(c, span, mid, h, NULL) == 0, "steps to the middle");
  check(api.get_state(c, &st) == 0, "fmi3GetFMUState");
  check(run_steps(c, mid, mid + span, h, trace) == 0, "steps after the state");
  check(api.set_state(c, st) == 0, "fmi3SetFMUState");
  check(run_steps(c, mid, mid + span, h, again) == 0, "steps again");
  check(!memcmp(trace, again, span * n_out_values * sizeof(double)),
        "a restored state repeats the steps bit for bit");
  check(api.state_size(c, st, &size) == 0 && size > 0, "fmi3SerializedFMUStateSize");
  buf = malloc(size);
  check(api.serialize(c, st, buf, size) == 0, "fmi3SerializeFMUState");
  check(api.free_state(c, &st) == 0 && st == NULL, "fmi3FreeFMUState");
  check(api.deserialize(c, buf, size / 2, &st2) == 3, "a truncated state is refused");
  check(api.deserialize(c, buf, size, &st2) == 0, "fmi3DeserializeFMUState");
  check(api.set_state(c, st2) == 0, "fmi3SetFMUState of the deserialised state");
  check(api.free_state(c, &st2) == 0, "fmi3FreeFMUState of the deserialised state");
  memset(again, 0, span * n_out_values * sizeof(double));
  check(run_steps(c, mid, mid + span, h, again) == 0, "steps after deserialising");
  check(!memcmp(trace, again, span * n_out_values * sizeof(double)),
        "a deserialised state repeats the steps bit for bit");
  check(run_steps(c, mid + span, steps, h, NULL) == 0, "steps to the end");
  check(api.get(c, out_vr, n_out, y, n_out_values) == 0, "outputs at the end");
  for (j = 0, e = 0; j < n_out; j++) {
    for (k = 0; k < sizes[out_var[j]]; k++, e++)
      printf("out %s#%lu %.17g\n", names[out_var[j]], (unsigned long)k, y[e]);
  }

  check(api.reset(c) == 0, "fmi3Reset");
  check(do_step(c, 0, h) == 3, "fmi3DoStep after reset is an error");
  check(api.enter_init(c, 0, 0, 0, 0, 0) == 0 && api.exit_init(c) == 0, "initialised after reset");
  check(api.get(c, out_vr, n_out, y, n_out_values) == 0 &&
            !memcmp(y, first, n_out_values * sizeof(double)),
        "after reset the outputs are the initial ones");
  check(run_steps(c, 0, span, h, trace) == 0, "steps after reset");
  check(!memcmp(trace, start, span * n_out_values * sizeof(double)),
        "after reset the run repeats bit for bit");
  check(api.terminate(c) == 0, "fmi3Terminate");
  check(do_step(c, 0, h) == 3, "fmi3DoStep after terminate is an error");
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
