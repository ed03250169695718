/* main.c: the `granmpm` command line: run, resume, check, info, extract,
 * state, constitutive; and the signals that stop a run.
 *
 * app/ is the only place that prints to the user or exits. Exit status (args.h):
 * 0 success, 1 a run failed (physical or I/O failure while running), 2 bad
 * usage or input (one error line naming file, line, key and what is
 * allowed), 3 a run stopped by a signal with a checkpoint to resume from. */
#define _POSIX_C_SOURCE 200809L
#include "config.h"
#include "revision.h"

#include <signal.h>
#include <stdio.h>
#include <string.h>

#include "app/analyse.h"
#include "app/args.h"
#include "app/constitutive.h"
#include "app/info.h"
#include "app/run.h"
#include "app/state.h"
#include "io/io.h"

static const char usage_text[] =
  "usage: granmpm COMMAND [ARGS]\n"
  "\n"
  "commands:\n"
  "  run FILE [--set section.key=value]... [--output DIR] [--quiet] [--force]\n"
  "        run the case described by FILE; writes DIR/run.h5, run.xdmf, diagnostics.csv\n"
  "        (and DIR/checkpoint.h5 on schedule or when stopped by a signal); --force\n"
  "        replaces a run already in DIR\n"
  "  resume DIR [--t-end T] [--quiet]\n"
  "        continue the run in DIR from its checkpoint (to time T if given)\n"
  "  check FILE [--set section.key=value]... [--output DIR]\n"
  "        validate FILE as run would (fills, size and output directory included)\n"
  "        and print the fully resolved input and the size of the run\n"
  "  info RUNDIR [--status]\n"
  "        where a run came from (version, revision, command, host, threads,\n"
  "        times, resumptions, input) and how it stands\n"
  "  extract RUNDIR [--frame N|last] [--fields a,b,c] [--z-range ZMIN:ZMAX]\n"
  "        print one output frame as CSV with a header row (a 3D run: z too;\n"
  "        --z-range keeps the points with ZMIN <= z <= ZMAX)\n"
  "  extract RUNDIR --bodies [--frame N|last]\n"
  "        the rigid bodies of every frame (or one) as CSV: frame, t, body, centre,\n"
  "        turn, velocity, angular velocity, force, torque, points put back\n"
  "  extract RUNDIR --profile N [--frame N|last] [--range YMIN:YMAX]\n"
  "  extract RUNDIR --surface [--frame N|last] [--width W]\n"
  "  extract RUNDIR --smooth [--frame N|last]\n"
  "  extract RUNDIR --series [--gdot-min G] [--front-cell H] [--front-min K]\n"
  "                 [--slope XA:XB|auto] [--width W]\n"
  "        measurements: velocity profile, free surface, smoothed pressure,\n"
  "        per-frame speed, acceleration, mu, front, slope (docs/diagnostics.md);\n"
  "        of a 3D run (not --smooth), on x and y, of the points with ZMIN <= z <=\n"
  "        ZMAX when --z-range ZMIN:ZMAX is given (any measurement)\n"
  "  extract RUNDIR --jam\n"
  "        silo classifier of [DK-silo] 7.2: static, flowing or unsure, with evidence\n"
  "  extract RUNDIR --jam-series\n"
  "        that evidence frame by frame: mean velocity of the dense material, points\n"
  "        (docs/diagnostics.md)\n"
  "  extract RUNDIR --roughness [--frame N|last] [--radius R]\n"
  "        pressure roughness and dense fraction of a frame (docs/diagnostics.md)\n"
  "  state INPUT RUNDIR [--frame N|last]\n"
  "        nodal density projected back to the points of one frame, and the\n"
  "        state it gives (dense / disconnected), as CSV\n"
  "  constitutive [ARGS]\n"
  "        drive one material point through a velocity-gradient history\n"
  "        (granmpm constitutive --help)\n"
  "  --version, --help\n"
  "\n"
  "exit status: 0 done, 1 a run failed, 2 bad usage or input (or a run refused\n"
  "before its first step), 3 a run stopped by SIGINT, SIGTERM, SIGHUP or SIGUSR1\n"
  "after writing its checkpoint (a second signal ends it at once)\n";

/* The signal that asks a run to stop, 0 while none has come. The one
 * mutable variable with static storage in granmpm: a signal handler can
 * only reach the program through one, and only a volatile sig_atomic_t may
 * be written there. It is read through the pointer given to the run. */
