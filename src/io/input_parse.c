/* input_parse.c: an input file to values in mpm_config. The text is read
 * whole (at most INPUT_MAX_BYTES), its comments are blanked and the lines
 * where sections open are noted, then libconfuse parses it with one CFGT_PTR
 * option per key of the key table, whose callback keeps each value's raw text
 * and line; the values are then collected section by section, item by item
 * of the titled sections, and stored through input_value.c. libconfuse's own
 * complaints are rewritten in the shape of the other input messages
 * (input_internal.h). */
#include <ctype.h>
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/input_internal.h"

#define INPUT_MAX_BYTES (16L << 20)  /* larger input files are refused */
#define CTX_KEY "granmpm-input-context"
#define LINE_MAX_CHARS 65536  /* longer lines are refused (check_line_lengths) */

/* ------------------------------------------------------- libconfuse glue */

/* A value as read: its text and the line it was on. */
typedef struct raw_value {
  int line;
  char text[];
} raw_value;

static int keep_raw(cfg_t *cfg, cfg_opt_t *opt, const char *value, void *result)
{
  if (cfg->name && strcmp(cfg->name, "root") == 0) {
    /* libconfuse reads "mesh|nx = 1" at the top level as mesh.nx: refuse */
    cfg_error(cfg, "no such option '%s'", opt->name);
    return -1;
  }
  size_t n = strlen(value);
  raw_value *r = malloc(sizeof *r + n + 1);
  if (!r) {
    cfg_error(cfg, "out of memory");
    return -1;
  }
  r->line = cfg->line;
  memcpy(r->text, value, n + 1);
  *(void **)result = r;
  return 0;
}

static int reject_value(cfg_t *cfg, cfg_opt_t *opt, const char *value, void *result)
{
  (void)value;
  (void)result;
  cfg_error(cfg, "no such option '%s'", opt->name);
  return -1;
}

static in_ctx *ctx_of(cfg_t *cfg)
{
  if (!cfg || !cfg->opts)
    return NULL;
  for (cfg_opt_t *o = cfg->opts; o->name; o++)
    if (strcmp(o->name, CTX_KEY) == 0 && o->simple_value.ptr)
      return *o->simple_value.ptr;
  return NULL;
}

static void unknown_option(in_ctx *c, const where *w, int sec, const char *title,
                           const char *name)
{
  if (sec >= 0) {
    mpm_io_in_fail_at(c, w, "%s", mpm_io_in_unknown_key_text(sec, title, name).s);
    return;
  }
  for (int k = 0; k < NKEYS; k++)
    if (strcmp(mpm_io_in_keys[k].name, name) == 0) {
      mpm_io_in_fail_at(c, w, "key '%s' outside a section (allowed: inside '%s { ... }')",
                        mpm_io_in_show(name).s, mpm_io_in_sec_names[mpm_io_in_keys[k].sec]);
      return;
    }
  mpm_io_in_fail_at(c, w, "unknown section '%s' (allowed: %s)", mpm_io_in_show(name).s,
                    mpm_io_in_section_list().s);
}

/* The titled section whose item titled `title` was opened again at `line`
 * (libconfuse names the title only): the last one opened at or before that
 * line that already has an item of that title. */
static int duplicate_section(const in_ctx *c, cfg_t *cfg, const char *title, int line)
{
  int best = 0, best_line = 0;
  for (int t = 0; t < NTITLED; t++) {
    if (!cfg_gettsec(cfg, mpm_io_in_sec_names[mpm_io_in_titled[t].sec], title))
      continue;
    for (int j = 0; j <= MAX_ITEMS && c->item_open[t][j]; j++)
      if (c->item_open[t][j] <= line && c->item_open[t][j] >= best_line) {
        best = t;
        best_line = c->item_open[t][j];
      }
  }
  return mpm_io_in_titled[best].sec;
}

