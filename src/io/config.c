/* Problem configuration: INI files read with inih, `--set` overrides, strict
 * typed getters, detection of unused keys and atomic write-back.
 *
 * Storage is a flat array of entries (section, key, value, origin) in order
 * of first appearance; a later file or --set of the same section and key
 * replaces the value and the origin but keeps the position.  Within one
 * file a key or a section given twice is refused, as is a key given twice
 * on one command line (cl_config_set_once).  Configurations are small, so
 * lookups are linear.
 *
 * Line numbers: Debian's inih is built without INI_HANDLER_LINENO, so the
 * file, read whole (and refused if it holds a NUL byte), is fed through our
 * own reader, which counts lines; the handler then knows the line of every
 * entry.  A line that does not fit inih's line buffer, or a section name
 * inih would cut, stops the parse and is reported instead of being split
 * silently; so that the written file reads back, --set refuses what would
 * make such a line, and a long key = value is written as key=value.
 *
 * inih treats an indented line after a key as a continuation of that key's
 * value (python-configparser style) and calls the handler again with the
 * same name.  Such a value would silently replace the earlier one, so
 * continuation lines are rejected with a message saying why.
 *
 * Every getter records the (section, key) it asked for, present or not;
 * cl_config_check_unused() uses those names both to decide what is unused
 * and to list the known keys/sections in its message. */
#include "io/config.h"

#include "io/atomic.h"
#include "io/input.h"

#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

#include <ini.h>

typedef struct {
    char *sec, *key, *value;
    char *path;       /* a file name's absolute form, for write-back */
    const char *file; /* interned in cl_config.files; NULL for --set */
    long line;        /* 1-based; 0 for --set */
    bool used;
} cl_entry;

typedef struct {
    char *sec, *key;
    char *def; /* the default a getter used when the key was absent */
} cl_name;

struct cl_config {
    cl_entry *ent;
    size_t nent, cap_ent;
    cl_name *asked; /* names some getter asked for, in first-ask order */
    size_t nasked, cap_asked;
    char **files;   /* every path given to cl_config_load */
    size_t nfiles, cap_files;
};

/* Room for an origin: never truncates more than the message holding it. */
typedef char cl_origin_buf[sizeof ((cl_error *)0)->msg];

/* ---------------------------------------------------------------- storage */

static bool cl_grow(void **arr, size_t *cap, size_t need, size_t elem)
{
    if (need <= *cap)
        return true;
    size_t ncap = *cap ? *cap : 8;
    while (ncap < need) {
        if (ncap > SIZE_MAX / 2 / elem)
            return false;
        ncap *= 2;
    }
    void *p = realloc(*arr, ncap * elem);
    if (!p)
        return false;
    *arr = p;
    *cap = ncap;
    return true;
}

cl_config *cl_config_alloc(void)
{
    return calloc(1, sizeof(cl_config));
}

void cl_config_free(cl_config *cfg)
{
    if (!cfg)
        return;
    for (size_t i = 0; i < cfg->nent; i++) {
        free(cfg->ent[i].sec);
        free(cfg->ent[i].key);
        free(cfg->ent[i].value);
        free(cfg->ent[i].path);
    }
    for (size_t i = 0; i < cfg->nasked; i++) {
        free(cfg->asked[i].sec);
        free(cfg->asked[i].key);
        free(cfg->asked[i].def);
    }
    for (size_t i = 0; i < cfg->nfiles; i++)
        free(cfg->files[i]);
    free(cfg->ent);
    free(cfg->asked);
    free(cfg->files);
    free(cfg);
}

static cl_entry *cl_find(const cl_config *cfg, const char *sec,
                         const char *key)
{
    for (size_t i = 0; i < cfg->nent; i++)
        if (!strcmp(cfg->ent[i].sec, sec) && !strcmp(cfg->ent[i].key, key))
            return &cfg->ent[i];
    return NULL;
}

static bool cl_was_asked(const cl_config *cfg, const char *sec,
                         const char *key)
{
    for (size_t i = 0; i < cfg->nasked; i++)
        if (!strcmp(cfg->asked[i].sec, sec) &&
            (!key || !strcmp(cfg->asked[i].key, key)))
            return true;
    return false;
}

/* Set (sec, key) = value, replacing an earlier value and its origin. */
static cl_status cl_put(cl_config *cfg, const char *sec, const char *key,
                        const char *value, const char *file, long line)
{
    char *v = strdup(value);
    if (!v)
        return CL_ENOMEM;
    cl_entry *e = cl_find(cfg, sec, key);
    if (!e) {
        char *s = strdup(sec), *k = strdup(key);
        if (!s || !k ||
            !cl_grow((void **)&cfg->ent, &cfg->cap_ent, cfg->nent + 1,
                     sizeof *cfg->ent)) {
            free(s);
            free(k);
            free(v);
            return CL_ENOMEM;
        }
        e = &cfg->ent[cfg->nent++];
        *e = (cl_entry){.sec = s, .key = k};
    }
    free(e->value);
    free(e->path);
    e->value = v;
    e->path = NULL;
    e->file = file;
    e->line = line;
    return CL_OK;
}

/* Remember that a getter asked for (sec, key).  Only the messages of
 * cl_config_check_unused depend on this list, so running out of memory here
 * is not an error: the entry itself is still marked used. */
