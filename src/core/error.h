/* Status codes and error messages shared by every layer.
 *
 * Library functions return a cl_status and, on failure, fill a cl_error with
 * one human-readable sentence (file, line, key, value, what is allowed where
 * they apply).  Only the command line prints the message and exits. */
#ifndef CL_ERROR_H
#define CL_ERROR_H

#include "core/decls.h"

CL_BEGIN_DECLS

typedef enum {
    CL_OK = 0,
    CL_EINVAL,      /* bad argument or parameter value */
    CL_ENOMEM,      /* allocation failed */
    CL_EIO,         /* file could not be read or written */
    CL_EPARSE,      /* malformed input file */
    CL_ESOLVER,     /* a solver reported failure */
    CL_EBLOWUP,     /* state became non-finite or ran away */
    CL_EUNSUPPORTED, /* valid request this build or problem cannot serve */
    CL_EINFEASIBLE, /* a state outside the feasible set (a particle at
                     * d <= 0 of a barrier obstacle): a smaller step may
                     * avoid it */
    CL_EBUDGET,     /* a run reached its --max-wall or --max-steps budget */
    CL_EINTR        /* a run stopped on SIGINT or SIGTERM (core/stop.h) */
} cl_status;

typedef struct {
    cl_status code;
    char msg[1024];
} cl_error;

/* Record an error (printf-style) and return its code, so callers can write
 * `return cl_error_set(err, CL_EINVAL, "...", ...);`.  err may be NULL. */
cl_status cl_error_set(cl_error *err, cl_status code, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

void cl_error_clear(cl_error *err);

const char *cl_status_name(cl_status code);

CL_END_DECLS

#endif