/* libconfuse's messages, rewritten; the formats are those of libconfuse 3.3. */
static void on_confuse_error(cfg_t *cfg, const char *fmt, va_list ap)
{
  in_ctx *c = ctx_of(cfg);
  if (!c || c->failed)
    return;
  int sec = cfg->name ? mpm_io_in_find_section(cfg->name) : -1;
  where w = {.at = {cfg->line > 0 ? cfg->line : 1, 0}, .sec = sec, .key = -1, .item = -1};
  char msg[MPM_ERR_MSG];
  if (strcmp(fmt, "no such option '%s'") == 0) {
    unknown_option(c, &w, sec, cfg->title, va_arg(ap, const char *));
  } else if (strcmp(fmt, "missing title for section '%s'") == 0) {
    const word name = mpm_io_in_show(va_arg(ap, const char *));
    mpm_io_in_fail_at(c, &w, "section '%s' needs a title (allowed: %s NAME { ... })", name.s,
                      name.s);
  } else if (strcmp(fmt, "found duplicate title '%s'") == 0) {
    const char *title = va_arg(ap, const char *);
    const char *name = mpm_io_in_sec_names[duplicate_section(c, cfg, title, w.at.line)];
    mpm_io_in_fail_at(c, &w, "a second %s titled '%s' (allowed: a different title for each %s)",
                      name, mpm_io_in_show(title).s, name);
  } else if (strcmp(fmt, "missing equal sign after option '%s'") == 0) {
    const char *k = va_arg(ap, const char *);
    w.key = sec >= 0 ? mpm_io_in_find_key(sec, k) : -1;
    w.title = cfg->title;
    mpm_io_in_fail_key(c, &w, "missing '=' (allowed: %s = value)", mpm_io_in_show(k).s);
  } else if (strcmp(fmt, "attempt to append to non-list option '%s'") == 0) {
    const char *k = va_arg(ap, const char *);
    w.key = sec >= 0 ? mpm_io_in_find_key(sec, k) : -1;
    w.title = cfg->title;
    mpm_io_in_fail_key(c, &w, "'+=' appends to lists only (allowed: %s = value)",
                       mpm_io_in_show(k).s);
  } else {
    vsnprintf(msg, sizeof msg, fmt, ap);
    if (sec >= 0)
      mpm_io_in_fail_at(c, &w, "syntax error in section '%s': %s", mpm_io_in_sec_names[sec], msg);
    else
      mpm_io_in_fail_at(c, &w, "syntax error: %s", msg);
  }
}

static cfg_opt_t ptr_option(const char *name, int flags, cfg_callback_t parse)
{
  cfg_opt_t o;
  memset(&o, 0, sizeof o);
  o.name = name;
  o.type = CFGT_PTR;
  o.flags = flags;
  o.parsecb = parse;
  o.freecb = free;
  return o;
}

/* The hidden option through which on_confuse_error finds the context. */
static cfg_opt_t ctx_option(in_ctx *c)
{
  cfg_opt_t o = ptr_option(CTX_KEY, CFGF_NONE, reject_value);
  o.freecb = NULL;
  o.simple_value.ptr = &c->self;
  return o;
}

static void build_options(in_ctx *c)
{
  cfg_opt_t *root = c->opts[NSEC];
  for (int s = 0; s < NSEC; s++) {
    cfg_opt_t *o = c->opts[s];
    int n = 0;
    for (int k = 0; k < NKEYS; k++)
      if (mpm_io_in_keys[k].sec == s)
        o[n++] = ptr_option(mpm_io_in_keys[k].name,
                            mpm_io_in_keys[k].type == KT_LIST ? CFGF_LIST : CFGF_NONE, keep_raw);
    o[n++] = ctx_option(c);
    memset(&o[n], 0, sizeof o[n]);
    memset(&root[s], 0, sizeof root[s]);
    root[s].name = mpm_io_in_sec_names[s];
    root[s].type = CFGT_SEC;
    root[s].subopts = o;
    root[s].flags = mpm_io_in_titled_of(s) >= 0 ? CFGF_MULTI | CFGF_TITLE | CFGF_NO_TITLE_DUPES
                                                : CFGF_NONE;
  }
  root[NSEC] = ctx_option(c);
  memset(&root[NSEC + 1], 0, sizeof root[NSEC + 1]);
}