static void cl_note_asked(cl_config *cfg, const char *sec, const char *key)
{
    if (cl_was_asked(cfg, sec, key))
        return;
    char *s = strdup(sec), *k = strdup(key);
    if (!s || !k ||
        !cl_grow((void **)&cfg->asked, &cfg->cap_asked, cfg->nasked + 1,
                 sizeof *cfg->asked)) {
        free(s);
        free(k);
        return;
    }
    cfg->asked[cfg->nasked++] = (cl_name){.sec = s, .key = k};
}

static cl_entry *cl_lookup(cl_config *cfg, const char *sec, const char *key)
{
    cl_note_asked(cfg, sec, key);
    cl_entry *e = cl_find(cfg, sec, key);
    if (e)
        e->used = true;
    return e;
}

/* Record the default a getter used for the absent (sec, key), the first
 * time only (cl_config_resolved); like the asked list, a record lost to a
 * lack of memory only leaves the default out of that list. */
static void cl_note_default(cl_config *cfg, const char *sec, const char *key,
                            const char *text)
{
    for (size_t i = 0; i < cfg->nasked; i++) {
        cl_name *n = &cfg->asked[i];
        if (!strcmp(n->sec, sec) && !strcmp(n->key, key) && !n->def) {
            n->def = strdup(text);
            return;
        }
    }
}

static void cl_origin_of(const cl_entry *e, char *buf, size_t len)
{
    if (e->file && e->line >= 0)
        snprintf(buf, len, "%s:%ld", e->file, e->line);
    else
        snprintf(buf, len, "%s", e->file ? e->file : "--set");
}

const char *cl_config_path(const cl_config *cfg)
{
    return cfg->nfiles ? cfg->files[0] : NULL;
}

const char *cl_config_origin(const cl_config *cfg, const char *sec,
                             const char *key, char *buf, size_t len)
{
    if (!buf || !len)
        return NULL;
    const cl_entry *e = cl_find(cfg, sec, key);
    if (e)
        cl_origin_of(e, buf, len);
    else
        snprintf(buf, len, "(default)");
    return buf;
}

/* ---------------------------------------------------------------- loading */

/* Copy of s[0..n) without leading and trailing white space. */
static char *cl_dup_trim(const char *s, size_t n)
{
    while (n && isspace((unsigned char)*s)) {
        s++;
        n--;
    }
    while (n && isspace((unsigned char)s[n - 1]))
        n--;
    return strndup(s, n);
}

/* The longest line (without its line break) inih reads whole: its buffer
 * holds INI_MAX_LINE bytes, 3 more than the longest line ('\r', '\n' and
 * '\0', as ini.h says). */
#define CL_INI_LINE (INI_MAX_LINE - 3)
#define CL_INI_LINE_VALUE 197 /* CL_INI_LINE, for messages */
#define CL_STR_(x) #x
#define CL_STR(x) CL_STR_(x)
_Static_assert(CL_INI_LINE == CL_INI_LINE_VALUE, "inih's line length");
/* inih copies a section name into a buffer of MAX_SECTION = 50 bytes
 * (ini.c), cutting longer names silently. */
#define CL_INI_SECTION 49

typedef struct {
    const char *text; /* the whole file, NUL-free */
    size_t size, pos;
    cl_config *cfg;
    const char *file;
    long line;       /* line of the chunk inih is parsing */
    const char *buf; /* inih's line buffer, as last handed to the reader */
    size_t lead;     /* leading white space of that line */
    char **heads;    /* section headers met so far in this file ... */
    long *head_line; /* ... and their lines */
    size_t nhead, cap_head, cap_head_line;
    cl_error herr;   /* first error raised while reading or handling ... */
    long herr_line;  /* ... and its line, or 0 */
} cl_reader;

/* Record the first error of the parse; returns 0 for inih's handler. */
static int cl_reader_fail(cl_reader *r, cl_status code, const char *fmt, ...)
{
    if (r->herr_line)
        return 0;
    va_list ap;
    char msg[sizeof r->herr.msg];
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    r->herr_line = r->line;
    cl_error_set(&r->herr, code, "%s:%ld: %s", r->file, r->line, msg);
    return 0;
}

/* A "[name]" line opens a section once per file: a second header of the
 * same name would merge silently into the first.  After the ']' only a
 * comment may follow (inih would drop anything else unread). */
static bool cl_check_header(cl_reader *r, const char *s)
{
    const char *close = strchr(s, ']');
    if (*s != '[' || !close)
        return true;
    const char *rest = close + 1 + strspn(close + 1, " \t\r\v\f");
    if (*rest && *rest != '\n' && *rest != ';' && *rest != '#')
        return cl_reader_fail(r, CL_EPARSE,
                              "text after the section header: \"%.*s\" (a"
                              " key = value goes on a line of its own; a"
                              " comment starts with ';' or '#')",
                              (int)strcspn(rest, "\r\n"), rest);
    if (close - s - 1 > CL_INI_SECTION)
        return cl_reader_fail(r, CL_EPARSE,
                              "section name of %td characters; the INI"
                              " parser reads names of at most %d",
                              close - s - 1, CL_INI_SECTION);
    char *name = cl_dup_trim(s + 1, (size_t)(close - s - 1));
    if (!name)
        return cl_reader_fail(r, CL_ENOMEM, "out of memory");
    for (size_t i = 0; i < r->nhead; i++)
        if (!strcmp(r->heads[i], name)) {
            cl_reader_fail(r, CL_EPARSE,
                           "duplicate section [%s] (opened on line %ld);"
                           " each section may appear once: merge the two",
                           name, r->head_line[i]);
            free(name);
            return false;
        }
    if (!cl_grow((void **)&r->heads, &r->cap_head, r->nhead + 1,
                 sizeof *r->heads) ||
        !cl_grow((void **)&r->head_line, &r->cap_head_line, r->nhead + 1,
                 sizeof *r->head_line)) {
        free(name);
        return cl_reader_fail(r, CL_ENOMEM, "out of memory");
    }
    r->heads[r->nhead] = name;
    r->head_line[r->nhead++] = r->line;
    return true;
}

