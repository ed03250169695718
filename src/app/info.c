/* info.c: `granmpm info DIR`: where a run came from and how it stands, from
 * the attributes of DIR/run.h5 and DIR/checkpoint.h5 (io.h,
 * mpm_io_run_provenance): program version and source revision, command
 * line, host, threads, start and end, status (and why a failed run
 * failed), resumptions, frames, the checkpoint, and the resolved input. With --status, the status alone (one
 * word, for scripts: finished, stopped, failed, running). */
#include "app/info.h"

#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "app/args.h"
#include "io/io.h"

/* 1 when DIR/checkpoint.h5 exists (readable or not). */
static int checkpoint_there(const char *dir)
{
  char path[MPM_PATH_MAX + 32];
  struct stat sb;
  snprintf(path, sizeof path, "%s/checkpoint.h5", dir);
  return stat(path, &sb) == 0;
}

static const char usage_line[] = "info: usage: granmpm info RUNDIR [--status]";

static void print_info(const char *dir, const mpm_io_provenance *p, FILE *f)
{
  double t = 0.0;
  long step = 0;
  mpm_err err = {0};
  const int has_ck = mpm_io_checkpoint_when(dir, &t, &step, &err) == MPM_OK;
  fprintf(f, "run:        %s/run.h5\n", dir);
  fprintf(f, "status:     %s", p->status[0] ? p->status : "unknown (not recorded)");
  if (has_ck && strcmp(p->status, "finished") != 0)
    fprintf(f, " (continue with: granmpm resume %s)", dir);
  else if (strcmp(p->status, "running") == 0)
    fprintf(f, " (or killed before its first checkpoint)");
  if (p->failure[0])
    fprintf(f, "\nfailure:    %s", p->failure);
  fprintf(f, "\nprogram:    granmpm %s (revision %s)\n", p->version,
          p->revision[0] ? p->revision : "unknown");
  fprintf(f, "command:    %s\n", p->command_line);
  fprintf(f, "host:       %s\n", p->host[0] ? p->host : "unknown");
  if (p->threads > 0)
    fprintf(f, "threads:    %d\n", p->threads);
  fprintf(f, "started:    %s\n", p->start_time[0] ? p->start_time : "unknown");
  fprintf(f, "ended:      %s\n", p->end_time[0] ? p->end_time : "-");
  if (p->resumed >= 0)
    fprintf(f, "resumed:    %d time%s\n", p->resumed, p->resumed == 1 ? "" : "s");
  for (const char *l = p->resume_log; *l;) {
    size_t n = strcspn(l, "\n");
    fprintf(f, "  %.*s\n", (int)n, l);
    l += n + (l[n] == '\n');
  }
  if (p->nframes > 0 && p->t_last < 0.0)       /* its time never written: a full disk */
    fprintf(f, "frames:     %d, the last incomplete (no time recorded)\n", p->nframes);
  else if (p->nframes > 0)
    fprintf(f, "frames:     %d, the last at t = %.6g s\n", p->nframes, p->t_last);
  else
    fprintf(f, "frames:     0\n");
  if (has_ck)
    fprintf(f, "checkpoint: t = %.6g s, step %ld (%s/checkpoint.h5)\n", t, step, dir);
  else if (checkpoint_there(dir))
    fprintf(f, "checkpoint: unusable: %s\n", err.msg);
  else
    fprintf(f, "checkpoint: none\n");
  fprintf(f, "input:\n");
  for (const char *l = p->input; *l;) {
    size_t n = strcspn(l, "\n");
    fprintf(f, "  %.*s\n", (int)n, l);
    l += n + (l[n] == '\n');
  }
}

int mpm_app_info(int argc, char **argv)
{
  const char *dir = NULL;
  int status_only = 0;
  for (int i = 1; i < argc; i++) {
    int st = 0;
    if (strcmp(argv[i], "--status") == 0)
      status_only = 1;
    else if (argv[i][0] == '-' && argv[i][1])
      st = mpm_app_usage("%s", usage_line);
    else
      st = mpm_app_arg_positional("info", argv[i], &dir, 1);
    if (st != 0)
      return st;
  }
  if (!dir)
    return mpm_app_usage("%s", usage_line);
  mpm_io_run *r = NULL;
  mpm_io_provenance p;
  mpm_err err = {0};
  int rc = mpm_io_run_open(&r, dir, &err);
  if (rc == MPM_OK)
    rc = mpm_io_run_provenance(r, &p, &err);
  mpm_io_run_close(r);
  if (rc != MPM_OK)
    return mpm_app_fail(&err);
  if (status_only)
    puts(p.status[0] ? p.status : "unknown");
  else
    print_info(dir, &p, stdout);
  mpm_io_run_provenance_clear(&p);
  return fflush(stdout) == 0 ? 0 : MPM_APP_EXIT_RUNTIME;
}
