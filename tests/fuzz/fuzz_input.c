/* fuzz_input.c: a libFuzzer target for the input reader and the checks
 * `granmpm check` makes before a run (scripts/fuzz builds and runs it).
 *
 * One input is the text of an input file, optionally followed by --set
 * arguments, each after a NUL byte:
 *     TEXT [NUL SECTION.KEY=VALUE]...      (at most MAX_SETS of them)
 * It goes the way of `granmpm check FILE --set ... --output DIR`
 * (app/plan.c): the reader loads, overrides and checks it
 * (mpm_io_input_open_text, the reader's entry for a text in memory: so a
 * NUL byte can end the text; one in a file is refused before parsing,
 * tests/cli-input.sh), then the size of the run is estimated and checked
 * and the fills, the time step and the output directory are tried. The
 * output is always a temporary directory of this process: a fuzzed
 * output.dir is never tried, as trying one creates and removes a file or a
 * directory where it names.
 *
 * A run that passes is built (mpm_app_plan_build: mesh, fills, bodies,
 * workspace) as check builds it when it is small: at most MAX_POINTS
 * points and MAX_NODES nodes by the estimate (what the build's work and
 * memory grow with), so that one input takes milliseconds; a larger one
 * stops at its estimate. No
 * step is ever run. Its resolved input is then written and read back, and
 * must load and write the same text (what tests/cli-input.sh asserts of
 * the good inputs): otherwise the target aborts, a crash for libFuzzer.
 *
 * Everything is freed before the next input (libFuzzer's leak check). The
 * messages of refused inputs go to stderr, as granmpm prints them;
 * scripts/fuzz runs with -close_fd_mask=2, which keeps libFuzzer's and
 * the sanitizers' reports. */
#define _POSIX_C_SOURCE 200809L
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app/plan.h"
#include "io/io.h"

enum { MAX_SETS = 8 };
#define MAX_POINTS 20000
#define MAX_NODES 100000

int LLVMFuzzerInitialize(int *argc, char ***argv);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* The output directory of every input, made once (removed at exit). */
static char outdir[256];

static void remove_outdir(void)
{
  rmdir(outdir);
}

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
  (void)argc;
  (void)argv;
  const char *tmp = getenv("TMPDIR");
  snprintf(outdir, sizeof outdir, "%s/fuzz-input.XXXXXX", tmp && *tmp ? tmp : "/tmp");
  if (!mkdtemp(outdir)) {
    perror("fuzz_input: mkdtemp");
    exit(1);
  }
  atexit(remove_outdir);
  return 0;
}

/* The text after the first line (which names the source). */
static const char *body(const char *text)
{
  const char *nl = strchr(text, '\n');
  return nl ? nl + 1 : text;
}

/* The resolved input reads back to the same resolved input. */
static void round_trip(const mpm_config *cfg)
{
  char *text = mpm_io_input_text(cfg), *again = NULL;
  if (!text)
    return;
  mpm_config *back = malloc(sizeof *back);
  mpm_io_input *in = NULL;
  mpm_err err = {0};
  if (back && mpm_io_input_open_text(&in, "resolved", text, NULL, 0, back, &err) != MPM_OK) {
    fprintf(stderr, "fuzz_input: the resolved input does not load: %s\n%s", err.msg, text);
    abort();
  }
  if (back && (again = mpm_io_input_text(back)) && strcmp(body(text), body(again)) != 0) {
    fprintf(stderr, "fuzz_input: the resolved input changes when read back:\n%s\n---\n%s", text,
            again);
    abort();
  }
  mpm_io_input_free(in);
  free(back);
  free(again);
  free(text);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  /* the text and the --set arguments, each NUL-terminated */
  char *buf = malloc(size + 1);
  if (!buf)
    return 0;
  memcpy(buf, data, size);
  buf[size] = '\0';
  const char *sets[MAX_SETS];
  int nset = 0;
  for (char *p = buf + strlen(buf); p < buf + size && nset < MAX_SETS; p += strlen(p))
    sets[nset++] = ++p;

  mpm_app_plan *p = malloc(sizeof *p);   /* mpm_config is large: not on the stack */
  if (!p) {
    free(buf);
    return 0;
  }
  int st = mpm_app_plan_load(p, "fuzz.conf", buf, sets, nset, outdir);
  const int loaded = p->in != NULL;
  if (st == 0 && p->size.points <= MAX_POINTS && p->size.nodes <= MAX_NODES)
    st = mpm_app_plan_build(p);
  if (st == 0) {
    FILE *null = fopen("/dev/null", "w");
    if (null) {
      mpm_app_plan_print(p, null);
      fclose(null);
    }
    mpm_app_plan_warn(p);
  }
  if (loaded)
    round_trip(&p->cfg);
  mpm_app_plan_free(p);
  free(p);
  free(buf);
  return 0;
}