/* fgets-style reader for ini_parse_stream over the file's text: one call
 * per line.  A line too long for inih's buffer stops the parse before inih
 * sees half of it. */
static char *cl_ini_read(char *str, int num, void *stream)
{
    cl_reader *r = stream;
    if (r->herr_line || r->pos >= r->size)
        return NULL;
    const char *s = r->text + r->pos;
    const char *nl = memchr(s, '\n', r->size - r->pos);
    size_t len = nl ? (size_t)(nl - s) : r->size - r->pos;
    r->line++;
    if (len > CL_INI_LINE || len + 2 >= (size_t)num) {
        cl_reader_fail(r, CL_EPARSE,
                       "line of %zu characters; the INI parser reads lines"
                       " of at most %d (shorten it)", len, CL_INI_LINE);
        return NULL;
    }
    memcpy(str, s, len + (nl != NULL));
    str[len + (nl != NULL)] = '\0';
    r->pos += len + (nl != NULL);
    r->buf = str;
    r->lead = strspn(str, " \t\r\v\f");
    return cl_check_header(r, str + r->lead) ? str : NULL;
}

static int cl_ini_entry(void *user, const char *sec, const char *name,
                        const char *value)
{
    cl_reader *r = user;
    /* inih passes a continuation's text starting at the first non-blank
     * character of the indented line; an ordinary value starts after '='. */
    if (r->lead > 0 && value == r->buf + r->lead)
        return cl_reader_fail(r, CL_EPARSE,
                              "indented line continues the value of [%s] %s;"
                              " multi-line values are not supported (remove"
                              " the indentation)", sec, name);
    if (!*name)
        return cl_reader_fail(r, CL_EPARSE, "'=' without a key name before"
                              " it (expected key = value)");
    /* inih trims keys and values but not "[ section ]" */
    char *s = cl_dup_trim(sec, strlen(sec));
    if (!s)
        return cl_reader_fail(r, CL_ENOMEM, "out of memory");
    const cl_entry *e = cl_find(r->cfg, s, name);
    if (e && e->file == r->file) {
        cl_reader_fail(r, CL_EPARSE,
                       "duplicate key [%s] %s (first on line %ld); each key"
                       " may appear once per section", s, name, e->line);
        free(s);
        return 0;
    }
    cl_status rc = cl_put(r->cfg, s, name, value, r->file, r->line);
    free(s);
    return rc == CL_OK ? 1 : cl_reader_fail(r, CL_ENOMEM, "out of memory");
}

static const char *cl_intern_file(cl_config *cfg, const char *path)
{
    char *p = strdup(path);
    if (!p || !cl_grow((void **)&cfg->files, &cfg->cap_files,
                       cfg->nfiles + 1, sizeof *cfg->files)) {
        free(p);
        return NULL;
    }
    cfg->files[cfg->nfiles++] = p;
    return p;
}

/* Whether some entry came from this load of a file. */
static bool cl_file_has_keys(const cl_config *cfg, const char *file)
{
    for (size_t i = 0; i < cfg->nent; i++)
        if (cfg->ent[i].file == file)
            return true;
    return false;
}

/* Pick the first problem found while parsing (by line). */
static cl_status cl_parse_result(const cl_reader *r, int rc, cl_error *err)
{
    if (rc == -2 || (r->herr_line && r->herr.code == CL_ENOMEM))
        return cl_error_set(err, CL_ENOMEM, "%s: out of memory", r->file);
    if (rc > 0 && (!r->herr_line || rc < r->herr_line))
        return cl_error_set(err, CL_EPARSE,
                            "%s:%d: malformed line (expected [section],"
                            " key = value or a ; comment)",
                            r->file, rc);
    if (r->herr_line) {
        if (err)
            *err = r->herr;
        return r->herr.code;
    }
    if (!cl_file_has_keys(r->cfg, r->file))
        return cl_error_set(err, CL_EPARSE,
                            "%s:1: no key = value line: the file is empty or"
                            " holds only comments and section headers",
                            r->file);
    return CL_OK;
}

/* The largest problem file read: problem files are a few kilobytes (the
 * meshes are files of their own). */
#define CL_CONFIG_MAX_BYTES (16L << 20)

/* The whole of the open file fp in a malloc'd buffer (*size bytes), or up
 * to its first NUL byte (cl_check_nul reports it: /dev/zero ends at once).
 * More than CL_CONFIG_MAX_BYTES: CL_EPARSE. */