/* ------------------------------------------------------------ reading text */

static int io_fail(mpm_err *err, int code, const char *path, const char *what, int e)
{
  mpm_err_set(err, code, "%s: %s: %s", path, what, strerror(e));
  mpm_io_in_one_line(err);
  return code;
}

int mpm_io_in_read_text(const char *path, char **out, size_t *len, mpm_err *err)
{
  FILE *f = fopen(path, "rb");
  if (!f)
    return io_fail(err, MPM_EIO, path, "cannot open input file", errno);
  size_t cap = 4096, n = 0, got;
  char *buf = malloc(cap);
  while (buf && (got = fread(buf + n, 1, cap - n - 1, f)) > 0) {
    n += got;
    if (n + 1 == cap && (long)cap <= INPUT_MAX_BYTES) {
      char *bigger = realloc(buf, cap * 2);
      if (!bigger)
        free(buf);
      buf = bigger;
      cap *= 2;
    } else if (n + 1 == cap) {
      break;
    }
  }
  int e = errno, bad = ferror(f);
  fclose(f);
  if (!buf)
    return mpm_err_set(err, MPM_ENOMEM, "%s: out of memory reading the input file", path);
  if (bad) {
    free(buf);
    return io_fail(err, MPM_EIO, path, "cannot read input file", e);
  }
  if ((long)n > INPUT_MAX_BYTES) {
    free(buf);
    mpm_err_set(err, MPM_EINPUT, "%s: input file larger than %ld bytes (allowed: at most %ld)",
                path, INPUT_MAX_BYTES, INPUT_MAX_BYTES);
    mpm_io_in_one_line(err);
    return MPM_EINPUT;
  }
  buf[n] = '\0';
  *out = buf;
  *len = n;
  return MPM_OK;
}

static int line_at(const char *s, size_t pos)
{
  int line = 1;
  for (size_t i = 0; i < pos; i++)
    line += s[i] == '\n';
  return line;
}

enum scan_state { SC_CODE, SC_DQ, SC_SQ, SC_LINE, SC_BLOCK };

typedef struct scan {
  int state, line, from, depth;
  int bad_ref;                /* line of the first "${" that starts no reference, 0: none */
  int nul_escape;             /* line of the first escape of a NUL byte, 0: none */
  int open_line[SCAN_DEPTH];  /* line of each open '{' */
} scan;

/* A top-level '{': where sections open. */
static void note_section_brace(in_ctx *c, const char *s, const char *p, int line)
{
  if (c->nbrace < MAX_BRACES) {
    c->brace_pos[c->nbrace] = (size_t)(p - s);
    c->brace_line[c->nbrace++] = line;
  }
}

/* The '}' that ends the ${NAME} or ${NAME:-fallback} starting at p (NAME:
 * a letter or '_', then letters, digits, '_'; the fallback on one line
 * without '}'), NULL if p starts no such reference. libconfuse takes
 * anything up to a '}' and searches the rest of the text for one at every
 * "${" it cannot close, which made many unclosed ones quadratic: they are
 * refused here, in one pass. */
static const char *env_ref_end(const char *p)
{
  const char *q = p + 2;
  if (!(isalpha((unsigned char)*q) || *q == '_'))
    return NULL;
  while (isalnum((unsigned char)*q) || *q == '_')
    q++;
  if (q[0] == ':' && q[1] == '-')
    for (q += 2; *q && *q != '}' && *q != '\n'; q++)
      ;
  return *q == '}' ? q : NULL;
}

