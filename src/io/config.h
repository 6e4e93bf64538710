/* Problem configuration: INI files (parsed by inih) plus command-line
 * overrides `--set section.key=value`.
 *
 * Every entry remembers where it came from (file and line, or "--set"), so
 * that a bad value is reported as
 *   problems/hang.ini:12: [type1] ks = "abc": expected a number >= 0
 * Typed getters mark entries as used; cl_config_check_unused() then reports
 * any key nobody asked for (a typo) with its file and line. */
#ifndef CL_CONFIG_H
#define CL_CONFIG_H

#include <stdbool.h>
#include <stddef.h>

#include "core/decls.h"
#include "core/error.h"

CL_BEGIN_DECLS

typedef struct cl_config cl_config;

/* The largest magnitude of a number (cl_config_double) in a problem file:
 * beyond it a value is no physical parameter (ks = 1e300 would run for
 * hours), and the message gives the allowed range.  Numbers that overflow
 * or underflow to a subnormal or zero, nan and inf are refused in vectors
 * too (README "Strict inputs"). */
#define CL_CONFIG_MAX_ABS 1e12
#define CL_CONFIG_MAX_ABS_TEXT "1e12"

cl_config *cl_config_alloc(void);
void cl_config_free(cl_config *cfg);

/* Parse an INI file; later entries override earlier ones (also across
 * several files).  Sections and keys are case-sensitive and trimmed.
 * Malformed lines give CL_EPARSE with file and line, as do indented lines
 * that inih would read as the continuation of the previous value and lines
 * too long for inih's buffer; a missing or unreadable file gives CL_EIO.
 * After a failure cfg may hold part of the file. */
cl_status cl_config_load(cl_config *cfg, const char *path, cl_error *err);

/* Apply "section.key=value" (as given to --set): split at the first '=' and
 * at the last '.' before it (so "obstacle.ball.radius=1" sets [obstacle.ball]
 * radius); parts are trimmed and the value may be empty.
 * Keys not present in the file are accepted here and checked by
 * cl_config_check_unused().  CL_EINVAL for a malformed assignment or names
 * and values that could not be written back as INI (e.g. "a.b:c=1"). */
cl_status cl_config_set(cl_config *cfg, const char *assignment, cl_error *err);
/* The same, with the entry's origin reported as `label` (e.g. "--dt" for a
 * command-line option that stands for a key); NULL means "--set". */
cl_status cl_config_set_as(cl_config *cfg, const char *assignment,
                           const char *label, cl_error *err);
/* cl_config_set_as for a command line, which gives each key once: a key
 * already set by an earlier assignment (not by a file) is refused with
 * CL_EINVAL instead of replaced. */
cl_status cl_config_set_once(cl_config *cfg, const char *assignment,
                             const char *label, cl_error *err);

/* The file name given to the first cl_config_load (for messages and
 * outputs), or NULL if no file was loaded. */
const char *cl_config_path(const cl_config *cfg);

/* Typed getters.  If the key is absent, *out = def and CL_OK.  A present
 * value that does not parse or lies outside [lo, hi] gives CL_EINVAL with the
 * origin, key, value and allowed range. */
cl_status cl_config_double(cl_config *cfg, const char *sec, const char *key,
                           double def, double lo, double hi, double *out,
                           cl_error *err);
cl_status cl_config_long(cl_config *cfg, const char *sec, const char *key,
                         long def, long lo, long hi, long *out, cl_error *err);
cl_status cl_config_bool(cl_config *cfg, const char *sec, const char *key,
                         bool def, bool *out, cl_error *err);
/* One of a fixed set of names; *out is the index into `choices`
 * (NULL-terminated).  The message lists the allowed names. */
cl_status cl_config_choice(cl_config *cfg, const char *sec, const char *key,
                           const char *const *choices, int def, int *out,
                           cl_error *err);
/* A list of `count` numbers separated by commas and/or spaces, e.g. a vector
 * "0, -9.81, 0".  If absent, out is left untouched. */
cl_status cl_config_vector(cl_config *cfg, const char *sec, const char *key,
                           size_t count, double *out, cl_error *err);
/* Raw string, or def if absent (pointer valid until the entry is set again
 * or cfg is freed). */
const char *cl_config_string(cl_config *cfg, const char *sec, const char *key,
                             const char *def);
/* Where an entry came from, "file:line" or "--set" ("(default)" if absent),
 * for messages built by callers that validate values themselves (e.g.
 * cross-key checks).  Written to buf (truncated to len); returns buf. */
