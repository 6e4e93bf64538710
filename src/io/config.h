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

#include "core/error.h"

typedef struct cl_config cl_config;

cl_config *cl_config_alloc(void);
void cl_config_free(cl_config *cfg);

/* Parse an INI file; later entries override earlier ones.  Malformed lines
 * give CL_EPARSE with file and line; a missing file gives CL_EIO. */
cl_status cl_config_load(cl_config *cfg, const char *path, cl_error *err);

/* Apply "section.key=value" (as given to --set).  Keys not present in the
 * file are accepted here and checked by cl_config_check_unused(). */
cl_status cl_config_set(cl_config *cfg, const char *assignment, cl_error *err);

/* The file name given to cl_config_load (for messages and outputs). */
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
/* Raw string, or def if absent (pointer valid while cfg lives). */
const char *cl_config_string(cl_config *cfg, const char *sec, const char *key,
                             const char *def);
/* Where an entry came from, "file:line" or "--set", for messages built by
 * callers that validate values themselves (e.g. cross-key checks). */
const char *cl_config_origin(const cl_config *cfg, const char *sec,
                             const char *key, char *buf, size_t len);

/* CL_EINVAL naming the first entry no getter asked for, with the list of
 * keys known in its section if that section is known at all. */
cl_status cl_config_check_unused(const cl_config *cfg, cl_error *err);

/* Write every entry as INI (sorted by section, in file order) so that a run
 * records the exact configuration it used. */
cl_status cl_config_write(const cl_config *cfg, const char *path,
                          cl_error *err);

#endif