/* 1 if the escape at p (a backslash in double quotes) makes a NUL byte:
 * an octal or hexadecimal escape of zero (\0, \000, \x00), which
 * libconfuse 3.3 decodes into the value, so that the value silently ends
 * there ("a\0b" was read as "a"). Its escapes take up to 3 octal or 2 hex
 * digits. */
static int nul_escape(const char *p)
{
  int n = 0, v = 0;
  if (p[1] == 'x')
    for (p += 2; n < 2 && isxdigit((unsigned char)p[n]); n++)
      v = 16 * v + (isdigit((unsigned char)p[n]) ? p[n] - '0'
                                                  : tolower((unsigned char)p[n]) - 'a' + 10);
  else
    for (p += 1; n < 3 && p[n] >= '0' && p[n] <= '7'; n++)
      v = 8 * v + p[n] - '0';
  return n > 0 && v == 0;
}

/* A "${" that starts no reference, at line `line`. */
static int bad_env_ref(in_ctx *c, int line)
{
  where w = {.at = {line, 0}, .sec = -1, .key = -1, .item = -1};
  return mpm_io_in_fail_at(c, &w, "'${' starts no variable reference "
                           "(allowed: ${NAME} or ${NAME:-fallback}, NAME of letters, digits, '_')");
}

/* One character of code outside strings and comments; p may advance. A
 * comment opener is blanked here, the rest of the comment by the caller. */
static void scan_code(in_ctx *c, scan *sc, const char *s, char **pp)
{
  char *p = *pp;
  if (*p == '"' || *p == '\'') {
    sc->state = *p == '"' ? SC_DQ : SC_SQ;
    sc->from = sc->line;
  } else if (*p == '#' || (*p == '/' && p[1] == '/')) {
    sc->state = SC_LINE;
    *p = ' ';
  } else if (*p == '/' && p[1] == '*') {
    sc->state = SC_BLOCK;
    sc->from = sc->line;
    *p++ = ' ';
    *p = ' ';
  } else if (*p == '$' && p[1] == '{') {
    const char *q = env_ref_end(p);  /* ${NAME}: one token, on one line */
    if (!q)
      sc->bad_ref = sc->bad_ref ? sc->bad_ref : sc->line;
    else
      p += q - p;
  } else if (*p == '{') {
    if (sc->depth == 0)
      note_section_brace(c, s, p, sc->line);
    sc->open_line[sc->depth < SCAN_DEPTH ? sc->depth : SCAN_DEPTH - 1] = sc->line;
    sc->depth++;
  } else if (*p == '}' && sc->depth > 0) {
    sc->depth--;
  }
  *pp = p;
}

/* Comments are blanked (newlines kept) before libconfuse sees the text: its
 * 3.3 lexer counts the newline of a comment twice, so every later line number
 * would be off, and it rejects a comment inside a list. Outside quotes, '#',
 * '//' and slash-star start a comment anywhere. The same scan catches what
 * libconfuse 3.3 accepts silently: a section left open, a comment left open
 * that hides the rest of the file (and open quotes, with their line), and an
 * escape that would cut a value at a NUL byte. */