static cl_status cl_slurp(FILE *fp, const char *path, char **text,
                         size_t *size, cl_error *err)
{
    char *buf = NULL;
    size_t len = 0, cap = 0;
    for (;;) {
        if (len > CL_CONFIG_MAX_BYTES) {
            free(buf);
            return cl_error_set(err, CL_EPARSE, "%s: longer than %ld MiB; "
                                "a problem file is text of at most %ld MiB",
                                path, CL_CONFIG_MAX_BYTES >> 20,
                                CL_CONFIG_MAX_BYTES >> 20);
        }
        if (!cl_grow((void **)&buf, &cap, len + 4096, 1)) {
            free(buf);
            return cl_error_set(err, CL_ENOMEM, "%s: out of memory", path);
        }
        size_t got = fread(buf + len, 1, cap - len, fp);
        len += got;
        if (got == 0 || memchr(buf + len - got, '\0', got))
            break;
    }
    if (ferror(fp)) {
        free(buf);
        return cl_error_set(err, CL_EIO, "cannot read %s: %s", path,
                            strerror(errno ? errno : EIO));
    }
    *text = buf;
    *size = len;
    return CL_OK;
}

/* A problem file is text: a NUL byte would end inih's view of its line. */
static cl_status cl_check_nul(const char *text, size_t size,
                              const char *path, cl_error *err)
{
    const char *nul = memchr(text, '\0', size);
    if (!nul)
        return CL_OK;
    long line = 1;
    const char *start = text;
    for (const char *c = text; c < nul; c++)
        if (*c == '\n') {
            line++;
            start = c + 1;
        }
    return cl_error_set(err, CL_EPARSE,
                        "%s:%ld: NUL byte at column %td; a problem file is"
                        " text without NUL bytes", path, line,
                        nul - start + 1);
}

static cl_status cl_parse_text(cl_config *cfg, const char *file,
                               const char *text, size_t size, cl_error *err)
{
    cl_reader r = {.text = text, .size = size, .cfg = cfg, .file = file};
    int rc = ini_parse_stream(cl_ini_read, &r, cl_ini_entry, &r);
    cl_status st = cl_parse_result(&r, rc, err);
    for (size_t i = 0; i < r.nhead; i++)
        free(r.heads[i]);
    free(r.heads);
    free(r.head_line);
    return st;
}

cl_status cl_config_load(cl_config *cfg, const char *path, cl_error *err)
{
    const char *why;
    if (!path)
        return cl_error_set(err, CL_EINVAL, "no problem file named (path "
                            "NULL)");
    FILE *fp = cl_input_open(path, "r", &why);
    if (!fp)
        return cl_error_set(err, CL_EIO, "cannot open %s: %s", path, why);
    char *text = NULL;
    size_t size = 0;
    const char *file = cl_intern_file(cfg, path);
    cl_status rc = file ? cl_slurp(fp, path, &text, &size, err)
                        : cl_error_set(err, CL_ENOMEM, "%s: out of memory",
                                       path);
    fclose(fp);
    if (!rc)
        rc = cl_check_nul(text, size, path, err);
    if (!rc)
        rc = cl_parse_text(cfg, file, text, size, err);
    free(text);
    return rc;
}

/* ------------------------------------------------------------------ --set */

/* Names and values must survive cl_config_write and a reload unchanged. */
static const char *cl_set_problem(const char *sec, const char *key,
                                  const char *value)
{
    if (!*sec)
        return "empty section name";
    if (!*key)
        return "empty key name";
    if (strpbrk(sec, "];\n\r"))
        return "section name may not contain ']' or ';'";
    if (strpbrk(key, ":;\n\r") || strchr("[#", key[0]))
        return "key name may not contain ':' or ';' nor start with"
               " '[' or '#'";
    if (strpbrk(value, "\n\r"))
        return "value may not contain a line break";
    if (strlen(sec) > CL_INI_SECTION)
        return "section name longer than the INI parser reads (at most"
               " 49 characters)";
    if (strlen(key) + 1 + strlen(value) > CL_INI_LINE)
        return "too long for a line of the INI file written back (at most "
               CL_STR(CL_INI_LINE_VALUE) " characters for key=value)";
    for (const char *p = strchr(value, ';'); p; p = strchr(p + 1, ';'))
        if (p == value || isspace((unsigned char)p[-1]))
            return "value may not start with ';' nor contain ' ;', which"
                   " starts a comment";
    return NULL;
}

/* A command line gives each key once: a second --set (or option) of the
 * same key would silently replace the first.  Who set it: the option's
 * label, or NULL for an earlier --set; NULL too if it is not set by the
 * command line. */
static bool cl_set_twice(const cl_config *cfg, const char *sec,
                         const char *key, const char **who)
{
    const cl_entry *e = cl_find(cfg, sec, key);
    *who = e ? e->file : NULL;
    return cl_config_set_by_command(cfg, sec, key);
}