static volatile sig_atomic_t stop_signal;

/* First signal: note it (the run stops after its step, with a checkpoint).
 * Second: the default action, at once. */
static void on_signal(int sig)
{
  if (stop_signal) {                       /* only async-signal-safe calls here */
    struct sigaction dfl = {.sa_handler = SIG_DFL};
    sigaction(sig, &dfl, NULL);
    raise(sig);
    return;
  }
  stop_signal = sig;
}

/* Signals for a run: the four that ask a stop, and SIGXFSZ ignored so that
 * a file-size limit is a write error (EFBIG) with a message, not a kill. */
static void catch_signals(void)
{
  const int sigs[] = {SIGINT, SIGTERM, SIGHUP, SIGUSR1};
  struct sigaction sa;
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  for (size_t k = 0; k < sizeof sigs / sizeof sigs[0]; k++)
    sigaction(sigs[k], &sa, NULL);
  sa.sa_handler = SIG_IGN;
  sigaction(SIGXFSZ, &sa, NULL);
}

/* ---- extract --------------------------------------------------------------- */

static int cmd_extract(int argc, char **argv)
{
  if (mpm_app_is_analysis(argc, argv))
    return mpm_app_analyse(argc, argv);
  const char *dir = NULL, *fields = NULL;
  int frame = -1, bodies = 0, frame_given = 0;
  mpm_io_zrange zr;
  const mpm_io_zrange *sel = NULL;
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
    int st = 0;
    if (strcmp(a, "--frame") == 0 && v) {
      st = mpm_app_arg_frame("extract", v, &frame);
      frame_given = 1;
      i++;
    } else if (strcmp(a, "--fields") == 0 && v) {
      fields = v;
      i++;
    } else if (strcmp(a, "--bodies") == 0) {
      bodies = 1;
    } else if (strcmp(a, "--z-range") == 0 && v) {
      if (!mpm_app_arg_pair(v, &zr.zmin, &zr.zmax))
        return mpm_app_usage("extract: --z-range expects ZMIN:ZMAX with ZMIN < ZMAX, got '%s'",
                             v);
      sel = &zr;
      i++;
    } else {
      st = mpm_app_arg_positional("extract", a, &dir, 1);
    }
    if (st != 0)
      return st;
  }
  if (!dir)
    return mpm_app_usage("%s: a run directory is required", "extract");
  if (bodies && (fields || sel))
    return mpm_app_usage("extract: --bodies takes --frame only");
  mpm_err err = {0};
  if (bodies ? mpm_io_extract_bodies(dir, frame_given ? frame : MPM_IO_ALL_FRAMES, stdout, &err) != MPM_OK
             : mpm_io_extract_in(dir, frame, fields, sel, stdout, &err) != MPM_OK)
    return mpm_app_fail(&err);
  return 0;
}

int main(int argc, char **argv)
{
  if (argc < 2)
    return mpm_app_usage("%s", "a command is required");
  const char *cmd = argv[1];
  if (strcmp(cmd, "--help") == 0 || strcmp(cmd, "-h") == 0 || strcmp(cmd, "help") == 0) {
    fputs(usage_text, stdout);
    return 0;
  }
  if (strcmp(cmd, "--version") == 0) {
    printf("granmpm %s (revision %s)\n", PACKAGE_VERSION, GRANMPM_REVISION);
    return 0;
  }
  if (strcmp(cmd, "run") == 0 || strcmp(cmd, "resume") == 0) {
    catch_signals();
    return (cmd[1] == 'u' ? mpm_app_run : mpm_app_resume)(argc - 1, argv + 1, argc, argv,
                                                          &stop_signal);
  }
  if (strcmp(cmd, "check") == 0)
    return mpm_app_check(argc - 1, argv + 1);
  if (strcmp(cmd, "info") == 0)
    return mpm_app_info(argc - 1, argv + 1);
  if (strcmp(cmd, "extract") == 0)
    return cmd_extract(argc - 1, argv + 1);
  if (strcmp(cmd, "state") == 0)
    return mpm_app_state(argc - 1, argv + 1);
  if (strcmp(cmd, "constitutive") == 0)
    return mpm_app_constitutive(argc - 1, argv + 1);
  return mpm_app_usage("unknown command '%s'", cmd);
}