static int blank_comments(in_ctx *c, char *s)
{
  scan sc = {.state = SC_CODE, .line = 1};
  for (char *p = s; *p; p++) {
    if (sc.state == SC_CODE) {
      scan_code(c, &sc, s, &p);
    } else if (sc.state == SC_DQ || sc.state == SC_SQ) {
      if (*p == '\\' && p[1]) {
        if (sc.state == SC_DQ && !sc.nul_escape && nul_escape(p))
          sc.nul_escape = sc.line;
        p++;  /* an escaped character */
      }
      else if (sc.state == SC_DQ && *p == '$' && p[1] == '{' && !env_ref_end(p) && !sc.bad_ref)
        sc.bad_ref = sc.line;
      else if (*p == (sc.state == SC_DQ ? '"' : '\''))
        sc.state = SC_CODE;
    } else if (*p == '\n') {
      sc.state = sc.state == SC_LINE ? SC_CODE : sc.state;
    } else if (sc.state == SC_BLOCK && *p == '*' && p[1] == '/') {
      sc.state = SC_CODE;
      *p++ = ' ';
      *p = ' ';
    } else {
      *p = ' ';
    }
    sc.line += *p == '\n';  /* a skipped first character is never a newline */
  }
  where w = {.at = {sc.from, 0}, .sec = -1, .key = -1, .item = -1};
  if (sc.bad_ref && (!sc.nul_escape || sc.bad_ref <= sc.nul_escape))
    return bad_env_ref(c, sc.bad_ref);
  if (sc.nul_escape) {
    w.at.line = sc.nul_escape;
    return mpm_io_in_fail_at(c, &w, "an escape of a NUL byte in quoted text, which would end "
                             "the value there (allowed: text without NUL bytes; \\0 and "
                             "\\x00 are such escapes)");
  }
  if (sc.state == SC_BLOCK)
    return mpm_io_in_fail_at(c, &w, "comment '/*' is not closed (allowed: /* ... */)");
  if (sc.state == SC_DQ || sc.state == SC_SQ)
    return mpm_io_in_fail_at(c, &w, "quoted text is not closed (allowed: \"...\" or '...')");
  if (sc.depth > 0) {
    w.at.line = sc.open_line[sc.depth <= SCAN_DEPTH ? sc.depth - 1 : SCAN_DEPTH - 1];
    return mpm_io_in_fail_at(c, &w, "'{' is not closed (allowed: a matching '}')");
  }
  return MPM_OK;
}

static int is_word_char(char ch)
{
  return ch && !isspace((unsigned char)ch) && !strchr("#\"'={}()+,*", ch);
}

/* The word that ends before p (blanks skipped), as [start, *end); a quoted
 * word includes its quotes. */
static const char *word_before(const char *s, const char *p, const char **end)
{
  while (p > s && isspace((unsigned char)p[-1]))
    p--;
  *end = p;
  if (p > s && (p[-1] == '"' || p[-1] == '\'')) {
    char q = *--p;
    while (p > s && p[-1] != q)
      p--;
    return p > s ? p - 1 : p;
  }
  while (p > s && is_word_char(p[-1]))
    p--;
  return p;
}

static int word_is(const char *w, const char *end, const char *name)
{
  return (size_t)(end - w) == strlen(name) && strncmp(w, name, strlen(name)) == 0;
}

/* The opening lines of the sections ("NAME {" or "fill TITLE {"), in the order
 * libconfuse keeps them: the first of a repeated plain section, every item of
 * a titled one. */
static void find_section_lines(in_ctx *c, const char *s)
{
  int nitem[NTITLED] = {0};
  for (int b = 0; b < c->nbrace; b++) {
    const char *e1, *e2, *w1 = word_before(s, s + c->brace_pos[b], &e1);
    const char *w2 = word_before(s, w1, &e2);
    int titled = 0;
    for (int t = 0; t < NTITLED; t++)
      if (word_is(w2, e2, mpm_io_in_sec_names[mpm_io_in_titled[t].sec])) {
        if (nitem[t] < MAX_ITEMS + 1)
          c->item_open[t][nitem[t]++] = c->brace_line[b];
        titled = 1;
      }
    if (titled)
      continue;
    for (int k = 0; k < NSEC; k++)
      if (mpm_io_in_titled_of(k) < 0 && word_is(w1, e1, mpm_io_in_sec_names[k]) &&
          !c->sec_open[k])
        c->sec_open[k] = c->brace_line[b];
  }
}

/* libconfuse's scanner reads its text in blocks and starts a token again
 * from its first character after each block, so one token of n characters
 * costs n^2 / 8 KiB: a line of 4 MB took 10 s. No line of an input needs
 * more than a few hundred characters; longer than LINE_MAX_CHARS is refused. */