static cl_status cl_set_split(cl_config *cfg, const char *a, const char *dot,
                              const char *eq, const char *label, bool once,
                              cl_error *err)
{
    char *sec = cl_dup_trim(a, (size_t)(dot - a));
    char *key = cl_dup_trim(dot + 1, (size_t)(eq - dot - 1));
    char *value = cl_dup_trim(eq + 1, strlen(eq + 1));
    cl_status rc = CL_OK;
    const char *why, *who;
    if (!sec || !key || !value)
        rc = cl_error_set(err, CL_ENOMEM, "--set \"%s\": out of memory", a);
    else if ((why = cl_set_problem(sec, key, value)))
        rc = cl_error_set(err, CL_EINVAL,
                          "--set \"%s\": %s (expected section.key=value)",
                          a, why);
    else if (once && cl_set_twice(cfg, sec, key, &who))
        rc = label ? cl_error_set(err, CL_EINVAL, "%s %s: [%s] %s is already "
                                  "set by %s; give each key once", label,
                                  value, sec, key,
                                  who ? who : "an earlier --set")
                   : cl_error_set(err, CL_EINVAL, "--set \"%s\": [%s] %s is "
                                  "already set by %s; give each key once", a,
                                  sec, key, who ? who : "an earlier --set");
    else if (cl_put(cfg, sec, key, value,
                    label ? cl_intern_file(cfg, label) : NULL,
                    label ? -1 : 0) != CL_OK)
        rc = cl_error_set(err, CL_ENOMEM, "--set \"%s\": out of memory", a);
    free(sec);
    free(key);
    free(value);
    return rc;
}

static cl_status cl_set_assign(cl_config *cfg, const char *assignment,
                               const char *label, bool once, cl_error *err)
{
    const char *eq = strchr(assignment, '=');
    if (!eq)
        return cl_error_set(err, CL_EINVAL,
                            "--set \"%s\": missing '=' (expected"
                            " section.key=value)",
                            assignment);
    const char *dot = NULL; /* the last '.': sections may hold dots */
    for (const char *c = assignment; c < eq; c++)
        if (*c == '.')
            dot = c;
    if (!dot)
        return cl_error_set(err, CL_EINVAL,
                            "--set \"%s\": missing '.' between section and"
                            " key (expected section.key=value)",
                            assignment);
    return cl_set_split(cfg, assignment, dot, eq, label, once, err);
}

cl_status cl_config_set(cl_config *cfg, const char *assignment, cl_error *err)
{
    return cl_set_assign(cfg, assignment, NULL, false, err);
}

cl_status cl_config_set_as(cl_config *cfg, const char *assignment,
                           const char *label, cl_error *err)
{
    return cl_set_assign(cfg, assignment, label, false, err);
}

cl_status cl_config_set_once(cl_config *cfg, const char *assignment,
                             const char *label, cl_error *err)
{
    return cl_set_assign(cfg, assignment, label, true, err);
}

/* ---------------------------------------------------------- value parsing */

static bool cl_only_space(const char *s)
{
    while (isspace((unsigned char)*s))
        s++;
    return *s == '\0';
}

/* strtod with clothode's rules for a number: NULL if *x is one, else why
 * not ("" for text that is no number at all).  `cap`: a parameter, at most
 * CL_CONFIG_MAX_ABS in magnitude (not a vector's component: a direction
 * such as a plane's normal may have any length). */
static const char *cl_strtod(const char *s, char **end, double *x, bool cap)
{
    errno = 0;
    *x = strtod(s, end);
    if (*end == s)
        return "";
    if (!isfinite(*x))
        return errno == ERANGE ? "beyond the range of a double"
                               : "not a finite number";
    if (errno == ERANGE)
        return "so small that it rounds to a subnormal number or zero";
    if (cap && fabs(*x) > CL_CONFIG_MAX_ABS)
        return "larger in magnitude than any physical parameter"
               " (at most " CL_CONFIG_MAX_ABS_TEXT ")";
    return NULL;
}

static const char *cl_parse_double(const char *s, double *out)
{
    char *end;
    const char *why = cl_strtod(s, &end, out, true);
    return why ? why : cl_only_space(end) ? NULL : "";
}

static bool cl_parse_long(const char *s, long *out)
{
    char *end;
    errno = 0;
    long x = strtol(s, &end, 10);
    if (end == s || !cl_only_space(end) || errno == ERANGE)
        return false;
    *out = x;
    return true;
}

/* Shortest "%.*g" of x that reads back as x. */
static void cl_fmt_double(char *buf, size_t len, double x)
{
    for (int prec = 6; prec < 17; prec++) {
        snprintf(buf, len, "%.*g", prec, x);
        if (strtod(buf, NULL) == x)
            return;
    }
    snprintf(buf, len, "%.17g", x);
}

static void cl_range_text(char *buf, size_t len, const char *noun,
                          const char *lo, const char *hi)
{
    if (lo && hi)
        snprintf(buf, len, "%s in [%s, %s]", noun, lo, hi);
    else if (lo)
        snprintf(buf, len, "%s >= %s", noun, lo);
    else if (hi)
        snprintf(buf, len, "%s <= %s", noun, hi);
    else
        snprintf(buf, len, "%s", noun);
}

/* "a number >= 0", "a number in [0.1, 1]"; open ends are closed at the
 * largest magnitude a number may have. */
static void cl_double_range(char *buf, size_t len, double lo, double hi)
{
    char l[32], h[32];
    cl_fmt_double(l, sizeof l, fmax(lo, -CL_CONFIG_MAX_ABS));
    cl_fmt_double(h, sizeof h, fmin(hi, CL_CONFIG_MAX_ABS));
    cl_range_text(buf, len, "a number", l, h);
}

static void cl_long_range(char *buf, size_t len, long lo, long hi)
{
    char l[32], h[32];
    snprintf(l, sizeof l, "%ld", lo);
    snprintf(h, sizeof h, "%ld", hi);
    cl_range_text(buf, len, "an integer", lo > LONG_MIN ? l : NULL,
                  hi < LONG_MAX ? h : NULL);
}

