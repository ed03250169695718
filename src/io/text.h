/* text.h: small text helpers shared by the readers in io/ (the history CSV
 * reader and the input parser's --set values). */
#ifndef MPM_IO_TEXT_H
#define MPM_IO_TEXT_H

/* Trim s in place: its trailing white space is overwritten with '\0' and the
 * first non-blank character is returned (the terminating '\0' if s is blank). */
char *mpm_io_text_trim(char *s);

#endif
