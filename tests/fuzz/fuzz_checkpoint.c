/* fuzz_checkpoint.c: a libFuzzer target for `granmpm resume` (and `info`)
 * of a damaged checkpoint (scripts/fuzz builds and runs it).
 *
 * One input is a mode byte and the bytes of a file:
 *     MODE FILE...
 * FILE is written as DIR/checkpoint.h5 (DIR a temporary directory of this
 * process) and read as resume reads it (mpm_io_checkpoint_read: the
 * checksum of the user block before HDF5 parses anything, then HDF5, then
 * the values); with MODE bit 1 set, first also as `info` reads its time and
 * step (mpm_io_checkpoint_when; a bit, as every HDF5 open of a file costs
 * milliseconds under the sanitizers). A checkpoint that reads is
 * resumed up to its first step: the simulation is built from its own
 * resolved input (app/plan.c, as resume does, with the output in DIR) and
 * its state put back (mpm_sim_state_set, which checks the restored state).
 * The build is what resume pays before any step, milliseconds for the small
 * runs of the seed corpus; a checkpoint whose input asks for a larger run
 * (more than MAX_POINTS points or MAX_NODES nodes by the estimate: what
 * the build's work and memory grow with) stops at the estimate, so that one
 * input stays fast. No step is run.
 *
 * MODE bit 0 clear: the file is read as it is, so nearly every change is
 * refused by the checksum before HDF5 sees the file, as granmpm refuses it
 * (only a file that starts with HDF5's own signature, a checkpoint of
 * format 1 without the block, goes to HDF5 unchecked).
 * MODE bit 0 set: before writing, the target writes a user block whose
 * checksum matches the fuzzed bytes after it (mpm_io_checkpoint_seal, as
 * a checkpoint is written), so that HDF5's parsing of the file and
 * granmpm's checks of its values and of the restored state are fuzzed too.
 * This mode fuzzes HDF5 itself on files that granmpm would refuse by their
 * checksum: a crash inside HDF5 found only in this mode is not reachable
 * through granmpm from a damaged checkpoint, only from one crafted to pass
 * the checksum.
 *
 * After each input every HDF5 object granmpm opened must be closed again
 * (H5Fget_obj_count over all files is 0; the target aborts otherwise), and
 * everything allocated freed (libFuzzer's leak check; HDF5 1.10.8's own
 * block lost on a failed metadata checksum is suppressed by
 * tests/lsan.supp, which scripts/fuzz passes). */
#define _POSIX_C_SOURCE 200809L
#include <hdf5.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app/plan.h"
#include "io/io.h"

#define MAX_POINTS 20000
#define MAX_NODES 100000

int LLVMFuzzerInitialize(int *argc, char ***argv);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* DIR and DIR/checkpoint.h5, made once (removed at exit). */
static char dir[256], path[300];

static void remove_dir(void)
{
  unlink(path);
  rmdir(dir);
}

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
  (void)argc;
  (void)argv;
  const char *tmp = getenv("TMPDIR");
  snprintf(dir, sizeof dir, "%s/fuzz-checkpoint.XXXXXX", tmp && *tmp ? tmp : "/tmp");
  if (!mkdtemp(dir)) {
    perror("fuzz_checkpoint: mkdtemp");
    exit(1);
  }
  snprintf(path, sizeof path, "%s/checkpoint.h5", dir);
  atexit(remove_dir);
  return 0;
}

/* The file's bytes at path; 0 on success. */
static int put_file(const uint8_t *bytes, size_t n)
{
  FILE *f = fopen(path, "wb");
  if (!f)
    return -1;
  const int short_write = n > 0 && fwrite(bytes, 1, n, f) != n;
  const int bad = fclose(f) != 0 || short_write;
  return bad ? -1 : 0;
}

/* Resume's steps after the read, up to the first step (app/run.c). */
static void resume(mpm_io_checkpoint *ck)
{
  mpm_app_plan *p = malloc(sizeof *p);     /* mpm_config is large: not on the stack */
  if (!p)
    return;
  int st = mpm_app_plan_load(p, path, ck->input, NULL, 0, dir);
  if (st == 0 && p->size.points <= MAX_POINTS && p->size.nodes <= MAX_NODES) {
    st = mpm_app_plan_build(p);
    mpm_err err = {0};
    if (st == 0)
      mpm_sim_state_set(p->sim, &ck->state, &err);
  }
  mpm_app_plan_free(p);
  free(p);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  if (size < 1)
    return 0;
  const int seal = data[0] & 1;
  const uint8_t *bytes = data + 1;
  const size_t n = size - 1;
  uint8_t *copy = NULL;
  if (seal && (copy = malloc(n ? n : 1))) {
    memcpy(copy, bytes, n);
    if (mpm_io_checkpoint_seal(copy, n) == 0)
      bytes = copy;
  }
  const int written = put_file(bytes, n);
  free(copy);
  if (written != 0) {
    perror("fuzz_checkpoint: writing the checkpoint");
    abort();
  }

  mpm_err err = {0};
  double t;
  long step;
  if (data[0] & 2)
    mpm_io_checkpoint_when(dir, &t, &step, &err);
  mpm_io_checkpoint ck;
  if (mpm_io_checkpoint_read(dir, &ck, &err) == MPM_OK)
    resume(&ck);
  mpm_io_checkpoint_clear(&ck);

  const ssize_t open = H5Fget_obj_count(H5F_OBJ_ALL, H5F_OBJ_ALL);
  if (open > 0) {
    fprintf(stderr, "fuzz_checkpoint: %zd HDF5 objects left open after reading\n", open);
    abort();
  }
  return 0;
}