/* "<origin>: [sec] key = "value": expected <what>" */
static cl_status cl_bad_value(const cl_entry *e, const char *what,
                              cl_error *err)
{
    cl_origin_buf origin;
    cl_origin_of(e, origin, sizeof origin);
    return cl_error_set(err, CL_EINVAL, "%s: [%s] %s = \"%s\": expected %s",
                        origin, e->sec, e->key, e->value, what);
}

/* Parse `count` numbers separated by commas and/or white space into out
 * (if not NULL); NULL, or why not (as cl_strtod). */
static const char *cl_parse_vector(const char *s, size_t count, double *out)
{
    for (size_t i = 0; i < count; i++) {
        while (isspace((unsigned char)*s))
            s++;
        if (i > 0 && *s == ',') {
            s++;
            while (isspace((unsigned char)*s))
                s++;
        }
        char *end;
        double x;
        const char *why = cl_strtod(s, &end, &x, false);
        if (why)
            return why;
        if (*end && *end != ',' && !isspace((unsigned char)*end))
            return "";
        if (out)
            out[i] = x;
        s = end;
    }
    return cl_only_space(s) ? NULL : "";
}

/* ---------------------------------------------------------------- getters */

cl_status cl_config_double(cl_config *cfg, const char *sec, const char *key,
                           double def, double lo, double hi, double *out,
                           cl_error *err)
{
    const cl_entry *e = cl_lookup(cfg, sec, key);
    double x = def;
    if (!e) {
        char text[32];
        cl_fmt_double(text, sizeof text, def);
        cl_note_default(cfg, sec, key, text);
    }
    const char *why = e ? cl_parse_double(e->value, &x) : NULL;
    if (e && (why || !(x >= lo && x <= hi))) {
        char range[96], what[224];
        cl_double_range(range, sizeof range, lo, hi);
        snprintf(what, sizeof what, why && *why ? "%s (this is %s)" : "%s",
                 range, why);
        return cl_bad_value(e, what, err);
    }
    *out = x;
    return CL_OK;
}

cl_status cl_config_long(cl_config *cfg, const char *sec, const char *key,
                         long def, long lo, long hi, long *out, cl_error *err)
{
    const cl_entry *e = cl_lookup(cfg, sec, key);
    long x = def;
    if (!e) {
        char text[32];
        snprintf(text, sizeof text, "%ld", def);
        cl_note_default(cfg, sec, key, text);
    }
    if (e && (!cl_parse_long(e->value, &x) || x < lo || x > hi)) {
        char what[128];
        cl_long_range(what, sizeof what, lo, hi);
        return cl_bad_value(e, what, err);
    }
    *out = x;
    return CL_OK;
}

cl_status cl_config_bool(cl_config *cfg, const char *sec, const char *key,
                         bool def, bool *out, cl_error *err)
{
    static const char *const names[] = {"true", "false", "yes", "no",
                                        "on",   "off",   "1",   "0"};
    const cl_entry *e = cl_lookup(cfg, sec, key);
    if (!e) {
        cl_note_default(cfg, sec, key, def ? "true" : "false");
        *out = def;
        return CL_OK;
    }
    for (size_t i = 0; i < sizeof names / sizeof *names; i++)
        if (!strcasecmp(e->value, names[i])) {
            *out = i % 2 == 0;
            return CL_OK;
        }
    return cl_bad_value(e, "true/false, yes/no, on/off or 1/0", err);
}

/* "one of a, b, c" in a malloc'd string, or NULL. */
static char *cl_choice_text(const char *const *choices)
{
    char *text = NULL;
    size_t size = 0;
    FILE *f = open_memstream(&text, &size);
    if (!f)
        return NULL;
    fputs("one of ", f);
    for (size_t i = 0; choices[i]; i++)
        fprintf(f, "%s%s", i ? ", " : "", choices[i]);
    if (fclose(f) != 0) {
        free(text);
        return NULL;
    }
    return text;
}

cl_status cl_config_choice(cl_config *cfg, const char *sec, const char *key,
                           const char *const *choices, int def, int *out,
                           cl_error *err)
{
    const cl_entry *e = cl_lookup(cfg, sec, key);
    if (!e) {
        cl_note_default(cfg, sec, key, choices[def]);
        *out = def;
        return CL_OK;
    }
    for (int i = 0; choices[i]; i++)
        if (!strcmp(e->value, choices[i])) {
            *out = i;
            return CL_OK;
        }
    char *what = cl_choice_text(choices);
    if (!what)
        return cl_error_set(err, CL_ENOMEM, "[%s] %s: out of memory", sec,
                            key);
    cl_status rc = cl_bad_value(e, what, err);
    free(what);
    return rc;
}

cl_status cl_config_vector(cl_config *cfg, const char *sec, const char *key,
                           size_t count, double *out, cl_error *err)
{
    const cl_entry *e = cl_lookup(cfg, sec, key);
    if (!e)
        return CL_OK;
    const char *why = cl_parse_vector(e->value, count, NULL);
    if (why) {
        char what[224];
        snprintf(what, sizeof what,
                 "%zu finite number%s separated by commas or spaces%s%s%s",
                 count, count == 1 ? "" : "s", *why ? " (one is " : "", why,
                 *why ? ")" : "");
        return cl_bad_value(e, what, err);
    }
    cl_parse_vector(e->value, count, out);
    return CL_OK;
}

