/* harness_util.h: what both FMI harnesses (fmi_harness.c, fmi3_harness.c) share: loading a
 * shared library the way an importer does, the check counters, reading a file, and reading an
 * XML attribute. Static functions: each harness is one translation unit. */
#ifndef HARNESS_UTIL_H
#define HARNESS_UTIL_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef _WIN32
#include <windows.h>
typedef HMODULE lib_t;
static lib_t lib_open(const char *p) { return LoadLibraryA(p); }
static void *lib_sym(lib_t l, const char *n) { return (void *)GetProcAddress(l, n); }
static void lib_close(lib_t l) { FreeLibrary(l); }
static const char *lib_error(void) {
  static char buf[64];
  snprintf(buf, sizeof buf, "Windows error %lu", (unsigned long)GetLastError());
  return buf;
}
#else
#include <dlfcn.h>
typedef void *lib_t;
static lib_t lib_open(const char *p) { return dlopen(p, RTLD_NOW | RTLD_LOCAL); }
static void *lib_sym(lib_t l, const char *n) { return dlsym(l, n); }
static void lib_close(lib_t l) { dlclose(l); }
static const char *lib_error(void) { return dlerror(); }
#endif

static int passed, failed;

static void check(int ok, const char *what) {
  if (ok) {
    passed++;
  } else {
    failed++;
    printf("FAIL %s\n", what);
  }
}

static char *read_file(const char *path) {
  FILE *f = fopen(path, "rb");
  long n;
  char *buf;
  if (!f) return NULL;
  fseek(f, 0, SEEK_END);
  n = ftell(f);
  fseek(f, 0, SEEK_SET);
  buf = malloc((size_t)n + 1);
  if (fread(buf, 1, (size_t)n, f) != (size_t)n) n = 0;
  buf[n] = 0;
  fclose(f);
  return buf;
}

/* the value of attribute `name` in the element starting at `from` (before `end`, if given),
 * copied into `out` */
static int attr(const char *from, const char *end, const char *name, char *out, size_t cap) {
  char key[64];
  const char *p, *q;
  snprintf(key, sizeof key, " %s=\"", name);
  p = strstr(from, key);
  if (!p || (end && p > end)) return 0;
  p += strlen(key);
  q = strchr(p, '"');
  if (!q || (size_t)(q - p) >= cap) return 0;
  memcpy(out, p, (size_t)(q - p));
  out[q - p] = 0;
  return 1;
}

/* the symbol `name` of `l`, or exit: an importer needs every function */
static void *sym(lib_t l, const char *name) {
  void *p = lib_sym(l, name);
  if (!p) {
    printf("FAIL missing export %s\n", name);
    exit(2);
  }
  return p;
}

#endif