static int check_line_lengths(in_ctx *c, const char *s)
{
  int line = 1;
  for (const char *p = s; *p; line++) {
    const char *nl = strchr(p, '\n');
    size_t n = nl ? (size_t)(nl - p) : strlen(p);
    if (n > LINE_MAX_CHARS) {
      where w = {.at = {line, 0}, .sec = -1, .key = -1, .item = -1};
      return mpm_io_in_fail_at(c, &w, "a line of %zu characters (allowed: at most %d per line)",
                               n, LINE_MAX_CHARS);
    }
    p += n + (nl != NULL);
  }
  return MPM_OK;
}

/* The UTF-8 byte-order mark, U+FEFF, which some editors put at the start of
 * a text file: invisible, so a message that quotes it shows nothing. */
static const char BOM[] = "\xEF\xBB\xBF";
enum { BOM_LEN = sizeof BOM - 1 };

/* A byte-order mark at the very start of the text is blanked (read as three
 * spaces: lines and offsets stay); one anywhere else outside a comment (a
 * file pasted into another) is an error naming it and its line, rather
 * than an unknown name of invisible bytes. Run after blank_comments. */
static int byte_order_mark(in_ctx *c, const char *s)
{
  const char *p = strstr(s, BOM);
  if (!p)
    return MPM_OK;
  where w = {.at = {line_at(s, (size_t)(p - s)), 0}, .sec = -1, .key = -1, .item = -1};
  return mpm_io_in_fail_at(c, &w, "a UTF-8 byte-order mark (bytes EF BB BF, invisible) inside "
                           "the text (allowed: only as the first bytes of the file)");
}

int mpm_io_in_parse_text(in_ctx *c, char *s, size_t len, cfg_t **root)
{
  const char *nul = memchr(s, '\0', len);
  if (nul) {
    where w = {.at = {line_at(s, (size_t)(nul - s)), 0}, .sec = -1, .key = -1, .item = -1};
    return mpm_io_in_fail_at(c, &w, "NUL byte in the input file (allowed: text)");
  }
  if (len >= BOM_LEN && memcmp(s, BOM, BOM_LEN) == 0)
    memset(s, ' ', BOM_LEN);                   /* a leading mark: read as nothing */
  int lines = line_at(s, len) - (len > 0 && s[len - 1] == '\n');
  c->eof_line = lines > 0 ? lines : 1;
  if (check_line_lengths(c, s) != MPM_OK)
    return MPM_EINPUT;
  if (blank_comments(c, s) != MPM_OK || byte_order_mark(c, s) != MPM_OK)
    return MPM_EINPUT;
  find_section_lines(c, s);
  build_options(c);
  *root = cfg_init(c->opts[NSEC], CFGF_NONE);
  if (!*root)
    return mpm_err_set(c->err, MPM_ENOMEM, "%s: out of memory", c->path);
  cfg_set_error_function(*root, on_confuse_error);
  if (cfg_parse_buf(*root, s) != CFG_SUCCESS) {
    where w = {.at = {c->eof_line, 0}, .sec = -1, .key = -1, .item = -1};
    return mpm_io_in_fail_at(c, &w, "syntax error");  /* kept only if nothing was said */
  }
  return MPM_OK;
}

/* ------------------------------------------------------ values from files */

static int collect_list(in_ctx *c, void *rec, const where *w, cfg_opt_t *o)
{
  const char *vals[MPM_MAX_POLY + 1];
  loc locs[MPM_MAX_POLY + 1];
  int n = (int)cfg_opt_size(o);
  for (int i = 0; i < n && i <= MPM_MAX_POLY; i++) {
    const raw_value *r = cfg_opt_getnptr(o, (unsigned)i);
    vals[i] = r->text;
    locs[i] = (loc){r->line, 0};
  }
  return mpm_io_in_store_list(c, rec, w, vals, locs, n);
}

