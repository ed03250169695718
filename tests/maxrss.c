/* maxrss.c: `maxrss COMMAND [ARGS...]` runs COMMAND and prints its peak
 * resident memory in kB (getrusage of the child, ru_maxrss) on standard
 * output; the exit status is the command's (127 when it cannot start).
 * For tests/cli-size.sh, which compares it with `granmpm check`'s estimate. */
#define _DEFAULT_SOURCE

#include <stdio.h>
#include <sys/resource.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

int main(int argc, char **argv)
{
  if (argc < 2) {
    fprintf(stderr, "usage: maxrss COMMAND [ARGS...]\n");
    return 2;
  }
  const pid_t pid = fork();
  if (pid < 0) {
    perror("maxrss: fork");
    return 127;
  }
  if (pid == 0) {
    execvp(argv[1], argv + 1);
    perror("maxrss: exec");
    _exit(127);
  }
  int status = 0;
  struct rusage ru;
  if (wait4(pid, &status, 0, &ru) != pid) {
    perror("maxrss: wait4");
    return 127;
  }
  printf("%ld\n", ru.ru_maxrss);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}