const char *cl_config_origin(const cl_config *cfg, const char *sec,
                             const char *key, char *buf, size_t len);

/* Refuse the value of an entry: `code` with "ORIGIN: [sec] key = "value":
 * why", for checks a typed getter cannot make (cross-key rules, a file's
 * content, a syntax of its own). */
cl_status cl_config_refuse(const cl_config *cfg, const char *sec,
                           const char *key, cl_status code, const char *why,
                           cl_error *err);

/* CL_EINVAL for a key section `sec` lacks: "ORIGIN: [sec] key: required
 * (what)", ORIGIN the file and line of the section's first entry (the
 * first file loaded if the section has none). */
cl_status cl_config_missing(const cl_config *cfg, const char *sec,
                            const char *key, const char *what,
                            cl_error *err);

/* CL_EINVAL naming the first entry no getter asked for, with the list of
 * keys known in its section if that section is known at all (names count as
 * known once a getter asked for them, present in the file or not). */
cl_status cl_config_check_unused(const cl_config *cfg, cl_error *err);

/* The distinct sections whose names start with `prefix` (e.g. "obstacle."
 * for [obstacle.ball], [obstacle.floor]), in order of first appearance:
 * the k-th (0-based) such name, or NULL when there are k or fewer.  Asked
 * for k = 0, the family counts as known ([obstacle.NAME] in the list of
 * known sections of cl_config_check_unused). */
const char *cl_config_section_at(cl_config *cfg, const char *prefix,
                                 size_t k);

/* Whether [sec] key was set by cl_config_set* (a command line) rather
 * than by a file or not at all. */
bool cl_config_set_by_command(const cl_config *cfg, const char *sec,
                              const char *key);

/* The k-th (0-based) entry set by cl_config_set (a --set of the command
 * line; not cl_config_set_as, a command's own option), its section in
 * *sec; NULL when there are k or fewer. */
const char *cl_config_set_key_at(const cl_config *cfg, size_t k,
                                 const char **sec);

/* The value of [sec] key as given, or NULL, without counting it as read
 * (cl_config_check_unused still reports a key nothing else reads). */
const char *cl_config_peek(const cl_config *cfg, const char *sec,
                           const char *key);

/* The k-th (0-based) key of section `sec` in order of first appearance,
 * or NULL when it has k or fewer; for sections whose keys are names of
 * the caller's choosing (a sweep's axes).  Does not mark it used. */
const char *cl_config_key_at(const cl_config *cfg, const char *sec,
                             size_t k);

/* A file named by a key, relative to the directory of the file that set
 * it (an entry from --set: relative to the working directory), into buf;
 * CL_EINVAL naming the entry if the key is absent or empty or the path
 * does not fit in len bytes. */
cl_status cl_config_path_of(cl_config *cfg, const char *sec, const char *key,
                            char *buf, size_t len, cl_error *err);

/* Count every entry now in section `sec` as used, for commands that
 * deliberately do not read that section. */
void cl_config_ignore_section(cl_config *cfg, const char *sec);

/* Count [sec] key as used and known without reading it, for a command
 * that deliberately does not read that key. */
void cl_config_ignore(cl_config *cfg, const char *sec, const char *key);

/* The fully resolved configuration: visit(ctx, sec, key, value, given)
 * for every entry (given, in the order set), then for every key a getter
 * asked for that was absent, with the default it used (not given).  An
 * absent key read without a default (cl_config_vector, whose caller keeps
 * its own values, or a string getter given NULL) is not visited. */
typedef void (*cl_config_visit_fn)(void *ctx, const char *sec,
                                   const char *key, const char *value,
                                   bool given);
void cl_config_resolved(const cl_config *cfg, cl_config_visit_fn visit,
                        void *ctx);

/* The input files the configuration named, as cl_config_path_of resolved
 * them: visit(ctx, sec, key, path, true) for each entry whose value was
 * read as a file name (a mesh), path the file's absolute, resolved name
 * (none when it did not exist). */
void cl_config_input_files(const cl_config *cfg, cl_config_visit_fn visit,
                           void *ctx);

/* Write every entry as INI (final values, grouped by section in order of
 * first appearance) so that a run records the exact configuration it used.
 * Atomic: written to "path.tmp.XXXXXX" and renamed onto path. */
cl_status cl_config_write(const cl_config *cfg, const char *path,
                          cl_error *err);

CL_END_DECLS

#endif