static int collect_section(in_ctx *c, cfg_t *sec, int s, int item, void *rec, const char *title)
{
  for (int k = 0; k < NKEYS; k++) {
    if (mpm_io_in_keys[k].sec != s)
      continue;
    cfg_opt_t *o = cfg_getopt(sec, mpm_io_in_keys[k].name);
    if (cfg_opt_size(o) == 0)
      continue;
    where w = {.sec = s, .key = k, .item = item, .title = title};
    int rc;
    if (mpm_io_in_keys[k].type == KT_LIST) {
      rc = collect_list(c, rec, &w, o);
    } else {
      const raw_value *r = cfg_opt_getnptr(o, 0);
      w.at.line = r->line;
      rc = mpm_io_in_store_value(c, rec, &w, r->text);
    }
    if (rc != MPM_OK)
      return rc;
  }
  return MPM_OK;
}

int mpm_io_in_valid_title(const char *t)
{
  size_t n = strlen(t);
  if (n == 0 || n >= MPM_NAME_MAX)
    return 0;
  for (; *t; t++)
    if (!isalnum((unsigned char)*t) && *t != '_' && *t != '-')
      return 0;
  return 1;
}

/* A record of titled section t with the defaults of its keys. */
static void item_defaults(void *rec, int t)
{
  memset(rec, 0, mpm_io_in_titled[t].size);
  for (int k = 0; k < NKEYS; k++)
    if (mpm_io_in_keys[k].sec == mpm_io_in_titled[t].sec)
      mpm_io_in_store_default(rec, &mpm_io_in_keys[k]);
}

/* The items of titled section t, each with its title checked. */
static int collect_items(in_ctx *c, cfg_t *root, mpm_config *cfg, int t)
{
  const titled_def *td = &mpm_io_in_titled[t];
  const char *name = mpm_io_in_sec_names[td->sec];
  unsigned n = cfg_size(root, name);
  for (unsigned i = 0; i < n; i++) {
    cfg_t *sec = cfg_getnsec(root, name, i);
    const char *title = cfg_title(sec) ? cfg_title(sec) : "";
    int line = i <= MAX_ITEMS && c->item_open[t][i] ? c->item_open[t][i] : sec->line;
    where w = {.at = {line, 0}, .sec = td->sec, .key = -1, .item = -1};
    if (i == (unsigned)td->max)
      return mpm_io_in_fail_at(c, &w,
                               "%s '%s' is %s number %u (allowed: at most %d %s sections)", name,
                               mpm_io_in_show(title).s, name, i + 1, td->max, name);
    if (!mpm_io_in_valid_title(title))
      return mpm_io_in_fail_at(c, &w,
                               "%s title '%s' (allowed: 1 ... %d letters, digits, '_' or '-')",
                               name, mpm_io_in_show(title).s, MPM_NAME_MAX - 1);
    c->item_line[t][i] = line;
    void *rec = mpm_io_in_item(cfg, t, (int)i);
    item_defaults(rec, t);
    char *stored = (char *)rec + td->name_off;
    mpm_io_in_copy_text(stored, MPM_NAME_MAX, title);
    *mpm_io_in_count(cfg, t) = (int)i + 1;
    if (collect_section(c, sec, td->sec, (int)i, rec, stored) != MPM_OK)
      return MPM_EINPUT;
  }
  return MPM_OK;
}

int mpm_io_in_collect(in_ctx *c, cfg_t *root, mpm_config *cfg)
{
  for (int s = 0; s < NSEC; s++) {
    if (mpm_io_in_titled_of(s) >= 0)
      continue;
    cfg_t *sec = cfg_getsec(root, mpm_io_in_sec_names[s]);
    c->sec_line[s] = c->sec_open[s] ? c->sec_open[s] : sec ? sec->line : 0;
    if (sec && collect_section(c, sec, s, -1, cfg, NULL) != MPM_OK)
      return MPM_EINPUT;
  }
  for (int t = 0; t < NTITLED; t++)
    if (collect_items(c, root, cfg, t) != MPM_OK)
      return MPM_EINPUT;
  return MPM_OK;
}
