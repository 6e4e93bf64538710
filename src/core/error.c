#include "core/error.h"

#include <stdarg.h>
#include <stdio.h>

cl_status cl_error_set(cl_error *err, cl_status code, const char *fmt, ...)
{
    if (err) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(err->msg, sizeof err->msg, fmt, ap);
        va_end(ap);
        err->code = code;
    }
    return code;
}

void cl_error_clear(cl_error *err)
{
    if (err) {
        err->code = CL_OK;
        err->msg[0] = '\0';
    }
}

const char *cl_status_name(cl_status code)
{
    switch (code) {
    case CL_OK: return "ok";
    case CL_EINVAL: return "invalid argument";
    case CL_ENOMEM: return "out of memory";
    case CL_EIO: return "i/o error";
    case CL_EPARSE: return "parse error";
    case CL_ESOLVER: return "solver failure";
    case CL_EBLOWUP: return "blow-up";
    case CL_EUNSUPPORTED: return "unsupported";
    case CL_EINFEASIBLE: return "infeasible state";
    case CL_EBUDGET: return "budget reached";
    case CL_EINTR: return "interrupted";
    }
    return "unknown status";
}
