/* text.c: small text helpers shared by the readers in io/ (text.h).
 *
 * Trim: skip leading isspace() characters, cut trailing ones; the string is
 * changed in place, nothing is allocated. */
#include "io/text.h"

#include <ctype.h>
#include <string.h>

char *mpm_io_text_trim(char *s)
{
  while (isspace((unsigned char)*s))
    s++;
  char *e = s + strlen(s);
  while (e > s && isspace((unsigned char)e[-1]))
    *--e = '\0';
  return s;
}