const char *cl_config_string(cl_config *cfg, const char *sec, const char *key,
                             const char *def)
{
    const cl_entry *e = cl_lookup(cfg, sec, key);
    if (!e && def)
        cl_note_default(cfg, sec, key, def);
    return e ? e->value : def;
}

cl_status cl_config_missing(const cl_config *cfg, const char *sec,
                            const char *key, const char *what,
                            cl_error *err)
{
    cl_origin_buf origin;
    snprintf(origin, sizeof origin, "%s",
             cfg->nfiles ? cfg->files[0] : "(no file)");
    for (size_t i = 0; i < cfg->nent; i++)
        if (!strcmp(cfg->ent[i].sec, sec)) {
            cl_origin_of(&cfg->ent[i], origin, sizeof origin);
            break;
        }
    return cl_error_set(err, CL_EINVAL, "%s: [%s] %s: required (%s)", origin,
                        sec, key, what);
}

bool cl_config_set_by_command(const cl_config *cfg, const char *sec,
                              const char *key)
{
    const cl_entry *e = cl_find(cfg, sec, key);
    return e && e->line <= 0;
}

const char *cl_config_set_key_at(const cl_config *cfg, size_t k,
                                 const char **sec)
{
    for (const cl_entry *e = cfg->ent; e < cfg->ent + cfg->nent; e++)
        if (e->line <= 0 && !e->file && k-- == 0) {
            *sec = e->sec;
            return e->key;
        }
    return NULL;
}

const char *cl_config_peek(const cl_config *cfg, const char *sec,
                           const char *key)
{
    const cl_entry *e = cl_find(cfg, sec, key);
    return e ? e->value : NULL;
}

void cl_config_resolved(const cl_config *cfg, cl_config_visit_fn visit,
                        void *ctx)
{
    for (size_t i = 0; i < cfg->nent; i++)
        visit(ctx, cfg->ent[i].sec, cfg->ent[i].key, cfg->ent[i].value,
              true);
    for (size_t i = 0; i < cfg->nasked; i++)
        if (cfg->asked[i].def &&
            !cl_find(cfg, cfg->asked[i].sec, cfg->asked[i].key))
            visit(ctx, cfg->asked[i].sec, cfg->asked[i].key,
                  cfg->asked[i].def, false);
}

void cl_config_input_files(const cl_config *cfg, cl_config_visit_fn visit,
                           void *ctx)
{
    for (size_t i = 0; i < cfg->nent; i++)
        if (cfg->ent[i].path)
            visit(ctx, cfg->ent[i].sec, cfg->ent[i].key, cfg->ent[i].path,
                  true);
}

/* ----------------------------------------------------------- unused keys */

/* Whether asked[i]'s section already occurs in asked[0..i-1]. */
static bool cl_seen_section(const cl_config *cfg, size_t i)
{
    for (size_t j = 0; j < i; j++)
        if (!strcmp(cfg->asked[j].sec, cfg->asked[i].sec))
            return true;
    return false;
}

/* Asked-for keys of `sec` (or, if sec is NULL, the asked-for sections),
 * comma-separated, in a malloc'd string; NULL if out of memory. */
static char *cl_known_text(const cl_config *cfg, const char *sec)
{
    char *text = NULL;
    size_t size = 0;
    FILE *f = open_memstream(&text, &size);
    if (!f)
        return NULL;
    const char *sep = "";
    for (size_t i = 0; i < cfg->nasked; i++) {
        const cl_name *n = &cfg->asked[i];
        if (sec ? strcmp(n->sec, sec) != 0 || !*n->key
                : cl_seen_section(cfg, i))
            continue;
        fprintf(f, sec ? "%s%s" : "%s[%s]", sep, sec ? n->key : n->sec);
        sep = ", ";
    }
    if (!*sep)
        fputs("none", f);
    if (fclose(f) != 0) {
        free(text);
        return NULL;
    }
    return text;
}

static cl_status cl_report_unused(const cl_config *cfg, const cl_entry *e,
                                  cl_error *err)
{
    bool known_sec = cl_was_asked(cfg, e->sec, NULL);
    char *known = cl_known_text(cfg, known_sec ? e->sec : NULL);
    if (!known)
        return cl_error_set(err, CL_ENOMEM, "out of memory");
    cl_origin_buf origin;
    cl_origin_of(e, origin, sizeof origin);
    cl_status rc;
    if (known_sec)
        rc = cl_error_set(err, CL_EINVAL,
                          "%s: unknown key [%s] %s (known keys in [%s]: %s)",
                          origin, e->sec, e->key, e->sec, known);
    else if (!*e->sec)
        rc = cl_error_set(err, CL_EINVAL,
                          "%s: unknown key %s outside any section (known"
                          " sections: %s)",
                          origin, e->key, known);
    else
        rc = cl_error_set(err, CL_EINVAL,
                          "%s: unknown section [%s] (known sections: %s)",
                          origin, e->sec, known);
    free(known);
    return rc;
}

cl_status cl_config_check_unused(const cl_config *cfg, cl_error *err)
{
    for (size_t i = 0; i < cfg->nent; i++) {
        const cl_entry *e = &cfg->ent[i];
        if (!e->used && !cl_was_asked(cfg, e->sec, e->key))
            return cl_report_unused(cfg, e, err);
    }
    return CL_OK;
}

void cl_config_ignore_section(cl_config *cfg, const char *sec)
{
    for (size_t i = 0; i < cfg->nent; i++)
        if (!strcmp(cfg->ent[i].sec, sec))
            cfg->ent[i].used = true;
}

void cl_config_ignore(cl_config *cfg, const char *sec, const char *key)
{
    (void)cl_lookup(cfg, sec, key);
}

static const cl_entry *cl_find_section(const cl_config *cfg,
                                       const char *sec);

cl_status cl_config_refuse(const cl_config *cfg, const char *sec,
                           const char *key, cl_status code, const char *why,
                           cl_error *err)
{
    cl_origin_buf origin;
    const cl_entry *e = cl_lookup((cl_config *)cfg, sec, key);
    cl_origin_of(e, origin, sizeof origin);
    return cl_error_set(err, code, "%s: [%s] %s = \"%s\": %s", origin, sec,
                        key, e ? e->value : "", why);
}

const char *cl_config_section_at(cl_config *cfg, const char *prefix,
                                 size_t k)
{
    size_t len = strlen(prefix), seen = 0;
    char family[128];
    /* the family counts as a known section, [PREFIXNAME], with no key */
    if (k == 0 && snprintf(family, sizeof family, "%sNAME", prefix) <
                      (int)sizeof family)
        cl_note_asked(cfg, family, "");
    for (const cl_entry *e = cfg->ent; e < cfg->ent + cfg->nent; e++)
        if (!strncmp(e->sec, prefix, len) && cl_find_section(cfg, e->sec) == e
            && seen++ == k)
            return e->sec;
    return NULL;
}

const char *cl_config_key_at(const cl_config *cfg, const char *sec,
                             size_t k)
{
    size_t seen = 0;
    for (const cl_entry *e = cfg->ent; e < cfg->ent + cfg->nent; e++)
        if (!strcmp(e->sec, sec) && seen++ == k)
            return e->key;
    return NULL;
}

cl_status cl_config_path_of(cl_config *cfg, const char *sec, const char *key,
                            char *buf, size_t len, cl_error *err)
{
    const char *name = cl_config_string(cfg, sec, key, "");
    cl_entry *e = cl_lookup(cfg, sec, key);
    cl_origin_buf origin;
    if (!*name)
        return cl_error_set(err, CL_EINVAL, "[%s] %s: a file name is "
                            "required", sec, key);
    cl_origin_of(e, origin, sizeof origin);
    const char *slash = e->file ? strrchr(e->file, '/') : NULL;
    int dirlen = name[0] == '/' || !slash ? 0 : (int)(slash - e->file) + 1;
    int n = snprintf(buf, len, "%.*s%s", dirlen, e->file ? e->file : "", name);
    if (n < 0 || (size_t)n >= len)
        return cl_error_set(err, CL_EINVAL, "%s: [%s] %s = \"%s\": path too "
                            "long (at most %zu bytes)", origin, sec, key, name,
                            len - 1);
    /* A relative name is relative to its file: config.ini, written
     * elsewhere, names the file absolutely to read back the same run. */
    free(e->path);
    e->path = realpath(buf, NULL);
    return CL_OK;
}

/* ---------------------------------------------------------------- writing */

/* The first entry of section `sec`, or NULL. */
static const cl_entry *cl_find_section(const cl_config *cfg, const char *sec)
{
    for (size_t i = 0; i < cfg->nent; i++)
        if (!strcmp(cfg->ent[i].sec, sec))
            return &cfg->ent[i];
    return NULL;
}

/* A section after other lines is set off by a blank line. */
static void cl_write_section(const cl_config *cfg, const cl_entry *first,
                             bool after, FILE *f)
{
    if (*first->sec)
        fprintf(f, "%s[%s]\n", after ? "\n" : "", first->sec);
    for (const cl_entry *e = first; e < cfg->ent + cfg->nent; e++) {
        if (strcmp(e->sec, first->sec) != 0)
            continue;
        const char *value = e->path ? e->path : e->value;
        /* "key = ;x" would start a comment: such a value was read from
         * "key=;x", as is a value too long for the spaced form */
        if (strlen(e->key) + 3 + strlen(value) > CL_INI_LINE ||
            value[0] == ';')
            fprintf(f, "%s=%s\n", e->key, value);
        else if (*value)
            fprintf(f, "%s = %s\n", e->key, value);
        else
            fprintf(f, "%s =\n", e->key);
    }
}

/* Keys before any header (section "") must come first, without a header;
 * then every section in order of first appearance. */
static void cl_write_entries(const cl_config *cfg, FILE *f)
{
    const cl_entry *top = cl_find_section(cfg, "");
    bool after = top != NULL;
    if (top)
        cl_write_section(cfg, top, false, f);
    for (const cl_entry *e = cfg->ent; e < cfg->ent + cfg->nent; e++)
        if (*e->sec && cl_find_section(cfg, e->sec) == e) {
            cl_write_section(cfg, e, after, f);
            after = true;
        }
}

cl_status cl_config_write(const cl_config *cfg, const char *path,
                          cl_error *err)
{
    cl_afile af;
    cl_status rc = cl_afile_open(&af, path, err);
    if (rc)
        return rc;
    cl_write_entries(cfg, af.fp);
    return cl_afile_commit(&af, err);
}
